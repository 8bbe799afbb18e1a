#include "case/particle_factory.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>

#include "case/body_pose.h"
#include "case/case_error.h"
#include "geometry/sphere_grid.h"
#include "util/morton.h"

namespace repose {
namespace {

std::string format_point(const Vec3d& p) {
  return "(" + format_number(p[0]) + ", " + format_number(p[1]) + ", " + format_number(p[2]) + ")";
}

std::string describe(const SphereSpec& sphere) {
  return sphere.where.key + " (line " + std::to_string(sphere.where.line) + ")";
}

bool reaches_into(const SphereSpec& s, const Vec3d& lo, const Vec3d& hi) {
  bool near = true;
  for (int axis = 0; axis < 3; ++axis)
    near = near && s.position[axis] + s.radius > lo[axis] && s.position[axis] - s.radius < hi[axis];
  return near;
}

// Grid over [lo, hi] holding the spheres whose bounding boxes reach into it: only they can touch
// the `adding` new spheres placed there. ids maps grid ids back to indices in `spheres`.
SphereGrid grid_near(const std::vector<SphereSpec>& spheres, const Vec3d& lo, const Vec3d& hi,
                     double new_radius_max, size_t adding, std::vector<int>& ids) {
  double largest = 0;
  size_t near = 0;
  for (const SphereSpec& s : spheres)
    if (reaches_into(s, lo, hi)) {
      largest = std::max(largest, s.radius);
      ++near;
    }
  // Cells about one new sphere wide; a much larger existing sphere then spans at most ~17^3.
  SphereGrid grid(std::max(2 * new_radius_max, largest / 8), lo, hi, near + adding);
  for (size_t i = 0; i < spheres.size(); ++i) {
    if (!reaches_into(spheres[i], lo, hi)) continue;
    grid.insert(spheres[i].position, spheres[i].radius);
    ids.push_back(int(i));
  }
  return grid;
}

// Sites per axis: corners at lo + r + i s, body centres half a cell further, all <= hi - r.
// The 1e-9 keeps a site that lands on the margin up to rounding (e.g. 0.9 / 0.1 = 8.999...).
int sites_along(double length, double radius, double spacing, double offset) {
  double usable = length - 2 * radius - offset;
  if (usable < 0) return 0;
  return int(std::floor(usable / spacing + 1e-9)) + 1;
}

// Two unit vectors that complete axis to an orthonormal basis, built the same way everywhere.
void perpendicular_basis(const Vec3d& axis, Vec3d& e1, Vec3d& e2) {
  Vec3d helper = std::fabs(axis[0]) < 0.9 ? Vec3d{1, 0, 0} : Vec3d{0, 1, 0};
  Vec3d c{axis[1] * helper[2] - axis[2] * helper[1], axis[2] * helper[0] - axis[0] * helper[2],
          axis[0] * helper[1] - axis[1] * helper[0]};
  double length = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
  e1 = {c[0] / length, c[1] / length, c[2] / length};
  e2 = {axis[1] * e1[2] - axis[2] * e1[1], axis[2] * e1[0] - axis[0] * e1[2],
        axis[0] * e1[1] - axis[1] * e1[0]};
}

// Puts spheres[first ...] in the Morton order of cells `cell` wide from `origin` (ties in
// placement order), so that spheres near in space are near in memory.
void order_by_cells(std::vector<SphereSpec>& spheres, size_t first, const Vec3d& origin, double cell) {
  std::vector<std::pair<uint64_t, size_t>> keys;
  keys.reserve(spheres.size() - first);
  for (size_t i = first; i < spheres.size(); ++i) {
    uint64_t c[3];
    for (int axis = 0; axis < 3; ++axis)
      c[axis] = uint64_t(std::max(0.0, std::floor((spheres[i].position[axis] - origin[axis]) / cell)));
    keys.push_back({morton_code(c[0], c[1], c[2]), i});
  }
  std::sort(keys.begin(), keys.end());
  std::vector<SphereSpec> ordered;
  ordered.reserve(keys.size());
  for (const auto& key : keys) ordered.push_back(std::move(spheres[key.second]));
  std::move(ordered.begin(), ordered.end(), spheres.begin() + std::ptrdiff_t(first));
}

// Every sphere and body sub-sphere placed so far, in the world.
std::vector<SphereSpec> occupied_spheres(const CaseSpec& spec) {
  std::vector<SphereSpec> occupied = spec.spheres;
  for (const BodySpec& body : spec.bodies) {
    auto subs = body_spheres(body, spec.templates[size_t(body.template_index)]);
    occupied.insert(occupied.end(), subs.begin(), subs.end());
  }
  return occupied;
}

}  // namespace

void check_no_overlaps(const std::vector<SphereSpec>& spheres) {
  if (spheres.empty()) return;
  double largest = 0;
  Vec3d lo = spheres[0].position, hi = lo;
  for (const SphereSpec& s : spheres) {
    largest = std::max(largest, s.radius);
    for (int axis = 0; axis < 3; ++axis) {
      lo[axis] = std::min(lo[axis], s.position[axis] - s.radius);
      hi[axis] = std::max(hi[axis], s.position[axis] + s.radius);
    }
  }
  SphereGrid grid(2 * largest, lo, hi, spheres.size());
  for (const SphereSpec& sphere : spheres) {
    int other = grid.find_overlap(sphere.position, sphere.radius);
    if (other >= 0) {
      const SphereSpec& earlier = spheres[size_t(other)];
      double dx = sphere.position[0] - earlier.position[0];
      double dy = sphere.position[1] - earlier.position[1];
      double dz = sphere.position[2] - earlier.position[2];
      throw CaseError(sphere.where,
                      "overlaps " + describe(earlier) + ": centres " +
                          format_number(std::sqrt(dx * dx + dy * dy + dz * dz)) +
                          " m apart, radii add up to " +
                          format_number(sphere.radius + earlier.radius) + " m");
    }
    grid.insert(sphere.position, sphere.radius);
  }
}

// Sites with a margin per axis and a cell edge per axis (the sphere lattice has both equal).
std::vector<Vec3d> lattice_sites(const LatticeSpec& lattice, const Vec3d& margin, const Vec3d& s) {
  bool bcc = lattice.kind == LatticeSpec::Kind::BodyCentredCubic;
  int corners[3], centres[3];
  for (int axis = 0; axis < 3; ++axis) {
    double length = lattice.box_max[axis] - lattice.box_min[axis];
    corners[axis] = sites_along(length, margin[axis], s[axis], 0);
    centres[axis] = bcc ? sites_along(length, margin[axis], s[axis], s[axis] / 2) : 0;
  }
  std::vector<Vec3d> sites;
  auto add_layer = [&](const int* counts, double offset, int k) {
    double z = lattice.box_min[2] + margin[2] + offset * s[2] + k * s[2];
    for (int j = 0; j < counts[1]; ++j)
      for (int i = 0; i < counts[0]; ++i)
        sites.push_back({lattice.box_min[0] + margin[0] + offset * s[0] + i * s[0],
                         lattice.box_min[1] + margin[1] + offset * s[1] + j * s[1], z});
  };
  for (int k = 0; k < std::max(corners[2], centres[2]); ++k) {
    if (k < corners[2]) add_layer(corners, 0, k);
    if (k < centres[2]) add_layer(centres, 0.5, k);
  }
  return sites;
}

std::vector<Vec3d> lattice_sites(const LatticeSpec& lattice) {
  const double s = lattice.spacing, r = lattice.radius;
  return lattice_sites(lattice, {r, r, r}, {s, s, s});
}

void append_lattice(const LatticeSpec& lattice, std::vector<SphereSpec>& spheres) {
  std::vector<Vec3d> sites = lattice_sites(lattice);
  if (sites.empty())
    throw CaseError(lattice.where, "no site fits: the box is narrower than one sphere diameter");
  if (lattice.max_count > 0) {
    if (size_t(lattice.max_count) > sites.size())
      throw CaseError(lattice.where, "count = " + std::to_string(lattice.max_count) + " but only " +
                                         std::to_string(sites.size()) +
                                         " sites fit in the box");
    sites.resize(size_t(lattice.max_count));
  }
  std::vector<int> ids;
  Vec3d lo = lattice.box_min, hi = lattice.box_max;
  SphereGrid grid = grid_near(spheres, lo, hi, lattice.radius, sites.size(), ids);
  for (const Vec3d& site : sites) {
    int other = grid.find_overlap(site, lattice.radius);
    if (other >= 0)
      throw CaseError(lattice.where, "the site at " + format_point(site) + " overlaps " +
                                         describe(spheres[size_t(ids[size_t(other)])]));
  }
  spheres.reserve(spheres.size() + sites.size());
  for (const Vec3d& site : sites) {
    SphereSpec sphere;
    sphere.position = site;
    sphere.velocity = lattice.velocity;
    sphere.radius = lattice.radius;
    sphere.material = lattice.material;
    sphere.fixed = lattice.fixed;
    sphere.where = lattice.where;
    spheres.push_back(sphere);
  }
}

// A fill's region and random points in it, keeping a margin from its boundary.
struct FillRegion {
  const FillSpec& fill;
  bool box;
  Vec3d e1{}, e2{};
  Vec3d lo{}, hi{};  // bounding box, for choosing which existing spheres can interfere

  explicit FillRegion(const FillSpec& f) : fill(f), box(f.shape == FillSpec::Shape::Box) {
    lo = fill.box_min;
    hi = fill.box_max;
    if (box) return;
    perpendicular_basis(fill.cyl_axis, e1, e2);
    for (int axis = 0; axis < 3; ++axis) {
      double top = fill.cyl_base[axis] + fill.cyl_axis[axis] * fill.cyl_height;
      lo[axis] = std::min(fill.cyl_base[axis], top) - fill.cyl_radius;
      hi[axis] = std::max(fill.cyl_base[axis], top) + fill.cyl_radius;
    }
  }

  template <class Uniform>
  Vec3d random_point(double margin, Uniform& uniform) const {
    Vec3d centre{};
    if (box) {
      for (int axis = 0; axis < 3; ++axis) {
        double span = fill.box_max[axis] - fill.box_min[axis] - 2 * margin;
        centre[axis] = fill.box_min[axis] + margin + span * uniform();
      }
      return centre;
    }
    double along = margin + (fill.cyl_height - 2 * margin) * uniform();
    double a, b;  // uniform in the unit disc by rejection from the square
    do {
      a = 2 * uniform() - 1;
      b = 2 * uniform() - 1;
    } while (a * a + b * b > 1);
    double reach = fill.cyl_radius - margin;
    for (int axis = 0; axis < 3; ++axis)
      centre[axis] = fill.cyl_base[axis] + fill.cyl_axis[axis] * along + e1[axis] * (reach * a) +
                     e2[axis] * (reach * b);
    return centre;
  }
};

void append_body_lattice(const LatticeSpec& lattice, CaseSpec& spec) {
  const TemplateSpec& templ = spec.templates.at(size_t(lattice.template_index));
  // Margin per axis: the half-extent of the oriented, scaled body about its template origin.
  BodySpec probe;
  probe.template_index = lattice.template_index;
  probe.orientation = lattice.orientation;
  probe.scale = lattice.scale;
  Vec3d margin{0, 0, 0};
  for (const SphereSpec& s : body_spheres(probe, templ))
    for (int axis = 0; axis < 3; ++axis)
      margin[axis] = std::max(margin[axis], std::abs(s.position[axis]) + s.radius);
  std::vector<Vec3d> sites = lattice_sites(lattice, margin, lattice.spacing_xyz);
  if (sites.empty())
    throw CaseError(lattice.where, "no site fits: the box is smaller than one '" + templ.name + "' body");
  if (lattice.max_count > 0) {
    if (size_t(lattice.max_count) > sites.size())
      throw CaseError(lattice.where, "count = " + std::to_string(lattice.max_count) + " but only " +
                                         std::to_string(sites.size()) + " sites fit in the box");
    sites.resize(size_t(lattice.max_count));
  }
  std::vector<SphereSpec> occupied = occupied_spheres(spec);
  double largest_sub = 0;
  for (const Sphere& s : templ.clump.spheres) largest_sub = std::max(largest_sub, s.radius * lattice.scale);
  std::vector<int> ids;
  SphereGrid grid = grid_near(occupied, lattice.box_min, lattice.box_max, largest_sub,
                              sites.size() * templ.clump.spheres.size(), ids);
  for (const Vec3d& site : sites) {
    BodySpec body = probe;
    body.material = lattice.material;
    body.position = site;
    body.velocity = lattice.velocity;
    body.fixed = lattice.fixed;
    body.where = lattice.where;
    auto subs = body_spheres(body, templ);
    for (const SphereSpec& s : subs)
      if (grid.find_overlap(s.position, s.radius) >= 0)
        throw CaseError(lattice.where, "the body at site " + format_point(site) +
                                           " overlaps a particle placed before it: widen spacing");
    for (const SphereSpec& s : subs) grid.insert(s.position, s.radius);
    spec.bodies.push_back(body);
  }
}

void append_fill(const FillSpec& fill, std::vector<SphereSpec>& spheres) {
  std::mt19937_64 engine(fill.seed);
  auto uniform = [&engine] { return unit_interval(engine()); };
  FillRegion region(fill);
  std::vector<int> ids;
  SphereGrid grid = grid_near(spheres, region.lo, region.hi, fill.radius_max, size_t(fill.count), ids);

  auto draw_radius = [&] {
    double radius = fill.radius_min;
    if (fill.radius_max > fill.radius_min) radius = fill.radius_min + (fill.radius_max - fill.radius_min) * uniform();
    return radius;
  };
  // Largest first: the big grains find room while the region is empty, the small ones fill gaps.
  std::vector<double> largest_first;
  if (fill.largest_first) {
    for (int k = 0; k < fill.count; ++k) largest_first.push_back(draw_radius());
    std::sort(largest_first.begin(), largest_first.end(), std::greater<double>());
  }
  spheres.reserve(spheres.size() + size_t(fill.count));
  for (int placed = 0; placed < fill.count; ++placed) {
    double radius = fill.largest_first ? largest_first[size_t(placed)] : draw_radius();
    bool found = false;
    Vec3d centre{};
    for (int attempt = 0; attempt < kFillTriesPerSphere && !found; ++attempt) {
      centre = region.random_point(radius, uniform);
      found = grid.find_overlap(centre, radius) < 0;
    }
    if (!found)
      throw CaseError(fill.where,
                      "only " + std::to_string(placed) + " of the " + std::to_string(fill.count) +
                          " spheres (count) fit without overlap: sphere " +
                          std::to_string(placed + 1) + " found no free place in " +
                          std::to_string(kFillTriesPerSphere) +
                          " random tries; enlarge the region or lower count");
    grid.insert(centre, radius);
    SphereSpec sphere;
    sphere.position = centre;
    sphere.velocity = fill.velocity;
    sphere.radius = radius;
    sphere.material = fill.material;
    sphere.fixed = fill.fixed;
    sphere.where = fill.where;
    spheres.push_back(sphere);
  }
  if (fill.count >= kFillInCellOrder) order_by_cells(spheres, spheres.size() - size_t(fill.count), region.lo, 2 * fill.radius_max);
}

void append_body_fill(const FillSpec& fill, CaseSpec& spec) {
  const TemplateSpec& templ = spec.templates.at(size_t(fill.template_index));
  std::mt19937_64 engine(fill.seed);
  auto uniform = [&engine] { return unit_interval(engine()); };
  FillRegion region(fill);
  double bound = bounding_radius(templ.clump);
  double largest_sub = 0;
  for (const Sphere& s : templ.clump.spheres) largest_sub = std::max(largest_sub, s.radius);

  std::vector<SphereSpec> occupied = occupied_spheres(spec);
  std::vector<int> ids;
  SphereGrid grid = grid_near(occupied, region.lo, region.hi, largest_sub * fill.scale_max,
                              size_t(fill.count) * templ.clump.spheres.size(), ids);

  for (int placed = 0; placed < fill.count; ++placed) {
    BodySpec body;
    body.template_index = fill.template_index;
    body.material = fill.material;
    body.velocity = fill.velocity;
    body.fixed = fill.fixed;
    body.where = fill.where;
    body.scale = fill.scale_min;
    if (fill.scale_max > fill.scale_min) body.scale += (fill.scale_max - fill.scale_min) * uniform();
    bool found = false;
    std::vector<SphereSpec> subs;
    for (int attempt = 0; attempt < kFillTriesPerBody && !found; ++attempt) {
      body.orientation = random_orientation(uniform);
      body.position = region.random_point(bound * body.scale, uniform);
      subs = body_spheres(body, templ);
      found = std::all_of(subs.begin(), subs.end(), [&](const SphereSpec& s) {
        return grid.find_overlap(s.position, s.radius) < 0;
      });
    }
    if (!found)
      throw CaseError(fill.where,
                      "only " + std::to_string(placed) + " of the " + std::to_string(fill.count) +
                          " '" + templ.name + "' bodies (count) fit without overlap: body " +
                          std::to_string(placed + 1) + " found no free place in " +
                          std::to_string(kFillTriesPerBody) +
                          " random poses; enlarge the region or lower count");
    for (const SphereSpec& s : subs) grid.insert(s.position, s.radius);
    spec.bodies.push_back(body);
  }
}

void expand_particles(CaseSpec& spec) {
  check_no_overlaps(spec.spheres);
  for (const LatticeSpec& lattice : spec.lattices)
    if (lattice.template_index < 0) append_lattice(lattice, spec.spheres);
  for (const FillSpec& fill : spec.fills)
    if (fill.template_index < 0) append_fill(fill, spec.spheres);
  for (const LatticeSpec& lattice : spec.lattices)
    if (lattice.template_index >= 0) append_body_lattice(lattice, spec);
  for (const FillSpec& fill : spec.fills)
    if (fill.template_index >= 0) append_body_fill(fill, spec);
}

}  // namespace repose
