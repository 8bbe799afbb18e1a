// The outputs of `repose diagnose`: DIR/diagnosis.json (verdict, cause, candidates with scores and
// fitted parameters, held-out errors, gain), DIR/report.md (the findings in plain words with the
// statistics) and the figures it shows (residuals vs each condition variable, measured vs
// simulated, the trajectories when the data has them).
#pragma once
#include <string>

#include "diagnosis/diagnose.h"

namespace repose {

// Writes every file atomically into `dir` (created if needed).
void write_diagnosis(const Observations& obs, const Diagnosis& d, const std::string& dir);

}  // namespace repose
