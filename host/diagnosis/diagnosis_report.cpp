#include "diagnosis/diagnosis_report.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "diagnosis/plot_png.h"
#include "io/provenance.h"
#include "util/units.h"
#include "util/atomic_file.h"
#include "util/number_text.h"

namespace repose {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const PlotColour kBaseline{200, 40, 40}, kExtended{30, 90, 200}, kMeasured{0, 0, 0}, kOther{40, 150, 60};

std::string standing_id(Standing s) {
  switch (s) {
    case Standing::Beats: return "beats";
    case Standing::ModestSupport: return "modest_support";
    case Standing::StrainedBaseline: return "strained_baseline";
    case Standing::HeldOutAgainst: return "heldout_against";
    case Standing::NoBetter: break;
  }
  return "no_better";
}

// The one meaning of "beats the baseline", stated once (report and diagnosis.json).
const char* kBeatsMeaning =
    "a candidate beats the baseline when its F test gives p < 1 % and its held-out error over every measure (each "
    "condition predicted by a fit to the others, in standard errors of the measured means, root mean square over the "
    "measures) is lower than the baseline's";

json model_json(const ModelResult& r, bool heldout) {
  json j;
  j["id"] = r.id;
  j["tested"] = r.tested;
  if (!r.tested) {
    j["reason"] = r.untested_reason;
    return j;
  }
  json p = json::object();
  for (size_t k = 0; k < r.params.size(); ++k) p[r.parameters[k].name] = r.params[k];
  j["parameters"] = p;
  j["k"] = r.k;
  j["chi2"] = r.chi2;
  j["aic"] = r.aic;
  j["simulated_replicates"] = r.prediction.replicates;  // behind the scored prediction
  j["fit_chi2"] = r.fit_chi2;                            // on the replicates the fit searched
  if (r.id != "baseline" && r.prediction.replicates > 1) {
    j["shrinkage"] = r.shrinkage;  // of its change from the baseline (model_fit.h shrink_change)
    j["change_chi2"] = r.change_d2;
  }
  if (!r.predicted_sd.empty()) j["predicted_sd"] = r.predicted_sd;  // per group, sigma + replicate scatter
  if (r.id != "baseline") {
    j["f"] = r.f;
    j["p"] = r.p;
    j["beats_baseline"] = r.significant;
    j["standing"] = standing_id(r.standing);
    j["dropped_early"] = r.dropped_early;
  }
  j["points"] = r.points;
  j["at_bound"] = json::array();
  for (const BoundFit& b : r.at_bound)
    j["at_bound"].push_back({{"parameter", b.parameter}, {"value", b.value}, {"bound", b.upper ? "upper" : "lower"}});
  if (heldout) {
    j["heldout_error"] = r.heldout_sds;  // standard errors, root mean square over every measure
    if (r.id != "baseline") j["heldout_gain_percent"] = r.heldout_gain;
    j["heldout_by_measure"] = json::array();
    for (const MeasureError& e : r.heldout_by_measure)
      j["heldout_by_measure"].push_back(
          {{"measure", e.measure}, {"unit", unit_of(e.measure)}, {"error", e.rms}, {"standard_errors", e.sds}});
  }
  return j;
}

const ModelResult* winner(const Diagnosis& d) {
  if (d.cause.empty()) return nullptr;
  for (const auto& c : d.candidates)
    if (c.id == d.cause[0]) return &c;
  return nullptr;
}

// How a measure is shown in the figures: lengths in millimetres (a residual of 0.004 m reads
// 4 mm), other units as measured.
struct Shown {
  double scale = 1;
  std::string unit;  // "" for a dimensionless measure
};
Shown shown(const std::string& measure) {
  for (const auto& m : known_measures())
    if (measure == m.name) {
      std::string unit = m.unit;
      if (unit == "m") return {1e3, "mm"};
      return {1, unit == "1" ? "" : unit};
    }
  return {};
}

// "rebound_height (mm)": a measure with its unit as shown, for axis labels.
std::string with_unit(const std::string& measure) {
  Shown s = shown(measure);
  return measure + (s.unit.empty() ? "" : " (" + s.unit + ")");
}

std::string safe(std::string s) {
  for (char& c : s)
    if (!std::isalnum((unsigned char)c)) c = '_';
  return s;
}

using Figures = std::vector<std::pair<std::string, std::string>>;  // (file, caption) in report order

bool is_series(const Observations& obs, const std::string& m) {
  for (const auto& g : obs.groups)
    if (g.measure == m && g.series) return true;
  return false;
}

// Residuals of a scalar measure against one condition variable, baseline and winner.
void residual_figure(const Observations& obs, const Diagnosis& d, const ModelResult* w, const std::string& m,
                     const std::string& v, const fs::path& dir, Figures& figures) {
  std::string wname = w ? w->id : "";
  Plot p;
  p.title = m + ": measured - simulated";
  p.x_label = quantity_label(v);
  p.y_label = with_unit(m) + " residual";
  p.zero_line = true;
  PlotSeries b{"baseline", {}, {}, {}, kBaseline, false, true}, e{wname, {}, {}, {}, kExtended, false, true};
  const double k = shown(m).scale;
  // The extended model's points sit a little to the right, so both error bars show.
  double lo = 1e300, hi = -1e300;
  for (const auto& c : obs.conditions)
    if (c.variables.count(v)) { lo = std::min(lo, c.variables.at(v)); hi = std::max(hi, c.variables.at(v)); }
  double shift = 0.015 * (hi - lo);
  for (size_t g = 0; g < obs.groups.size(); ++g) {
    const auto& grp = obs.groups[g];
    if (grp.measure != m || !obs.conditions[grp.condition].variables.count(v)) continue;
    double x = obs.conditions[grp.condition].variables.at(v);
    double se = k * grp.sd / std::sqrt(double(grp.values.size()));
    b.x.push_back(x);
    b.y.push_back(k * (grp.mean - d.baseline.predicted[g]));
    b.error.push_back(se);
    if (w) {
      e.x.push_back(x + shift);
      e.y.push_back(k * (grp.mean - w->predicted[g]));
      e.error.push_back(se);
    }
  }
  p.series.push_back(b);
  if (w) p.series.push_back(e);
  std::string file = "residuals_" + safe(m) + "_vs_" + safe(v.substr(v.rfind('.') + 1)) + ".png";
  write_plot_png(p, (dir / file).string());
  figures.push_back({file, "Residuals of " + m + " against " + v +
                               " (bars: standard error of each mean from the replicate scatter)"});
}

// A scalar measure, measured against simulated, baseline and winner.
void measured_vs_simulated_figure(const Observations& obs, const Diagnosis& d, const ModelResult* w,
                                  const std::string& m, const fs::path& dir, Figures& figures) {
  std::string wname = w ? w->id : "";
  Plot p;
  p.title = m + ": measured vs simulated";
  p.x_label = "simulated " + with_unit(m);
  p.y_label = "measured " + with_unit(m);
  p.diagonal = true;
  p.diagonal_label = "measured = simulated";
  PlotSeries b{"baseline", {}, {}, {}, kBaseline, false, true}, e{wname, {}, {}, {}, kExtended, false, true};
  const double k = shown(m).scale;
  for (size_t g = 0; g < obs.groups.size(); ++g) {
    const auto& grp = obs.groups[g];
    if (grp.measure != m) continue;
    double se = k * grp.sd / std::sqrt(double(grp.values.size()));
    b.x.push_back(k * d.baseline.predicted[g]);
    b.y.push_back(k * grp.mean);
    b.error.push_back(se);
    if (w) {
      e.x.push_back(k * w->predicted[g]);
      e.y.push_back(k * grp.mean);
      e.error.push_back(se);
    }
  }
  p.series.push_back(b);
  if (w) p.series.push_back(e);
  std::string file = "measured_vs_simulated_" + safe(m) + ".png";
  write_plot_png(p, (dir / file).string());
  figures.push_back({file, "Measured against simulated " + m + " (the line is measured = simulated)"});
}

// A series: the residuals against time, every condition, and the series of the last condition.
void series_figures(const Observations& obs, const Diagnosis& d, const ModelResult* w, const std::string& m,
                    const fs::path& dir, Figures& figures) {
  std::string wname = w ? w->id : "";
  Plot r;
  r.title = m + "(t): measured - simulated";
  r.x_label = "t (s)";
  r.y_label = with_unit(m) + " residual";
  r.zero_line = true;
  PlotSeries b{"baseline", {}, {}, {}, kBaseline, false, true}, e{wname, {}, {}, {}, kExtended, false, true};
  Plot z;
  size_t last = obs.conditions.size() - 1;
  z.title = m + "(t), " + obs.conditions[last].label;
  z.x_label = "t (s)";
  z.y_label = with_unit(m);
  PlotSeries zm{"measured", {}, {}, {}, kMeasured, false, true}, zb{"baseline", {}, {}, {}, kBaseline, true, false},
      ze{wname, {}, {}, {}, kExtended, true, false};
  const double k = shown(m).scale;
  for (size_t g = 0; g < obs.groups.size(); ++g) {
    const auto& grp = obs.groups[g];
    if (grp.measure != m || !grp.series) continue;
    b.x.push_back(grp.t);
    b.y.push_back(k * (grp.mean - d.baseline.predicted[g]));
    if (w) {
      e.x.push_back(grp.t);
      e.y.push_back(k * (grp.mean - w->predicted[g]));
    }
    if (grp.condition == last) {
      zm.x.push_back(grp.t);
      zm.y.push_back(k * grp.mean);
      zb.x.push_back(grp.t);
      zb.y.push_back(k * d.baseline.predicted[g]);
      if (w) {
        ze.x.push_back(grp.t);
        ze.y.push_back(k * w->predicted[g]);
      }
    }
  }
  if (b.x.empty()) return;
  r.series.push_back(b);
  if (w) r.series.push_back(e);
  std::string file = "residuals_" + safe(m) + "_vs_t.png";
  write_plot_png(r, (dir / file).string());
  figures.push_back({file, "Residuals of the " + m + " series against time, every condition"});
  z.series = {zm, zb};
  if (w) z.series.push_back(ze);
  file = "series_" + safe(m) + ".png";
  write_plot_png(z, (dir / file).string());
  figures.push_back({file, "The " + m + " series of " + obs.conditions[last].label + ": measured means and simulations"});
}

// The figures, in report order: per scalar measure its residuals against each condition variable
// and measured against simulated; then per series its residuals and the last condition's series.
Figures write_figures(const Observations& obs, const Diagnosis& d, const fs::path& dir) {
  Figures figures;
  const ModelResult* w = winner(d);
  for (const std::string& m : obs.measures) {
    if (is_series(obs, m)) continue;
    for (const std::string& v : obs.variables) residual_figure(obs, d, w, m, v, dir, figures);
    measured_vs_simulated_figure(obs, d, w, m, dir, figures);
  }
  for (const std::string& m : obs.measures) series_figures(obs, d, w, m, dir, figures);
  return figures;
}

// The verdict's confidence, the Akaike weights, the pairs and the untested rivals.
void confidence_json(const Diagnosis& d, json& j) {
  j["confidence"] = d.confidence;
  j["weights"] = json::object();
  for (const auto& [id, w] : d.weights) j["weights"][id] = w;
  j["untested_rivals"] = d.untested_rivals;
  j["pairs"] = json::array();
  for (const auto& p : d.pairs) {
    json e = {{"a", p.a}, {"b", p.b}, {"told_apart", p.told_apart}};
    e["a_as_b_chi2"] = p.a_as_b >= 0 ? json(p.a_as_b) : json(nullptr);
    e["b_as_a_chi2"] = p.b_as_a >= 0 ? json(p.b_as_a) : json(nullptr);
    j["pairs"].push_back(e);
  }
}

// Every fitted model's held-out error per measure, in its unit (RMS over the conditions).
void heldout_markdown(const Diagnosis& d, std::ostringstream& md) {
  md << "\nHeld-out error per measure (RMS over the conditions, each predicted by a fit to the others"
     << (d.scatter_scored ? "; mean and replicate SD together" : "") << "):\n\n| model |";
  // Lengths in mm, as the findings give them.
  auto in_mm = [](const std::string& measure) { return unit_of(measure) == "m"; };
  for (const MeasureError& e : d.baseline.heldout_by_measure)
    md << " " << (in_mm(e.measure) ? e.measure + " (mm)" : with_unit(e.measure)) << " |";
  md << "\n|---|";
  for (size_t m = 0; m < d.baseline.heldout_by_measure.size(); ++m) md << "---|";
  md << "\n";
  auto row = [&](const ModelResult& r) {
    if (!r.tested || r.heldout_by_measure.empty()) return;
    md << "| " << r.id << " |";
    for (const MeasureError& e : r.heldout_by_measure)
      md << " " << format_g(in_mm(e.measure) ? 1000 * e.rms : e.rms, 4) << " |";
    md << "\n";
  };
  row(d.baseline);
  for (const auto& c : d.candidates) row(c);
}

// Which pairs of candidates the data tell apart, as a markdown table.
void pairs_markdown(const Diagnosis& d, std::ostringstream& md) {
  if (d.pairs.empty()) return;
  auto chi2 = [](double v) { return v < 0 ? std::string("not tried") : std::to_string(v).substr(0, 6); };
  md << "\n## Which candidates these data tell apart\n\nEach refitted to the other's predictions; apart when "
        "every tried direction misses by chi^2 >= "
     << kSeparableChi2 << " (3 sigma), or the data reject the refitted one (its AIC more than 10 above the other's).\n\n| a | b | a refitted to b: chi^2 | b refitted to a: chi^2 | told apart |\n"
        "|---|---|---|---|---|\n";
  for (const auto& p : d.pairs)
    md << "| " << p.a << " | " << p.b << " | " << chi2(p.a_as_b) << " | " << chi2(p.b_as_a) << " | "
       << (p.told_apart ? "yes" : "no") << " |\n";
}

// diagnosis.json: the verdict, every model's fit, the tests, the noise and the figures' files.
json diagnosis_json(const Observations& obs, const Diagnosis& d, const Figures& figures) {
  json j;
  j["data"] = obs.path;
  j["verdict"] = d.verdict;
  if (d.verdict == "effect") j["cause"] = d.cause[0];
  else if (d.verdict == "ambiguous") j["cause"] = d.cause;
  else j["cause"] = nullptr;
  j["tried"] = d.tried;
  j["untested"] = json::array();
  for (const auto& c : d.candidates)
    if (!c.tested || !c.simulation_error.empty())
      j["untested"].push_back({{"id", c.id}, {"reason", c.simulation_error.empty() ? c.untested_reason : c.simulation_error}});
  j["baseline"] = model_json(d.baseline, d.heldout_available);
  j["candidates"] = json::array();
  for (const auto& c : d.candidates) j["candidates"].push_back(model_json(c, d.heldout_available));
  j["beats_baseline_means"] = kBeatsMeaning;
  j["heldout_unit"] = "standard errors of the measured means, root mean square over every measure";
  if (d.heldout_available) {
    j["heldout_error_baseline"] = d.heldout_error_baseline;
    j["heldout_error_extended"] = d.heldout_error_extended;
    j["gain_percent"] = d.gain_percent;
    // Per measure, of what the verdict names (the baseline again when it names none).
    const ModelResult* named = winner(d);
    if (!named) named = &d.baseline;
    j["gain_by_measure"] = json::array();
    for (size_t m = 0; m < named->heldout_by_measure.size() && m < d.baseline.heldout_by_measure.size(); ++m) {
      const MeasureError &e = named->heldout_by_measure[m], &b = d.baseline.heldout_by_measure[m];
      j["gain_by_measure"].push_back({{"measure", e.measure}, {"unit", unit_of(e.measure)}, {"baseline", b.rms},
                                      {"extended", e.rms}, {"gain_percent", b.sds > 0 ? 100 * (1 - e.sds / b.sds) : 0.0}});
    }
  } else {
    j["heldout_error_baseline"] = nullptr;
    j["heldout_error_extended"] = nullptr;
    j["gain_percent"] = nullptr;
  }
  j["heldout_method"] = d.scatter_scored
                            ? "leave one condition out: refit on the others, predict it; error of the mean and "
                              "of the replicate SD together (2-Wasserstein distance of normals)"
                            : "leave one condition out: refit on the others, predict it";
  j["lack_of_fit"] = json::array();
  for (const auto& l : d.lack_of_fit)
    j["lack_of_fit"].push_back({{"measure", l.measure}, {"chi2", l.chi2}, {"groups", l.groups}, {"df", l.df},
                                {"noise_df", l.noise_df}, {"p", l.p}});
  j["trends"] = json::array();
  for (const auto& t : d.trends)
    j["trends"].push_back({{"measure", t.measure}, {"variable", t.variable}, {"slope", t.slope}, {"se", t.se},
                           {"z", t.z}, {"p", t.p}});
  confidence_json(d, j);
  if (d.separation_chi2 >= 0) j["separation_chi2"] = d.separation_chi2;
  if (!d.separating_measurement.empty()) j["separating_measurement"] = d.separating_measurement;
  j["noise"] = json::object();
  for (const auto& [m, n] : obs.noise)
    j["noise"][m] = {{"sd", n.sd}, {"df", n.df}, {"given", n.given}, {"lag1", n.lag1}, {"rho", n.rho}, {"inflation", n.inflation}};
  j["conditions"] = json::array();
  for (const auto& c : obs.conditions) j["conditions"].push_back(c.label);
  j["statements"] = d.statements;
  j["figures"] = json::array();
  for (const auto& f : figures) j["figures"].push_back(f.first);
  j["simulations"] = d.simulations;
  j["seconds"] = d.seconds;
  j["provenance"] = input_provenance({obs.path});
  return j;
}

// report.md: the verdict, the findings in words, the candidates' table and the figures.
std::string report_markdown(const Observations& obs, const Diagnosis& d, const Figures& figures) {
  std::ostringstream md;
  md << "# Diagnosis of " << fs::path(obs.path).filename().string() << "\n\n";
  md << "**Verdict: " << d.verdict << "**";
  if (!d.cause.empty()) {
    md << " (";
    for (size_t k = 0; k < d.cause.size(); ++k) md << (k ? ", " : "") << "`" << d.cause[k] << "`";
    md << ")";
  }
  md << ", confidence " << std::to_string(d.confidence).substr(0, 4);
  md << "\n\n" << obs.conditions.size() << " conditions, " << obs.groups.size() << " measured means; noise from the "
     << "replicate scatter:";
  for (const auto& [m, n] : obs.noise)
    md << " " << m << " SD " << n.sd << (n.given ? " (given)" : " (pooled, df " + std::to_string(n.df) + ")")
       << (n.inflation > 1 ? ", lag-1 correlation along t " + std::to_string(n.lag1).substr(0, 5) +
                                 " (whitened, AR(1))"
                           : std::string())
       << ";";
  md << "\n\n## Findings\n\n";
  for (const auto& s : d.statements) md << "- " << s << "\n";
  md << "\n## Candidates\n\nOne meaning throughout: " << kBeatsMeaning
     << ". Held-out error in standard errors; per measure below.\n\n| model | fitted parameters | chi^2 | AIC | "
        "Akaike weight | F test p | held-out error | held-out gain | beats baseline |\n"
        "|---|---|---|---|---|---|---|---|---|\n";
  auto row = [&](const ModelResult& r) {
    if (!r.tested) {
      md << "| " << r.id << " | not tested: " << r.untested_reason << " | | | | | | | |\n";
      return;
    }
    std::string ps;
    for (size_t k = 0; k < r.params.size(); ++k) {
      char buf[96];
      std::snprintf(buf, sizeof buf, "%s%s = %.4g", k ? ", " : "", r.parameters[k].name.c_str(), r.params[k]);
      ps += buf;
    }
    char p[32] = "", held[32] = "", gain[32] = "", weight[32] = "", buf[256];
    bool candidate = r.id != "baseline";
    if (candidate) std::snprintf(p, sizeof p, "%.2g", r.p);
    if (d.heldout_available) std::snprintf(held, sizeof held, "%.4g", r.heldout_sds);
    if (d.heldout_available && candidate) std::snprintf(gain, sizeof gain, "%+.3g %%", r.heldout_gain);
    for (const auto& [id, w] : d.weights)
      if (id == r.id) std::snprintf(weight, sizeof weight, "%.3g", w);
    std::snprintf(buf, sizeof buf, "| %.4g | %.4g | %s | %s | %s | %s | %s |\n", r.chi2, r.aic, weight, p, held, gain,
                  !candidate ? "" : r.significant ? "yes" : "no");
    md << "| " << r.id << " | " << ps << " " << buf;
  };
  row(d.baseline);
  for (const auto& c : d.candidates) row(c);
  if (d.heldout_available) heldout_markdown(d, md);
  pairs_markdown(d, md);
  md << "\n## Figures\n\n";
  for (const auto& [file, caption] : figures) md << caption << ":\n\n![" << caption << "](" << file << ")\n\n";
  md << "---\n" << d.simulations << " simulations in " << d.seconds << " s.\n";
  return md.str();
}

}  // namespace

void write_diagnosis(const Observations& obs, const Diagnosis& d, const std::string& dir_name) {
  fs::path dir(dir_name);
  fs::create_directories(dir);
  Figures figures = write_figures(obs, d, dir);
  write_file_atomically((dir / "diagnosis.json").string(), diagnosis_json(obs, d, figures).dump(2) + "\n");
  write_file_atomically((dir / "report.md").string(), report_markdown(obs, d, figures));
}

}  // namespace repose
