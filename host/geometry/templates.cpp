#include "geometry/templates.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <stdexcept>

#include "util/math.h"

namespace repose {
namespace {

double radians(double degrees) { return degrees * kPi / 180.0; }

ClumpTemplate translated_copies(const std::string& name, const ClumpTemplate& body,
                                const std::vector<glm::dvec3>& offsets) {
  ClumpTemplate group;
  group.name = name;
  for (const glm::dvec3& offset : offsets)
    for (const Sphere& s : body.spheres) group.spheres.push_back({s.centre + offset, s.radius});
  return group;
}

}  // namespace

ClumpTemplate cotton_stalk(const CottonStalkSpec& spec) {
  if (spec.layers < 2 || spec.spheres_per_layer < 1 || !(spec.sphere_radius > 0) ||
      !(spec.hull_diameter > 2 * spec.sphere_radius) || !(spec.hull_length > 2 * spec.sphere_radius))
    throw std::invalid_argument("cotton_stalk: inconsistent specification");
  ClumpTemplate stalk;
  stalk.name = "cotton_stalk";
  const double ring_radius = 0.5 * spec.hull_diameter - spec.sphere_radius;
  const double pitch = (spec.hull_length - 2 * spec.sphere_radius) / (spec.layers - 1);
  const double first_z = -0.5 * (spec.layers - 1) * pitch;
  for (int layer = 0; layer < spec.layers; ++layer) {
    const double z = first_z + layer * pitch;
    for (int k = 0; k < spec.spheres_per_layer; ++k) {
      // Angles in degrees first, reduced mod 360 so that equal angles give bit-equal positions.
      const double degrees = std::fmod(360.0 * k / spec.spheres_per_layer + spec.layer_rotation_deg * layer, 360.0);
      const double a = radians(degrees);
      stalk.spheres.push_back({{ring_radius * std::cos(a), ring_radius * std::sin(a), z}, spec.sphere_radius});
    }
  }
  return stalk;
}

CottonStalkSpec coarse_cotton_stalk_spec() {
  CottonStalkSpec spec;
  spec.layers = 16;
  spec.spheres_per_layer = 3;
  spec.sphere_radius = 2.5e-3;
  spec.layer_rotation_deg = 60.0;
  return spec;
}

ClumpTemplate cotton_stalk_group2(const ClumpTemplate& stalk) {
  double x_extent = 0;  // largest x reached by the stalk's surface
  for (const Sphere& s : stalk.spheres) x_extent = std::max(x_extent, s.centre.x + s.radius);
  return translated_copies(stalk.name + "_group2", stalk, {{-x_extent, 0, 0}, {x_extent, 0, 0}});
}

ClumpTemplate cabbage(const CabbageSpec& spec) {
  if (spec.veins < 1 || spec.spheres_per_vein < 2 || !(spec.core_diameter > 0))
    throw std::invalid_argument("cabbage: inconsistent specification");
  ClumpTemplate head;
  head.name = "cabbage";
  const double core_radius = 0.5 * spec.core_diameter;
  head.spheres.push_back({{0, 0, 0}, core_radius});

  for (int vein = 0; vein < spec.veins; ++vein) {
    const double azimuth = radians(360.0 * vein / spec.veins);
    for (int i = 0; i < spec.spheres_per_vein; ++i) {
      const double t = static_cast<double>(i) / (spec.spheres_per_vein - 1);  // 0 at the stem
      const double polar = radians(spec.vein_start_polar_deg +
                                   t * (spec.vein_end_polar_deg - spec.vein_start_polar_deg));
      const double radius = spec.vein_radius_at_stem + t * (spec.vein_radius_at_tip - spec.vein_radius_at_stem);
      const double protrusion = spec.protrusion_at_stem + t * (spec.protrusion_at_tip - spec.protrusion_at_stem);
      // The sphere's outermost point lies `protrusion` beyond the core surface.
      const double distance = core_radius + protrusion - radius;
      const glm::dvec3 direction(std::sin(polar) * std::cos(azimuth), std::sin(polar) * std::sin(azimuth),
                                 std::cos(polar));
      head.spheres.push_back({distance * direction, radius});
    }
  }
  const double stem_distance = core_radius + spec.stem_protrusion - spec.stem_radius;
  head.spheres.push_back({{0, 0, -stem_distance}, spec.stem_radius});
  const double cut_distance = core_radius + spec.stem_cut_protrusion - spec.stem_cut_radius;
  head.spheres.push_back({{0, 0, -cut_distance}, spec.stem_cut_radius});
  return head;
}

ClumpTemplate cabbage_group4(const ClumpTemplate& head) {
  double half_spacing = 0;  // the head's reach along +x and +y: neighbours then just touch
  for (const Sphere& s : head.spheres)
    half_spacing = std::max({half_spacing, s.centre.x + s.radius, s.centre.y + s.radius});
  const double h = half_spacing;
  return translated_copies(head.name + "_group4", head,
                           {{-h, -h, 0}, {h, -h, 0}, {-h, h, 0}, {h, h, 0}});
}

const std::vector<ShippedTemplate>& shipped_templates() {
  static const std::vector<ShippedTemplate> list = {
      {"cabbage", "cabbage study: 160 mm core sphere + leaf veins and stem, 203 sub-spheres",
       [] { return cabbage(); }},
      {"cabbage_group4", "cabbage study's sliding test: four cabbages bonded in a 2x2 square, 812 sub-spheres",
       [] { return cabbage_group4(cabbage()); }},
      {"cotton_stalk", "cotton-stalk study: 40 layers x 18 spheres r=1 mm, 10 mm x 80 mm, 720 sub-spheres",
       [] { return cotton_stalk(); }},
      {"cotton_stalk_group2", "cotton-stalk study's sliding test: two stalks side by side, 1440 sub-spheres",
       [] { return cotton_stalk_group2(cotton_stalk()); }},
      {"cotton_stalk_coarse", "coarse stalk for CPU runs: 16 layers x 3 spheres r=2.5 mm, same hull, 48 sub-spheres",
       [] {
         ClumpTemplate t = cotton_stalk(coarse_cotton_stalk_spec());
         t.name = "cotton_stalk_coarse";
         return t;
       }},
  };
  return list;
}

ClumpTemplate make_shipped_template(const std::string& name) {
  std::string known;
  for (const auto& t : shipped_templates()) {
    if (t.name == name) return t.make();
    known += (known.empty() ? "" : ", ") + t.name;
  }
  throw std::invalid_argument("unknown template '" + name + "' (known: " + known + ")");
}

}  // namespace repose
