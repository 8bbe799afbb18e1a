// The outputs of `repose diagnose`: DIR/diagnosis.json (verdict, cause, candidates with scores and
// fitted parameters, held-out errors, gain), DIR/report.md (the findings in plain words with the
// statistics) and the figures it shows (residuals vs each condition variable, measured vs
// simulated, the trajectories when the data has them).
#pragma once
#include <string>
#include <vector>

#include "diagnosis/diagnose.h"

namespace repose {

// Writes every file atomically into `dir` (created if needed).
void write_diagnosis(const Observations& obs, const Diagnosis& d, const std::string& dir);

// The findings in plain words, in report order, written from the stages' results
// (diagnosis_statements.cpp): the baseline, its lack of fit and residual trends, each candidate
// tried, the rivals' mimic tests, the verdict and the held-out gain.
std::vector<std::string> diagnosis_statements(const Observations& obs, const Diagnosis& d);

// What would separate two close candidates, as a measurement to make ("" when nothing to say).
std::string separation_in_words(const Separation& s, const Observations& obs);

}  // namespace repose
