// Synthetic measured data with a known truth, to check that `repose diagnose` finds what was
// hidden: the case's drop test simulated with a truth model (the baseline plus, optionally, one
// extension of given strength) at several drop heights, each replicate with Gaussian noise of a
// stated size, written in the measured-data CSV format (README "Measured data"). A truth whose
// body is a clump (extension `shape`) lands at a random orientation: every replicate is its own
// drop, with seeds no diagnosis uses (1,000,000 + 10,000 seed + 100 height index + replicate).
// A heap case (experiment repose, grains from sphere [[fill]]s) is refilled for every replicate
// with such seeds; each replicate gives repose_angle and bed_height, with measurement noise on top
// of the heaps' own scatter.
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
  std::vector<double> heights;           // drop heights, m (the condition variable); a heap case:
                                         // the values of heap_condition_key
  std::string heap_condition_key = "fill.0.count";  // a heap's condition variable (any case key)
  double angle_noise = 0.5;              // heap: SD of one measured angle, deg (bed height: `noise`)
  bool bed_height_only = false;          // heap: only bed_height rows (the bed alone is simulated)
  int replicates = 5;
  double noise = 0.001;                  // SD of one measured rebound height, m
  double series_dt = 0;                  // > 0: also the camera trajectory every series_dt s
  double series_noise = 0.001;           // SD of one tracked height, m
  bool write_sigma = false;              // a sigma column (the noise SDs): the scatter becomes data
  uint64_t seed = 1;                     // noise; and the orientations of a clump body (shape)
};

// Writes the CSV (the case column relative to the CSV's folder) atomically.
void write_synthetic_data(const SyntheticTruth& truth, const std::string& csv_path);

}  // namespace repose
