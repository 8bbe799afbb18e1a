// The parameters consistent with the measured values: a posterior over the coded factor box
// (flat prior), from the campaign's surrogate of each calibrating response. The likelihood of a
// point is prod_i N(measured_i; mean_i(x), se_i^2 + sd_i(x)^2 + cell_i(x)): the lab's standard
// error, the surrogate's uncertainty about the mean response (the runs' noise averaged), and the
// spread of the mean across one grid cell (so a noise-free model is not sharper than the grid).
// Evaluated on a dense grid of cell centres (Halton points beyond 4 free factors): credible
// intervals per parameter, the joint 90 % region, and the ridge, the direction along which the
// data leave the parameters free.
#pragma once
#include <Eigen/Dense>
#include <functional>
#include <string>
#include <vector>

namespace repose::calibrate {

struct PosteriorInput {  // one calibrating response
  std::function<double(const Eigen::VectorXd&)> mean, sd;  // at a coded point; sd may be empty (exact)
  double measured = 0, measured_se = 0;
};

struct CredibleInterval {  // coded units
  double low = 0, median = 0, high = 0;  // 5 %, 50 %, 95 % of the marginal
  double mean = 0, sd = 0;
};

struct Posterior {
  bool computed = false;
  int factors = 0;
  std::vector<int> free;                 // the factors the grid spans (the others held)
  Eigen::VectorXd held;                  // every factor's coded value where held (free ones ignored)
  std::vector<Eigen::VectorXd> nodes;    // grid nodes, coded, full dimension
  std::vector<double> mass;              // posterior mass of each node (sums to 1)
  std::vector<int> per_axis;             // nodes along each free factor (grid); empty: Halton points
  double region_mass = 0.9;
  double region_threshold = 0;           // nodes with at least this mass form the joint 90 % region
  std::vector<CredibleInterval> marginal;  // per factor (a held factor: its value, zero width)
  Eigen::VectorXd region_low, region_high;  // extent of the joint region per factor (coded)
  double region_fraction = 0;            // share of the free box inside the joint region
  Eigen::VectorXd ridge;                 // unit direction (coded, full dimension) of largest posterior spread
  double ridge_sd = 0, across_sd = 0;    // posterior sd along it, and along the narrowest direction
  double cell = 0;                       // coded spacing of the grid (per free factor)

  // Whether the joint 90 % region holds a coded point (the node nearest it).
  bool in_region(const Eigen::VectorXd& coded) const;
  // Index of the node nearest a coded point.
  int nearest(const Eigen::VectorXd& coded) const;
};

// `held`: (factor, coded value) pairs kept fixed. Throws std::invalid_argument with no input.
Posterior compute_posterior(int factors, const std::vector<PosteriorInput>& inputs,
                            const std::vector<std::pair<int, double>>& held = {});

// The prior sd of a coded factor uniform on [-1, 1]: a posterior this wide along a direction
// has learnt nothing there.
constexpr double kFlatPriorSd = 0.5773502691896258;

// "+0.36 mu_s - 0.93 mu_r": a coded direction in factor names (largest components first; zero
// components left out).
std::string direction_text(const Eigen::VectorXd& direction, const std::vector<std::string>& names);

}  // namespace repose::calibrate
