// A Gaussian-process surrogate of one response over coded factors: a linear trend in the factors
// (its coefficients estimated with their uncertainty, universal kriging) plus a squared-exponential
// process (one length scale per factor) and a nugget for run-to-run noise. A response that rises
// with a parameter is then carried on by the trend beyond the runs, not pulled back to its mean.
// Hyperparameters maximise the restricted (REML) likelihood over a fixed grid (length scales, and
// noise/signal ratios with the signal variance profiled; one eigendecomposition per length
// scale), so a fit is deterministic and needs no random start. The noise can be held inside bounds
// measured from replicates, so a curve is never drawn through noisy runs as if they were exact.
#pragma once
#include <Eigen/Dense>
#include <vector>

namespace repose::calibrate {

struct GaussianProcess {
  Eigen::MatrixXd x;              // training inputs (runs x factors, coded)
  Eigen::VectorXd length_scale;   // per factor (coded units)
  double noise_ratio = 1e-8;      // nugget / signal variance
  double signal_variance = 1;     // of the standardised response
  double y_mean = 0, y_scale = 1;  // standardisation of the training response
  bool trend = true;              // linear trend (false: a constant, with too few runs for the trend)
  Eigen::VectorXd beta;           // trend coefficients (standardised): 1, x_1 .. x_k
  Eigen::VectorXd alpha;          // (R + nugget)^-1 (y - H beta) (standardised)
  Eigen::LLT<Eigen::MatrixXd> chol;     // of R + nugget
  Eigen::MatrixXd h;                    // the trend's basis at the training points (runs x terms)
  Eigen::MatrixXd h_kinv_h_inverse;     // (H' (R + nugget)^-1 H)^-1: the trend's uncertainty
  double log_likelihood = 0;

  // Posterior mean and standard deviation of the latent (noise-free mean) response at a coded point.
  double mean(const Eigen::VectorXd& at) const;
  double sd(const Eigen::VectorXd& at) const;
  // d mean / d x (coded), by central differences of the mean.
  Eigen::VectorXd gradient(const Eigen::VectorXd& at) const;
  // The run-to-run noise sd the fit settled on (the nugget), in the response's units.
  double noise_sd() const;
  // The trend's basis at a point: 1, then the coded factors (only 1 without the trend).
  Eigen::VectorXd basis(const Eigen::VectorXd& at) const;
};

// Bounds on the run-to-run noise sd, in the response's units (from replicates: their confidence
// interval). The default leaves the noise free, from noise-free up.
struct NoiseBounds {
  double low = 0, high = INFINITY;
};

// Throws std::runtime_error with fewer than two runs. `linear_trend` false: a constant mean only
// (for a response that is already the residual of a fitted trend).
GaussianProcess fit_gaussian_process(const Eigen::MatrixXd& x, const Eigen::VectorXd& y, const NoiseBounds& noise = {},
                                     bool linear_trend = true);

// The same process for another response over the same inputs: the hyperparameters and the kernel
// matrix's factor are kept, the response standardised, the trend and alpha solved again and the
// signal variance profiled (as fitting does).
GaussianProcess with_response(const GaussianProcess& shape, const Eigen::VectorXd& y);

// Expected improvement for hitting a target: E[max(0, best - |Y - target|)] with
// Y ~ N(mean, sd^2) and `best` the smallest |y - target| seen so far (closed form).
double expected_improvement_to_target(double mean, double sd, double target, double best);

}  // namespace repose::calibrate
