// A calibration campaign's plan (TOML, docs/calibration.md): the virtual experiment and its base
// case (and other rigs), the factors (case keys with ranges), the design or the adaptive loop,
// the responses with their measured values and uncertainties, the verification. Loading checks everything that can be checked before a
// simulation runs, each problem as "PLAN:LINE: KEY: what is wrong" (a CaseError).
#pragma once
#include <Eigen/Dense>
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

  double to_coded(double actual) const { return (actual - 0.5 * (low + high)) / (0.5 * (high - low)); }
  double to_actual(double coded) const { return 0.5 * (low + high) + coded * 0.5 * (high - low); }
};

struct PlanSetting {  // a [set] entry: applied to every run, before the factors
  std::string key, value;
  SourceRef where;
};

// A case the campaign runs: its own ([campaign] case, rig 0) or another rig ([[rig]]), e.g. the
// box a heap is calibrated on and the cylinder it is verified on. Runs on rig r > 0 have ids
// ending in "@NAME".
struct PlanRig {
  std::string name;        // "" for the campaign's own case
  std::string experiment;  // registered experiment type
  std::string case_path;   // resolved against the plan's folder
  std::string case_text;   // its content (sent to MPI ranks)
  // CaseSpec::identity with [set] applied and every factor at its low end (hashed into the plan):
  // a factor's value in the base case is no run's, so editing it keeps the campaign.
  std::string case_identity;
  std::string case_identity_as_given;  // without the factors pinned: databases from before
  std::string seed_key = "simulation.seed";
  std::vector<PlanSetting> settings;
  SourceRef where;
};

// What a response is for: fitted and verified, or only checked at the calibrated point.
enum class ResponseRole { calibrate, verify };

// A measured value to match: a response of one rig's experiment, the lab's value and how well
// the lab knows it.
struct PlanResponse {
  std::string name;          // one of the experiment's responses
  int rig = 0;               // index into CampaignPlan::rigs
  double measured = 0;
  double measured_sd = 0;    // lab standard deviation (0: not given, the value taken as exact)
  int measured_n = 1;        // lab replicates behind `measured`: its standard error is sd / sqrt(n)
  double tolerance = 0.01;   // relative: met when |simulated - measured| <= tolerance |measured|
  double noise_sd = 0;       // expected run-to-run sd (an earlier pilot), for --check only; 0: unknown
  ResponseRole role = ResponseRole::calibrate;
  std::string label;         // name, or name@RIG on another rig: unique in the plan
  SourceRef where;

  double absolute_tolerance() const;
  double measured_se() const;
};

enum class CampaignMode { design, adaptive };

struct DesignPlan {
  std::string type = "ccd";  // ccd, bbd, factorial, fractional, sweep, table, path
  std::string alpha = "rotatable";
  int centre = 3;            // centre points (each its own packing seed)
  int replicates = 1;        // runs of every other design point
  std::string model = "quadratic";
  double reduce = 0;         // backward elimination p threshold; 0: keep the full model
  std::vector<std::string> generators;  // fractional factorial, e.g. "C=AB"
  int levels = 5;            // sweep: evenly spaced levels of the single factor; path: its points
  int degree = 3;            // sweep: calibration curve degree
  std::uint64_t order_seed = 0;  // randomised run order (0: standard order)
  std::string table;             // type "table": CSV of actual factor values, one run per row
  std::vector<std::vector<double>> table_rows;
  // type "path" (steepest ascent): `levels` points evenly from `path_from` to `path_to` (actual
  // values, one per factor; default every factor's low and high).
  std::vector<double> path_from, path_to;
  // Factors held at an actual value when the model is optimised (the cabbage study's e = 0.42):
  // index into factors -> value. The design still varies them.
  std::vector<std::pair<int, double>> fixed;
};

struct AdaptivePlan {
  int initial = 0;     // space-filling start (0: 2k + 1)
  int budget = 20;     // most simulations of the loop, the start included (the pilot comes on top)
  // false ("same"): every loop run packs with base_seed, so runs differ only by the factors
  // (right for a smooth response). true ("per_run"): loop run i packs with base_seed +
  // verification runs + i, so a response that is chaotic in the packing becomes independent
  // noise the surrogate averages, and the loop may repeat a point.
  bool seed_per_run = false;
  // The noise pilot: `pilot` fills, each its own seed, at each of `pilot_points` points (1: the
  // centre; 2: coded -0.5 and +0.5 along the diagonal). Required with per_run seeds.
  int pilot = 0;
  int pilot_points = 1;
};

struct CampaignPlan {
  std::string path;        // the plan file
  std::string name;
  CampaignMode mode = CampaignMode::design;
  std::string backend = kLibraryBackend;
  std::uint64_t base_seed = 1;  // replicate r runs with base_seed + r
  std::vector<PlanRig> rigs;            // rigs[0]: the campaign's own case
  std::vector<PlanResponse> responses;  // in plan order; at least one calibrates
  std::vector<PlanFactor> factors;
  DesignPlan design;
  int verification_runs = 3;  // runs at the calibrated point on each verified rig, each its own seed
  AdaptivePlan adaptive;

  std::vector<std::string> factor_names() const;
  // The responses that calibrate, and those the verification checks: the verify-only ones when
  // there are any (calibrate on the box, verify on the cylinder), else the calibrating ones.
  std::vector<int> calibration_responses() const;
  std::vector<int> verified_responses() const;
  // Whether other runs' seeds follow the verification's (an adaptive loop with a seed per run
  // starts its seeds after them): then the verification count is part of the campaign's identity.
  bool seeds_follow_verification() const { return mode == CampaignMode::adaptive && adaptive.seed_per_run; }
  // The rigs these responses run on, each once, in rig order.
  std::vector<int> rigs_of(const std::vector<int>& responses) const;
  const PlanResponse& primary() const { return responses[size_t(calibration_responses().front())]; }
};

// Reads and checks a plan. Throws CaseError located in the plan (or, for a base case problem,
// naming the plan key that leads to it).
CampaignPlan load_plan(const std::string& path);

// What identifies the runs: every parsed setting as sorted "key = value" lines, then the base case
// as parsed (CaseSpec::identity, files it reads by content), each line after kCaseLinePrefix.
// Comments, layout and key order do not change it.
constexpr const char* kCaseLinePrefix = "case| ";
std::string canonical_plan_text(const CampaignPlan& plan);
// The same text as plans before the factors were pinned in the base case wrote it.
std::string canonical_plan_text_as_given(const CampaignPlan& plan);
std::string plan_hash(const std::string& canonical_text);  // FNV-1a 64, hex
// "factor.e.high: 0.55 -> 0.6; design.centre: 3 -> 5" between two canonical texts.
std::string describe_plan_change(const std::string& stored, const std::string& current);

// The overrides of one run on `rig`: its [set], the factors at `x` (actual values), the seed.
std::vector<CaseOverride> run_overrides(const CampaignPlan& plan, int rig, const std::vector<double>& x,
                                        std::uint64_t seed);

// A point in actual factor values from coded ones, and back.
std::vector<double> to_actual(const CampaignPlan& plan, const Eigen::VectorXd& coded);
Eigen::VectorXd to_coded(const CampaignPlan& plan, const std::vector<double>& actual);

}  // namespace repose::calibrate
