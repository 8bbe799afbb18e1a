// Helpers of the hidden-effect tests (issue 5): seeded draws, the synthetic data written next to
// a copy of the case, and the diagnosis of that CSV alone.
#pragma once
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <string>

#include "diagnosis/diagnose.h"
#include "diagnosis/synthetic_data.h"

namespace repose::hidden {

// A uniform draw in [lo, hi] (log-uniform when log_scale) from a seeded generator.
inline double draw(uint64_t seed, double lo, double hi, bool log_scale = false) {
  std::mt19937_64 rng(seed);
  double u = (rng() >> 11) * 0x1.0p-53;
  return log_scale ? lo * std::pow(hi / lo, u) : lo + u * (hi - lo);
}

// Writes the truth's data in a temporary folder and diagnoses them; `data_out` gets the CSV path.
// `options` (progress and threads are set here): e.g. the calibrated values given (--params).
// `keep` (optional) picks the CSV's data rows that are kept (a lab that measured less).
inline Diagnosis diagnose_hidden(const std::string& name, SyntheticTruth truth, std::string* data_out = nullptr,
                                 DiagnoseOptions options = {},
                                 const std::function<bool(const std::string& row)>& keep = {}) {
  namespace fs = std::filesystem;
  fs::path dir = fs::temp_directory_path() / ("repose_hidden_" + name);
  fs::create_directories(dir);
  fs::path case_file = dir / fs::path(truth.case_path).filename();
  fs::copy_file(truth.case_path, case_file, fs::copy_options::overwrite_existing);
  truth.case_path = case_file.string();
  std::string csv = (dir / "data.csv").string();
  write_synthetic_data(truth, csv);
  if (keep) {
    std::ifstream in(csv);
    std::string header, row, kept;
    std::getline(in, header);
    while (std::getline(in, row))
      if (keep(row)) kept += row + "\n";
    in.close();
    std::ofstream(csv) << header << "\n" << kept;
  }
  if (data_out) *data_out = csv;
  options.progress = false;
  options.threads = 2;
  return diagnose(group_observations(read_measured_data(csv)), options);
}

inline std::string case_path(const std::string& name) {
  return std::string(REPOSE_SOURCE_DIR) + "/cases/diagnosis/" + name + ".toml";
}

inline const ModelResult& candidate(const Diagnosis& d, const std::string& id) {
  for (const auto& c : d.candidates)
    if (c.id == id) return c;
  FAIL("no candidate " << id);
  return d.baseline;
}

inline std::string summary(const Diagnosis& d) {
  std::string s = "verdict " + d.verdict + "\n";
  for (const auto& line : d.statements) s += "  " + line + "\n";
  return s;
}

}  // namespace repose::hidden
