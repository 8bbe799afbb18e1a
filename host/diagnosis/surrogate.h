// A model's predictions as smooth functions of its parameters, so that a diagnosis fits on a
// surface instead of simulating every trial (docs/diagnosis.md, "Fits on a surrogate"). The model
// is simulated at a design of points in the unit cube of its parameters, every condition at each
// point; each group's mean (and, where the data give sigma, a stochastic model's replicate SD)
// over the points is a quadratic trend plus a Gaussian process on its residual
// (calibrate/gaussian_process.h, the calibration's surrogate). A fit minimises the score
// (model_fit.h) on that surface and simulates where the minimum lies, in a trust region, until the
// surface agrees with the simulation there; the leave-one-condition-out refits and the mimic tests
// reuse the same points.
//
// A heap is chaotic: any parameter change redraws every fill's outcome, so each design point is
// filled with fills of its own (the surface pools their luck instead of keeping one set's) and
// half the replicates of --sim-replicates (the neighbouring points average the rest). A clump's
// drop keeps common random numbers: the same orientations at every point, a smooth surface.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "calibrate/gaussian_process.h"
#include "diagnosis/model_fit.h"
#include "stats/model_terms.h"

namespace repose {

// A minimum of the score on the surface (or, with no parameter, the one simulated model).
struct SurfaceMinimum {
  std::vector<double> u;     // in the unit cube of the model's parameters
  double score = 0;          // the surface's score there, or the simulation's when `simulated`
  bool simulated = false;    // the model was simulated at u and `score` is the simulation's
  Prediction prediction;     // at u: simulated when `simulated`, else the surface's
};

// One group's surface: a quadratic trend over the unit cube plus a Gaussian process on its residual
// (none where the residual is the points' own noise).
struct GroupSurface {
  std::vector<stats::Term> trend;
  Eigen::VectorXd coef;
  bool has_process = true;
  calibrate::GaussianProcess process;
  double trend_variance = 0;  // without a process: the trend's own variance at a point
  double mean(const Eigen::VectorXd& at) const;
  double latent_variance(const Eigen::VectorXd& at) const;  // of the mean's estimate
};

// Surfaces for one response per group, `of(point, group)` over the design `x` (points x
// parameters); `noise` (empty for a smooth model) the variance of a point's value per group.
std::vector<GroupSurface> fit_group_surfaces(const Observations& obs, const Eigen::MatrixXd& x,
                                             const std::function<double(size_t, size_t)>& of,
                                             const std::vector<double>& noise);

class ModelSurrogate {
 public:
  // `on_point(what)` is called after every design point is simulated (progress).
  ModelSurrogate(Predictor& predictor, const ModelExtension* extension,
                 std::function<void(const std::string&)> on_point = {});

  const ModelExtension* extension() const { return extension_; }
  const std::vector<FreeParameter>& parameters() const { return parameters_; }
  std::vector<double> values(const std::vector<double>& u) const;  // unit cube -> parameter values
  bool stochastic() const { return stochastic_; }
  bool chaotic() const { return chaotic_; }  // a heap: noisy between points (else smooth)
  int replicates_per_point() const { return replicates_; }
  size_t points() const { return design_.size(); }

  // Simulates the initial design: a grid over the unit cube (7 points for one parameter, 3 x 3 for
  // two) and, given `near` (an extension's start: the baseline's fitted values, the extension
  // off), a line of 5 points through it along the extension's own parameters: there the
  // extension's effect must be resolved against the baseline's response, which elsewhere may
  // change a hundred times as much across the cube. A model without parameters is simulated once.
  void simulate_design(const std::vector<double>& near = {});
  // An extension's valley: where its parameters trade off against the baseline's (a cohesion
  // absorbed by a higher restitution), the score's minimum is a narrow valley no coarse grid
  // resolves. For each point of the design's line the baseline's parameters are refitted on the
  // surface with the extension's held, and the model simulated there; repeated (at most `passes`
  // times) until the simulations agree with the surface (within 0.5 in chi^2 or 2 %), once for a
  // chaotic model. A model without a line (the baseline, an extension fitted alone) has none.
  void trace_valley(const std::vector<char>& use, int passes);
  // The model simulated at u on every condition, added to the design (an existing point is reused).
  Prediction simulate(const std::vector<double>& u);
  // The surface at u: the processes' means; for a stochastic model the replicate variance (from
  // the SD surface where the data give sigma, else pooled over the points) and each mean's
  // variance from the process's uncertainty.
  Prediction predict(const std::vector<double>& u) const;
  // The same through every point simulated so far (refitted first when points were added).
  Prediction surface(const std::vector<double>& u);
  // The score's minimum on the surface over the conditions in `use` (against `target`'s
  // predictions instead of the data when given), from the three design points the surface scores
  // best and, for a smooth model, the one the simulations score best.
  SurfaceMinimum minimise(const std::vector<char>& use, const Prediction* target = nullptr);
  // A fit with at most `new_points` simulated. A smooth model: a trust region around the best
  // simulated point (the first step over the whole cube), its surface minimum simulated, the region
  // moved to a better point (and doubled where the surface agreed, within 0.05 in chi^2 or 0.5 %)
  // or halved, until the surface's minimum is the best point and agrees there; the result is the
  // best simulated point, exact. Given `near` (a held-out refit starts at the full fit), the first
  // region lies within 0.1 of it. A chaotic model: the surface's minimum, simulated and the
  // surface refitted until it falls within 0.05 of a simulated point; the result is the surface's
  // minimum.
  SurfaceMinimum fit(const std::vector<char>& use, const Prediction* target, int new_points,
                     const std::vector<double>& near = {});

  // Points the design and the fits of a model with `k` parameters plan for (the progress's
  // estimate): the design, the refinement and the held-out refits.
  static int planned_points(size_t k, size_t conditions, bool chaotic);

 private:
  void refit();
  SurfaceMinimum minimise_within(const std::vector<char>& use, const Prediction* target,
                                 const std::vector<double>& centre, double radius);
  size_t best_simulated(const std::vector<char>& use, const Prediction* target) const;
  SurfaceMinimum fit_chaotic(const std::vector<char>& use, const Prediction* target, int new_points);
  Predictor& predictor_;
  const ModelExtension* extension_;
  std::vector<FreeParameter> parameters_;
  std::function<void(const std::string&)> on_point_;
  bool stochastic_ = false, chaotic_ = false, scatter_scored_ = false;
  int replicates_ = 1;
  std::vector<std::vector<double>> design_;
  std::vector<std::vector<double>> line_;  // the design's line through an extension's start
  std::vector<Prediction> simulated_;
  bool stale_ = true;
  std::vector<GroupSurface> mean_, sd_;  // per group; sd_ only where the data score the scatter
  std::vector<double> pooled_var_;        // per group: the points' replicate variance, pooled
};

}  // namespace repose
