#include "diagnosis/observations.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace repose {

int Observations::noise_df() const {
  int df = 1 << 30;
  for (const auto& [m, n] : noise) df = std::min(df, n.df);
  return df;
}

namespace {

constexpr double kMaxLag1 = 0.95;  // beyond this a track is one measurement, not many: cap it

std::string condition_key(const Measurement& m) {
  std::string key = m.case_path;
  for (const auto& s : m.sets) key += "|" + s.key + "=" + s.value;
  return key;
}

// Lag-1 correlation of the deviations from the replicate mean along each replicate's track of a
// series measure (pooled over tracks), and the AR(1) variance inflation it implies.
void serial_correlation(const MeasuredData& data, const Observations& obs, const std::string& measure,
                        const std::map<std::string, size_t>& condition_of, NoiseEstimate& n) {
  std::map<std::pair<size_t, double>, double> mean_at;  // (condition, t) -> replicate mean
  for (const auto& g : obs.groups)
    if (g.measure == measure && g.series) mean_at[{g.condition, g.t}] = g.mean;
  if (mean_at.empty()) return;
  std::map<std::pair<size_t, int>, std::vector<std::pair<double, double>>> tracks;  // (condition, replicate)
  for (const Measurement& m : data.rows) {
    if (m.measure != measure || !m.t) continue;
    size_t c = condition_of.at(condition_key(m));
    tracks[{c, m.replicate}].push_back({*m.t, m.value - mean_at.at({c, *m.t})});
  }
  double lagged = 0, squared = 0;
  for (auto& [key, track] : tracks) {
    std::sort(track.begin(), track.end());
    for (size_t k = 0; k < track.size(); ++k) {
      squared += track[k].second * track[k].second;
      if (k > 0) lagged += track[k].second * track[k - 1].second;
    }
  }
  if (!(squared > 0)) return;
  n.lag1 = lagged / squared;
  n.rho = std::clamp(n.lag1, 0.0, kMaxLag1);
  n.inflation = (1 + n.rho) / (1 - n.rho);
  n.df = std::max(1, int(n.df / n.inflation));
}

// A new condition for a row: its case, overrides, label and numeric variables.
Condition make_condition(const Measurement& m) {
  Condition c;
  c.case_path = m.case_path;
  c.sets = m.sets;
  for (const auto& s : m.sets) {
    std::string shortkey = s.key.substr(s.key.rfind('.') + 1);
    c.label += (c.label.empty() ? "" : ", ") + shortkey + "=" + s.value;
    try {
      size_t used = 0;
      double v = std::stod(s.value, &used);
      if (used == s.value.size()) c.variables[s.key] = v;
    } catch (const std::exception&) {
    }
  }
  if (c.label.empty()) c.label = std::filesystem::path(m.case_path).stem().string();
  return c;
}

// The replicates' means and variances of a measure's groups, and its noise: the pooled replicate
// scatter (pure error), or the given sigma (root mean square). Throws DataError when it has neither.
NoiseEstimate measure_noise(Observations& obs, const std::string& measure, const std::vector<double>* given,
                            const std::string& path) {
  NoiseEstimate n;
  double ss = 0;
  for (auto& g : obs.groups) {
    if (g.measure != measure) continue;
    double mean = 0;
    for (double v : g.values) mean += v;
    g.mean = mean / g.values.size();
    double gs = 0;
    for (double v : g.values) gs += (v - g.mean) * (v - g.mean);
    g.s2 = g.values.size() > 1 ? gs / double(g.values.size() - 1) : 0.0;
    ss += gs;
    n.df += int(g.values.size()) - 1;
  }
  if (given) {
    double s2 = 0;
    for (double s : *given) s2 += s * s;
    n.sd = std::sqrt(s2 / given->size());
    n.df = 1000000;
    n.given = true;
  } else if (n.df > 0 && ss > 0) {
    n.sd = std::sqrt(ss / n.df);
  } else {
    throw DataError(path + ": measure '" + measure +
                    "' has no replicate scatter (give several replicates per condition or a sigma column)");
  }
  return n;
}

// Each series point's predecessor in time (the AR(1) whitening of the score).
void link_series(Observations& obs) {
  std::map<std::pair<size_t, std::string>, std::vector<std::pair<double, size_t>>> series;
  for (size_t g = 0; g < obs.groups.size(); ++g)
    if (obs.groups[g].series) series[{obs.groups[g].condition, obs.groups[g].measure}].push_back({obs.groups[g].t, g});
  for (auto& [key, points] : series) {
    std::sort(points.begin(), points.end());
    for (size_t k = 1; k < points.size(); ++k) obs.groups[points[k].second].previous = long(points[k - 1].second);
  }
}

// Condition variables that take more than one value.
std::vector<std::string> varying_variables(const Observations& obs) {
  std::vector<std::string> out;
  std::map<std::string, std::vector<double>> seen;
  for (const auto& c : obs.conditions)
    for (const auto& [k, v] : c.variables) seen[k].push_back(v);
  for (auto& [k, vs] : seen) {
    std::sort(vs.begin(), vs.end());
    if (vs.size() >= 2 && vs.front() != vs.back()) out.push_back(k);
  }
  return out;
}

}  // namespace

Observations group_observations(const MeasuredData& data) {
  Observations obs;
  obs.path = data.path;
  std::map<std::string, size_t> condition_of;
  std::map<std::string, size_t> group_of;
  std::map<std::string, std::vector<double>> given_sigma;
  for (const Measurement& m : data.rows) {
    std::string ckey = condition_key(m);
    if (!condition_of.count(ckey)) {
      condition_of[ckey] = obs.conditions.size();
      obs.conditions.push_back(make_condition(m));
    }
    size_t ci = condition_of[ckey];
    bool series = m.t.has_value();
    char tbuf[64];
    std::snprintf(tbuf, sizeof tbuf, "%.9g", series ? *m.t : 0.0);
    std::string gkey = std::to_string(ci) + "|" + m.measure + "|" + tbuf;
    if (!group_of.count(gkey)) {
      ObservationGroup g;
      g.condition = ci;
      g.measure = m.measure;
      g.series = series;
      g.t = series ? *m.t : 0.0;
      g.line = m.line;
      group_of[gkey] = obs.groups.size();
      obs.groups.push_back(g);
    }
    obs.groups[group_of[gkey]].values.push_back(m.value);
    if (m.sigma) given_sigma[m.measure].push_back(*m.sigma);
    if (std::find(obs.measures.begin(), obs.measures.end(), m.measure) == obs.measures.end())
      obs.measures.push_back(m.measure);
  }
  for (const std::string& measure : obs.measures) {
    auto given = given_sigma.find(measure);
    NoiseEstimate n = measure_noise(obs, measure, given == given_sigma.end() ? nullptr : &given->second, data.path);
    serial_correlation(data, obs, measure, condition_of, n);
    obs.noise[measure] = n;
    for (auto& g : obs.groups)
      if (g.measure == measure) {
        g.sd = n.sd;
        g.sigma_given = n.given;
      }
  }
  link_series(obs);
  obs.variables = varying_variables(obs);
  return obs;
}

}  // namespace repose
