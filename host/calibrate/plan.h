// A calibration campaign's plan (TOML, docs/calibration.md): the virtual experiment and its base
// case, the factors (case keys with ranges), the design or the adaptive loop, the response and
// its measured value, the verification. Loading checks everything that can be checked before a
// simulation runs, each problem as "PLAN:LINE: KEY: what is wrong" (a CaseError).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "case/case_error.h"
#include "case/case_loader.h"
#include "engine/backend.h"
#include "util/number_text.h"

namespace repose::calibrate {

struct PlanFactor {
  std::string name;  // short name for tables and figures ("e", "mu_s")
  std::string key;   // case key, as `--set` takes it
  double low = 0, high = 0;
  SourceRef where;
};

struct PlanSetting {  // a [set] entry: applied to every run, before the factors
  std::string key, value;
  SourceRef where;
};

enum class CampaignMode { design, adaptive };

struct DesignPlan {
  std::string type = "ccd";  // ccd, bbd, factorial, fractional, sweep, table
  std::string alpha = "rotatable";
  int centre = 3;            // centre points (each its own packing seed)
  int replicates = 1;        // runs of every other design point
  std::string model = "quadratic";
  double reduce = 0;         // backward elimination p threshold; 0: keep the full model
  std::vector<std::string> generators;  // fractional factorial, e.g. "C=AB"
  int levels = 5;            // sweep: evenly spaced levels of the single factor
  int degree = 3;            // sweep: calibration curve degree
  std::uint64_t order_seed = 0;  // randomised run order (0: standard order)
  std::string table;             // type "table": CSV of actual factor values, one run per row
  std::vector<std::vector<double>> table_rows;
};

struct AdaptivePlan {
  int initial = 0;     // space-filling start (0: 2k + 1)
  int budget = 20;     // most simulations of the loop, the start included
  // false ("same"): every loop run packs with base_seed, so runs differ only by the factors
  // (right for a smooth response). true ("per_run"): loop run i packs with base_seed +
  // verification runs + i, so a response that is chaotic in the packing becomes independent
  // noise the surrogate averages, and the loop may repeat a point.
  bool seed_per_run = false;
};

struct CampaignPlan {
  std::string path;        // the plan file
  std::string name;
  std::string experiment;  // registered experiment type
  std::string case_path;   // base case, resolved against the plan's folder
  std::string case_text;   // its content (sent to MPI ranks)
  std::string case_identity;  // CaseSpec::identity of the base case with [set] (hashed into the plan)
  CampaignMode mode = CampaignMode::design;
  std::string backend = kLibraryBackend;
  std::string seed_key = "simulation.seed";
  std::uint64_t base_seed = 1;  // replicate r runs with base_seed + r
  std::string response;
  double measured = 0;
  double measured_sd = 0;   // lab standard deviation of the measured value (0: not given)
  double tolerance = 0.01;  // relative: met when |simulated - measured| <= tolerance |measured|
  std::vector<PlanSetting> settings;
  std::vector<PlanFactor> factors;
  DesignPlan design;
  int verification_runs = 3;  // runs at the calibrated point, each its own packing seed
  AdaptivePlan adaptive;

  double absolute_tolerance() const;
  std::vector<std::string> factor_names() const;
};

// Reads and checks a plan. Throws CaseError located in the plan (or, for a base case problem,
// naming the plan key that leads to it).
CampaignPlan load_plan(const std::string& path);

// What identifies the runs: every parsed setting as sorted "key = value" lines, then the base case
// as parsed (CaseSpec::identity, files it reads by content), each line after kCaseLinePrefix.
// Comments, layout and key order do not change it.
constexpr const char* kCaseLinePrefix = "case| ";
std::string canonical_plan_text(const CampaignPlan& plan);
std::string plan_hash(const std::string& canonical_text);  // FNV-1a 64, hex
// "factor.e.high: 0.55 -> 0.6; design.centre: 3 -> 5" between two canonical texts.
std::string describe_plan_change(const std::string& stored, const std::string& current);

// The overrides of one run: the plan's [set], the factors at `x` (actual values), the seed.
std::vector<CaseOverride> run_overrides(const CampaignPlan& plan, const std::vector<double>& x,
                                        std::uint64_t seed);

}  // namespace repose::calibrate
