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

Observations group_observations(const MeasuredData& data) {
  Observations obs;
  obs.path = data.path;
  std::map<std::string, size_t> condition_of;
  std::map<std::string, size_t> group_of;
  std::map<std::string, std::vector<double>> given_sigma;
  for (const Measurement& m : data.rows) {
    std::string ckey = m.case_path;
    for (const auto& s : m.sets) ckey += "|" + s.key + "=" + s.value;
    if (!condition_of.count(ckey)) {
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
      condition_of[ckey] = obs.conditions.size();
      obs.conditions.push_back(c);
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

  // Pooled replicate scatter per measure (pure error), or the given sigma (root mean square).
  for (const std::string& measure : obs.measures) {
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
    if (given_sigma.count(measure)) {
      double s2 = 0;
      for (double s : given_sigma[measure]) s2 += s * s;
      n.sd = std::sqrt(s2 / given_sigma[measure].size());
      n.df = 1000000;
      n.given = true;
    } else if (n.df > 0 && ss > 0) {
      n.sd = std::sqrt(ss / n.df);
    } else {
      throw DataError(data.path + ": measure '" + measure +
                      "' has no replicate scatter (give several replicates per condition or a sigma column)");
    }
    obs.noise[measure] = n;
    for (auto& g : obs.groups)
      if (g.measure == measure) {
        g.sd = n.sd;
        g.sigma_given = n.given;
      }
  }

  // Condition variables that take more than one value.
  std::map<std::string, std::vector<double>> seen;
  for (const auto& c : obs.conditions)
    for (const auto& [k, v] : c.variables) seen[k].push_back(v);
  for (auto& [k, vs] : seen) {
    std::sort(vs.begin(), vs.end());
    if (vs.size() >= 2 && vs.front() != vs.back()) obs.variables.push_back(k);
  }
  return obs;
}

}  // namespace repose
