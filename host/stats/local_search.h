// Local searches shared by the program's fits (the one optimiser module, with optimize.h's
// pattern search for response surfaces): Nelder-Mead and golden-section search in the unit cube
// (the diagnosis's model fits, parameters scaled to [0, 1]) and a compass search that polishes
// the best of a set of candidates in the coded cube [-1, 1]^k (the adaptive loop). All are
// derivative-free and deterministic.
#pragma once
#include <Eigen/Dense>
#include <cstddef>
#include <functional>
#include <vector>

namespace repose::stats {

using UnitObjective = std::function<double(const std::vector<double>&)>;

struct UnitMinimum {
  std::vector<double> x;
  double value = 0;
};

// Nelder-Mead with the standard coefficients over the dimensions `free` of `start` (the others
// held), the simplex kept inside the unit cube by clamping; the first simplex spans `size`
// along each free dimension. Stops after `budget` evaluations, when the simplex is smaller than
// 1e-3, or when it is smaller than 0.03 and its values span less than `value_tolerance`.
UnitMinimum nelder_mead(const UnitObjective& f, const std::vector<double>& start, const std::vector<size_t>& free,
                        double size, int budget, double value_tolerance);

// Golden-section search of dimension `dim` over [0, 1], the others held at `start`, in
// `evaluations` evaluations of f.
UnitMinimum golden_section(const UnitObjective& f, const std::vector<double>& start, size_t dim, int evaluations);

// The best of `candidates` under `score` (maximised), then polished by a compass search inside
// [-1, 1]^k: steps of 0.05 halved down to 1e-4 along each axis, a move kept when it gains more
// than 1e-15. `top` receives the best score.
Eigen::VectorXd compass_maximise(const std::function<double(const Eigen::VectorXd&)>& score,
                                 const std::vector<Eigen::VectorXd>& candidates, double& top);

}  // namespace repose::stats
