// Synthetic measured data with a known truth, to check that `repose diagnose` finds what was
// hidden: the case's experiment simulated with a truth model (the baseline plus, optionally, one
// extension of given strength) at several conditions, each replicate with Gaussian noise of a
// stated size, written in the measured-data CSV format (README "Measured data").
// The experiment the case names says how (experiments/experiment.h, DiagnosisRole):
// - A drop case varies the drop height. A truth whose body is a clump (extension `shape`) lands
//   at a random orientation: every replicate is its own drop, with seeds no diagnosis uses
//   (1,000,000 + 10,000 seed + 100 condition index + replicate).
// - A heap case (experiment repose, grains from sphere [[fill]]s) is refilled for every replicate
//   with such seeds; each replicate gives repose_angle and bed_height (or the measures asked for:
//   heap_height, runout, profile_convexity too), with measurement noise on top of the heaps' own
//   scatter.
// - A slide or roll case (one body) is simulated once per condition: slide_angle, roll_angle or
//   roll_distance, with the measurement noise.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace repose {

struct SyntheticTruth {
  std::string case_path;                 // the drop case simulated
  std::string extension;                 // "" : the baseline alone
  std::vector<double> extension_params;  // in the order of the extension's parameters
  std::optional<double> restitution;     // body-plate restitution of the truth (default: the case's)
  std::optional<double> grain_friction;  // heap: the grains' sliding friction (default: the case's)
  std::optional<double> plate_friction;  // slide: body-plate sliding friction; roll: rolling friction
  std::vector<double> heights;           // drop heights, m (the condition variable); other cases:
                                         // the values of condition_key
  // The key the conditions vary in a heap, slide or roll case (any case key); empty: the
  // experiment's own (its DiagnosisRole: experiment.drop_height, fill.0.count,
  // experiment.slope_distance, material.0.density).
  std::string condition_key;
  double angle_noise = 0.5;              // SD of one measured angle, deg (lengths: `noise`)
  bool bed_height_only = false;          // heap: only bed_height rows (the bed alone is simulated)
  // The scalar measures written (any the experiment reports: a heap's heap_height, runout,
  // profile_convexity too); empty: the experiment's usual ones (a heap's repose_angle, bed_height).
  std::vector<std::string> measures;
  double unitless_noise = 0.01;          // SD of one measured dimensionless value (profile_convexity)
  int replicates = 5;
  double noise = 0.001;                  // SD of one measured length (rebound height, bed height, L), m
  double series_dt = 0;                  // > 0: also the camera trajectory every series_dt s
  double series_noise = 0.001;           // SD of one tracked height, m
  double series_correlation = 0;         // lag-1 correlation of a track's noise (AR(1); a camera's
                                         // tracking error drifts from frame to frame)
  bool write_sigma = false;              // a sigma column (the noise SDs): the scatter becomes data
  uint64_t seed = 1;                     // noise; and the orientations of a clump body (shape)
  bool progress = false;                 // a line per simulation on stderr, with its ETA
};

// Writes the CSV (the case column relative to the CSV's folder) atomically.
void write_synthetic_data(const SyntheticTruth& truth, const std::string& csv_path);

}  // namespace repose
