// Experimental designs in coded units (-1/+1 for the factorial range), with the factors'
// actual ranges to decode them: two-level full and fractional factorials, Plackett-Burman
// screening designs, central composite and Box-Behnken response-surface designs, steepest
// ascent/descent paths, centre points and a seeded randomised run order.
#pragma once
#include <Eigen/Dense>
#include <cstdint>
#include <string>
#include <vector>

#include "stats/csv_table.h"
#include "stats/factor.h"

namespace repose::stats {

enum class PointType { factorial, axial, edge, centre, path };
std::string point_type_name(PointType t);

struct Design {
  std::string type;                  // "factorial", "fractional", "pb12", "pb20", "ccd", "bbd", "path"
  std::vector<Factor> factors;       // real factors, in column order
  std::vector<std::string> dummies;  // Plackett-Burman dummy columns (coded only)
  Eigen::MatrixXd coded;             // runs x (factors + dummies), standard order
  std::vector<PointType> points;     // kind of each run, standard order
  std::vector<int> run_order;        // run_order[r] = standard-order index of the r-th run
  double alpha = 0;                  // axial distance of a central composite design
  std::vector<std::string> generators;  // of a fractional factorial, e.g. "D=ABC"

  int runs() const { return static_cast<int>(coded.rows()); }
  double actual(int std_index, int factor) const {
    return factors[factor].to_actual(coded(std_index, factor));
  }
};

// 2^k runs in Yates standard order (A changes fastest), then `centres` centre points.
Design full_factorial(const std::vector<Factor>& factors, int centres);

// 2^(k-p) runs. Each generator names a non-base factor as a signed product of base factors,
// e.g. "D=ABC" or "E=-ABD" (letters A, B, ... by column; I is skipped). Base factors are the
// first k-p. Throws DesignError for a letter that is out of range or a factor generated twice.
Design fractional_factorial(const std::vector<Factor>& factors,
                            const std::vector<std::string>& generators, int centres);
// Minimum-aberration generators (Montgomery, Design and Analysis of Experiments, Table 8.14)
// for 3 <= k <= 8; throws DesignError for a (k, p) the table does not list.
std::vector<std::string> default_generators(int k, int p);

// Plackett-Burman with 12 or 20 runs: the published first row, cyclically shifted, plus a row
// of minus signs. The first factors.size() columns are the real factors, the remaining
// (runs-1-k) columns are dummies, whose effects estimate the error.
Design plackett_burman(int runs, const std::vector<Factor>& factors, int centres);

enum class AlphaKind { rotatable, orthogonal, face, value };
struct AlphaSpec {
  AlphaKind kind = AlphaKind::rotatable;
  double value = 0;  // used when kind == value
};
AlphaSpec parse_alpha(const std::string& s);  // "rotatable", "orthogonal", "face" or a number
// Rotatable: F^(1/4); orthogonal: makes the quadratic columns uncorrelated,
// sqrt((sqrt(F N) - F) / 2) with N = F + 2k + centres; face-centred: 1.
double ccd_alpha(const AlphaSpec& spec, int k, int factorial_points, int centres);

// Papers print the axial level rounded (1.682 for the rotatable alpha 1.68179 of k = 3).
// Replaces every coded value within `tolerance` of +-alpha by +-alpha exactly, so a refit uses
// the design the software actually ran. Returns the number of cells changed.
int snap_to_alpha(Eigen::MatrixXd& coded, double alpha, double tolerance = 5e-4);

// Full 2^k cube, 2k axial points at +-alpha, then `centres` centre points.
Design central_composite(const std::vector<Factor>& factors, const AlphaSpec& alpha, int centres);

// Box-Behnken for 3 <= k <= 7: +-1 on pairs (k = 3, 4, 5) or on the triples of Box and
// Behnken's incomplete block designs (k = 6, 7), other factors at 0; then the centre points.
Design box_behnken(const std::vector<Factor>& factors, int centres);

// The path of steepest ascent (or descent) of a first-order model with coded slopes b:
// each step moves the base factor (default: the largest |b|) by `base_step` coded units and
// every other factor by b_i / |b_base| * base_step, in the direction that raises (or lowers)
// the response. Step 0 is the design centre.
Design steepest_path(const std::vector<Factor>& factors, const Eigen::VectorXd& slopes,
                     double base_step, int steps, bool ascent, int base_factor = -1);

// Replaces the run order by a permutation drawn with std::mt19937_64 seeded by `seed`, using
// an unbiased bounded draw written out here, so the order is the same on every platform.
void randomise_run_order(Design& design, std::uint64_t seed);

// The design as a table in run order: Std, Run, Type, the actual values of each factor (named
// after the factor), each factor coded ("<name>_coded"), then the dummy columns (coded).
Table design_table(const Design& design, int digits = 10);

}  // namespace repose::stats
