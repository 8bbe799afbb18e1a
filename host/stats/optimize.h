// Optimisation of fitted response surfaces inside the coded design region: minimise, maximise,
// hit a target, or maximise Derringer's overall desirability of several responses. A
// deterministic multi-start pattern search (Hooke-Jeeves) finds the best point; then, because
// one measured value is matched by a whole curve or surface of parameter sets, the region
// within a tolerance of the optimum (or of the target) is sampled and reported, not only the
// single best point.
#pragma once
#include <Eigen/Dense>
#include <functional>
#include <string>
#include <vector>

namespace repose::stats {

using Objective = std::function<double(const Eigen::VectorXd&)>;

enum class GoalKind { minimize, maximize, target };
struct Goal {
  GoalKind kind = GoalKind::minimize;
  double target = 0;  // for GoalKind::target
};
std::string goal_name(const Goal& g);

// Coded bounds of every factor; a factor with lower == upper is held fixed there.
struct Box {
  Eigen::VectorXd lower, upper;
  static Box cube(int k, double half_width);  // [-h, h]^k
  void fix(int factor, double coded_value);
};

struct OptimizeOptions {
  int halton_starts = 32;      // quasi-random starts, added to the centre and the corners
  double tolerance = 0;        // width of the reported set in response units (0: 1 % of the
                               // response's range over the box, estimated from the samples)
  int grid_budget = 200000;    // points sampled to find the near-optimal set
  int representatives = 12;    // points of that set listed (farthest-point sampling)
};

struct Optimum {
  Eigen::VectorXd x;             // best point (coded)
  double value = 0;              // response (or overall desirability) there
  double tolerance = 0;          // the tolerance actually used
  // The near-optimal set: all sampled points whose response is within `tolerance` of the
  // optimum (minimise/maximise/desirability) or of the target (target).
  int set_size = 0;              // sampled points in the set
  int sampled = 0;               // sampled points in total
  Eigen::VectorXd set_lower, set_upper;  // per-factor extent of the set (coded)
  Eigen::VectorXd principal_direction;   // direction along which the set extends most
  std::vector<Eigen::VectorXd> representatives;  // spread-out members, the best first
  std::vector<double> representative_values;
  bool target_reached = true;    // target goal: |best - target| <= tolerance
};

Optimum optimize(const Objective& response, const Box& box, const Goal& goal,
                 const OptimizeOptions& options = {});

// Derringer and Suich (1980) desirability of one response: 0 outside [low, high], rising to 1
// at the goal with exponent `weight`; responses combine by a geometric mean weighted by
// `importance`.
struct DesirabilityGoal {
  GoalKind kind = GoalKind::maximize;
  double low = 0, high = 1;  // acceptable range of the response
  double target = 0;         // for GoalKind::target (low <= target <= high)
  double weight = 1;         // shape exponent (for a target: both sides)
  double importance = 1;
};
double desirability(double y, const DesirabilityGoal& goal);
double overall_desirability(const std::vector<double>& y, const std::vector<DesirabilityGoal>& goals);

// Maximises the overall desirability; Optimum::value is D at the best point.
Optimum optimize_desirability(const std::vector<Objective>& responses,
                              const std::vector<DesirabilityGoal>& goals, const Box& box,
                              const OptimizeOptions& options = {});

// How a given (e.g. published) point compares with the optimum found.
struct PointComparison {
  double value = 0;       // response at the point
  double gap = 0;         // how much worse than the optimum, in the goal's sense (>= 0 if worse)
  bool in_near_set = false;  // within the optimum's tolerance
  bool inside_box = true;
};
PointComparison compare_point(const Objective& response, const Goal& goal, const Optimum& best,
                              const Box& box, const Eigen::VectorXd& point);

}  // namespace repose::stats
