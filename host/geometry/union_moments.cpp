#include "geometry/union_moments.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace repose {
namespace {

// Sphere as seen by the integrator: (p, q) across the lines, l along them, relative to the
// bounding-box centre so that the second moments do not lose digits to a far origin.
struct LocalSphere {
  double p, q, l, r, r2;
  double finest_cell;  // edge refinement stops at this cell size: a fixed fraction of r
};

// Running sums of the integrals of 1, p, q, l, pp, qq, ll, pq, pl, ql over the union.
struct Sums {
  double v = 0, p = 0, q = 0, l = 0, pp = 0, qq = 0, ll = 0, pq = 0, pl = 0, ql = 0;
  void add(const Sums& o) {
    v += o.v; p += o.p; q += o.q; l += o.l;
    pp += o.pp; qq += o.qq; ll += o.ll; pq += o.pq; pl += o.pl; ql += o.ql;
  }
};

struct Interval {
  double lo, hi;
};

class Integrator {
 public:
  Integrator(const std::vector<LocalSphere>& spheres, std::vector<std::vector<int>> overlapping)
      : spheres_(spheres), overlapping_(std::move(overlapping)), stamp_(spheres.size(), 0) {}

  // Adds the integral over the rectangle [p0,p1] x [q0,q1] to out; candidates are the spheres
  // whose silhouette disc may touch the rectangle.
  //
  // The integrand (union chord length and its moments) is smooth except (a) near a silhouette
  // circle, where it behaves like sqrt(distance), and (b) on the projection of the intersection
  // circle of two overlapping spheres, where two chord ends cross and the union has a kink.
  // Cells with either are split into quadrants until they reach the finest cell size of the
  // spheres involved (a fixed fraction of their radius); smooth cells take 3x3 Gauss points,
  // the finest non-smooth ones 2x2.
  void rectangle(double p0, double p1, double q0, double q1, const std::vector<int>& candidates,
                 Sums& out) {
    std::vector<int> touching;
    std::vector<double> far2;  // squared distance from each touching centre to the farthest corner
    const double size = std::max(p1 - p0, q1 - q0);
    bool near_edge = false, refine = false;
    for (int index : candidates) {
      const LocalSphere& s = spheres_[static_cast<size_t>(index)];
      double near_p = std::clamp(s.p, p0, p1), near_q = std::clamp(s.q, q0, q1);
      double dmin2 = (s.p - near_p) * (s.p - near_p) + (s.q - near_q) * (s.q - near_q);
      if (dmin2 >= s.r2) continue;  // the disc misses the rectangle
      touching.push_back(index);
      double far_p = std::max(std::abs(s.p - p0), std::abs(s.p - p1));
      double far_q = std::max(std::abs(s.q - q0), std::abs(s.q - q1));
      far2.push_back(far_p * far_p + far_q * far_q);
      // Within one cell size of the circle counts as near: Gauss points lose their order there.
      double inner = std::max(0.0, s.r - size);
      if (far2.back() > inner * inner) {
        near_edge = true;
        if (size > s.finest_cell) refine = true;
      }
    }
    if (touching.empty()) return;
    const double pm = 0.5 * (p0 + p1), qm = 0.5 * (q0 + q1);
    bool kink = false;
    if (!near_edge && touching.size() > 1) {
      // Every touching disc covers the whole cell here. A chord end moves with slope
      // |grad h| = rho / h, largest at the farthest corner; if two chord ends differ at the
      // centre by more than that slope times the half-diagonal, they cannot cross in the cell.
      ++stamp_counter_;
      for (size_t k = 0; k < touching.size(); ++k) {
        stamp_[static_cast<size_t>(touching[k])] = stamp_counter_;
        slope_bound_[static_cast<size_t>(touching[k])] =
            std::sqrt(far2[k] / (spheres_[static_cast<size_t>(touching[k])].r2 - far2[k]));
      }
      const double half_diagonal = 0.5 * std::hypot(p1 - p0, q1 - q0);
      for (int i : touching) {
        const LocalSphere& a = spheres_[static_cast<size_t>(i)];
        for (int j : overlapping_[static_cast<size_t>(i)]) {
          if (j < i || stamp_[static_cast<size_t>(j)] != stamp_counter_) continue;
          const LocalSphere& b = spheres_[static_cast<size_t>(j)];
          double ha = std::sqrt(a.r2 - ((pm - a.p) * (pm - a.p) + (qm - a.q) * (qm - a.q)));
          double hb = std::sqrt(b.r2 - ((pm - b.p) * (pm - b.p) + (qm - b.q) * (qm - b.q)));
          double bound = (slope_bound_[static_cast<size_t>(i)] + slope_bound_[static_cast<size_t>(j)]) * half_diagonal;
          double closest = std::min({std::abs((a.l + ha) - (b.l + hb)), std::abs((a.l - ha) - (b.l - hb)),
                                     std::abs((a.l + ha) - (b.l - hb)), std::abs((b.l + hb) - (a.l - ha))});
          if (closest <= bound) {
            kink = true;
            if (size > std::min(a.finest_cell, b.finest_cell)) refine = true;
          }
        }
        if (refine) break;
      }
    }
    if (refine) {
      rectangle(p0, pm, q0, qm, touching, out);
      rectangle(pm, p1, q0, qm, touching, out);
      rectangle(p0, pm, qm, q1, touching, out);
      rectangle(pm, p1, qm, q1, touching, out);
      return;
    }
    static const double kNodes3[3] = {-0.77459666924148337704, 0.0, 0.77459666924148337704};
    static const double kWeights3[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
    static const double kNodes2[2] = {-0.57735026918962576451, 0.57735026918962576451};
    static const double kWeights2[2] = {1.0, 1.0};
    const bool smooth = !near_edge && !kink;
    const int n = smooth ? 3 : 2;
    const double* nodes = smooth ? kNodes3 : kNodes2;
    const double* weights = smooth ? kWeights3 : kWeights2;
    const double ap = 0.5 * (p1 - p0), aq = 0.5 * (q1 - q0);
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b)
        line(pm + ap * nodes[a], qm + aq * nodes[b], ap * aq * weights[a] * weights[b], touching, out);
  }

 private:
  // Exact integrals along the line (p, q, l) of 1, l and l^2 over the union of chords, weighted.
  void line(double p, double q, double weight, const std::vector<int>& candidates, Sums& out) {
    chords_.clear();
    for (int index : candidates) {
      const LocalSphere& s = spheres_[static_cast<size_t>(index)];
      double rho2 = (p - s.p) * (p - s.p) + (q - s.q) * (q - s.q);
      if (rho2 >= s.r2) continue;
      double half = std::sqrt(s.r2 - rho2);
      chords_.push_back({s.l - half, s.l + half});
    }
    if (chords_.empty()) return;
    std::sort(chords_.begin(), chords_.end(), [](const Interval& a, const Interval& b) {
      return a.lo < b.lo || (a.lo == b.lo && a.hi < b.hi);
    });
    double length = 0, first = 0, second = 0;
    auto close = [&](double lo, double hi) {
      double d = hi - lo;
      length += d;
      first += 0.5 * d * (hi + lo);
      second += d * (hi * hi + hi * lo + lo * lo) / 3.0;
    };
    double lo = chords_[0].lo, hi = chords_[0].hi;
    for (size_t i = 1; i < chords_.size(); ++i) {
      if (chords_[i].lo > hi) {
        close(lo, hi);
        lo = chords_[i].lo;
        hi = chords_[i].hi;
      } else {
        hi = std::max(hi, chords_[i].hi);
      }
    }
    close(lo, hi);
    double wl = weight * length, w1 = weight * first;
    out.v += wl;
    out.p += p * wl;
    out.q += q * wl;
    out.l += w1;
    out.pp += p * p * wl;
    out.qq += q * q * wl;
    out.pq += p * q * wl;
    out.pl += p * w1;
    out.ql += q * w1;
    out.ll += weight * second;
  }

  const std::vector<LocalSphere>& spheres_;
  std::vector<std::vector<int>> overlapping_;  // per sphere: spheres whose surfaces intersect it
  std::vector<unsigned> stamp_;                 // == stamp_counter_: sphere touches the current cell
  std::vector<double> slope_bound_ = std::vector<double>(spheres_.size(), 0.0);
  unsigned stamp_counter_ = 0;
  std::vector<Interval> chords_;
};

// For each sphere, the spheres whose surfaces intersect it (overlapping, neither inside the
// other): only such pairs make kinks. Sweep along l, so the cost is near-linear for clumps.
std::vector<std::vector<int>> overlapping_pairs(const std::vector<LocalSphere>& spheres) {
  std::vector<int> order(spheres.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    double la = spheres[static_cast<size_t>(a)].l - spheres[static_cast<size_t>(a)].r;
    double lb = spheres[static_cast<size_t>(b)].l - spheres[static_cast<size_t>(b)].r;
    return la < lb || (la == lb && a < b);
  });
  std::vector<std::vector<int>> result(spheres.size());
  for (size_t x = 0; x < order.size(); ++x) {
    const LocalSphere& a = spheres[static_cast<size_t>(order[x])];
    for (size_t y = x + 1; y < order.size(); ++y) {
      const LocalSphere& b = spheres[static_cast<size_t>(order[y])];
      if (b.l - b.r >= a.l + a.r) break;
      double d = std::sqrt((a.p - b.p) * (a.p - b.p) + (a.q - b.q) * (a.q - b.q) + (a.l - b.l) * (a.l - b.l));
      if (d < a.r + b.r && d > std::abs(a.r - b.r)) {
        result[static_cast<size_t>(order[x])].push_back(order[y]);
        result[static_cast<size_t>(order[y])].push_back(order[x]);
      }
    }
  }
  for (auto& list : result) std::sort(list.begin(), list.end());
  return result;
}

// The integration grid: lines along the axis l (the longest extent unless given), cells in the
// plane (p, q) across it, everything relative to the bounding box's centre `reference`.
struct Grid {
  glm::dvec3 reference{0.0};
  int axis_p = 1, axis_q = 2, axis_l = 0;
  int np = 1, nq = 1;
  double hp = 0, hq = 0, p_origin = 0, q_origin = 0;
  std::vector<LocalSphere> local;        // the spheres in grid coordinates
  std::vector<std::vector<int>> rows;    // spheres per grid row (a band in q), in input order
};

// Checks the spheres and options and lays the grid over them.
Grid integration_grid(const std::vector<Sphere>& spheres, const UnionIntegration& options) {
  if (spheres.empty()) throw std::invalid_argument("union_moments: no spheres");
  if (!(options.cells_per_min_radius > 0) || options.max_cells_per_side < 1 || options.refine_depth < 0 ||
      options.refine_depth > 20 || options.line_axis < -1 || options.line_axis > 2)
    throw std::invalid_argument("union_moments: invalid integration options");
  glm::dvec3 lo(HUGE_VAL), hi(-HUGE_VAL);
  double min_radius = HUGE_VAL;
  for (size_t i = 0; i < spheres.size(); ++i) {
    const Sphere& s = spheres[i];
    if (!(s.radius > 0) || !std::isfinite(s.radius) || !std::isfinite(s.centre.x) ||
        !std::isfinite(s.centre.y) || !std::isfinite(s.centre.z))
      throw std::invalid_argument("union_moments: sphere " + std::to_string(i + 1) +
                                  " has a non-positive radius or a non-finite value");
    lo = glm::min(lo, s.centre - s.radius);
    hi = glm::max(hi, s.centre + s.radius);
    min_radius = std::min(min_radius, s.radius);
  }
  Grid g;
  g.reference = 0.5 * (lo + hi);
  const glm::dvec3 extent = hi - lo;

  // Lines run along the longest extent: that gives the fewest lines for elongated bodies.
  g.axis_l = options.line_axis;
  if (g.axis_l < 0) {
    g.axis_l = 0;
    for (int a = 1; a < 3; ++a)
      if (extent[a] > extent[g.axis_l]) g.axis_l = a;
  }
  g.axis_p = (g.axis_l + 1) % 3;
  g.axis_q = (g.axis_l + 2) % 3;

  g.local.reserve(spheres.size());
  for (const Sphere& s : spheres) {
    glm::dvec3 c = s.centre - g.reference;
    g.local.push_back({c[g.axis_p], c[g.axis_q], c[g.axis_l], s.radius, s.radius * s.radius,
                       s.radius / (options.cells_per_min_radius * std::ldexp(1.0, options.refine_depth))});
  }

  double cell = min_radius / options.cells_per_min_radius;
  cell = std::max(cell, std::max(extent[g.axis_p], extent[g.axis_q]) / options.max_cells_per_side);
  g.np = std::max(1, static_cast<int>(std::ceil(extent[g.axis_p] / cell)));
  g.nq = std::max(1, static_cast<int>(std::ceil(extent[g.axis_q] / cell)));
  g.hp = extent[g.axis_p] / g.np;
  g.hq = extent[g.axis_q] / g.nq;
  g.p_origin = -0.5 * extent[g.axis_p];
  g.q_origin = -0.5 * extent[g.axis_q];

  g.rows.assign(static_cast<size_t>(g.nq), {});
  for (size_t i = 0; i < g.local.size(); ++i) {
    int j0 = static_cast<int>(std::floor((g.local[i].q - g.local[i].r - g.q_origin) / g.hq));
    int j1 = static_cast<int>(std::floor((g.local[i].q + g.local[i].r - g.q_origin) / g.hq));
    for (int j = std::max(0, j0); j <= std::min(g.nq - 1, j1); ++j)
      g.rows[static_cast<size_t>(j)].push_back(static_cast<int>(i));
  }
  return g;
}

// The sums over the union, cell by cell, each grid row summed on its own and then added in order.
Sums integrate_cells(const Grid& g) {
  Integrator integrator(g.local, overlapping_pairs(g.local));
  Sums total;
  std::vector<int> in_cell;
  for (int j = 0; j < g.nq; ++j) {
    const double q0 = g.q_origin + j * g.hq, q1 = g.q_origin + (j + 1) * g.hq;
    Sums row_sum;
    for (int i = 0; i < g.np; ++i) {
      const double p0 = g.p_origin + i * g.hp, p1 = g.p_origin + (i + 1) * g.hp;
      in_cell.clear();
      for (int index : g.rows[static_cast<size_t>(j)]) {
        const LocalSphere& s = g.local[static_cast<size_t>(index)];
        if (s.p + s.r > p0 && s.p - s.r < p1) in_cell.push_back(index);
      }
      if (!in_cell.empty()) integrator.rectangle(p0, p1, q0, q1, in_cell, row_sum);
    }
    total.add(row_sum);
  }
  return total;
}

}  // namespace

UnionMoments union_moments(const std::vector<Sphere>& spheres, const UnionIntegration& options) {
  const Grid g = integration_grid(spheres, options);
  const Sums total = integrate_cells(g);
  const int axis_p = g.axis_p, axis_q = g.axis_q, axis_l = g.axis_l;
  UnionMoments result;
  result.volume = total.v;
  glm::dvec3 first(0.0);
  first[axis_p] = total.p;
  first[axis_q] = total.q;
  first[axis_l] = total.l;
  const glm::dvec3 offset = first / total.v;  // centroid relative to the reference point
  result.centroid = g.reference + offset;

  double raw[3][3];
  raw[axis_p][axis_p] = total.pp;
  raw[axis_q][axis_q] = total.qq;
  raw[axis_l][axis_l] = total.ll;
  raw[axis_p][axis_q] = raw[axis_q][axis_p] = total.pq;
  raw[axis_p][axis_l] = raw[axis_l][axis_p] = total.pl;
  raw[axis_q][axis_l] = raw[axis_l][axis_q] = total.ql;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      result.central_second_moment[a][b] = raw[a][b] - total.v * offset[a] * offset[b];
  return result;
}

}  // namespace repose
