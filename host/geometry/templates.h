// The clump templates shipped in cases/templates/, generated here so that their geometry is
// documented by code (cases/templates/README.md explains the choices and the resulting mass
// properties). All in metres, template frame; the long axis of a stalk and the stem-to-crown
// axis of a cabbage are z.
#pragma once
#include <string>
#include <vector>

#include "geometry/clump.h"

namespace repose {

// Cotton stalk of the cotton-stalk study: 40 layers of 18 spheres of radius 1 mm. The study's hull is
// 10 mm x 80 mm, so the layer ring radius is 5 - 1 = 4 mm and the layer pitch is
// (80 - 2*1) / (40 - 1) = 2 mm (adjacent layers touch). Neighbours in a ring are 20 degrees
// apart, so the study's 30 degrees between layers staggers each layer by half a pitch
// (30 mod 20 = 10): a closed, hollow, bumpy tube, centred at the origin.
struct CottonStalkSpec {
  int layers = 40;
  int spheres_per_layer = 18;
  double sphere_radius = 1.0e-3;
  double hull_diameter = 10.0e-3;
  double hull_length = 80.0e-3;
  double layer_rotation_deg = 30.0;
};
ClumpTemplate cotton_stalk(const CottonStalkSpec& spec = {});

// Coarse stalk for CPU-only runs: the same 10 mm x 80 mm hull from 16 layers of 3 spheres of
// radius 2.5 mm (ring radius 2.5 mm, pitch 5 mm, 60 degrees between layers = half a ring pitch,
// the fine model's staggering rule): 48 spheres instead of 720, a 2.5x longer Rayleigh step.
CottonStalkSpec coarse_cotton_stalk_spec();

// The sliding test's group: two parallel stalks side by side along x, hulls touching.
ClumpTemplate cotton_stalk_group2(const ClumpTemplate& stalk);

// Cabbage of the cabbage study: a 160 mm core sphere and 202 sub-spheres of leaf veins and stem
// (203 in all). Eight meridian veins (midribs of the outer leaves, every 45 degrees of azimuth)
// run from the stem (the -z pole) over the head, each of 25 overlapping spheres whose radius
// tapers from 12 mm near the stem to 5 mm at the tip while their protrusion beyond the core
// tapers from 4 mm to 2 mm; the polar angle goes from 160 degrees (near the stem) to 30 degrees.
// A short stem of two spheres (radius 15 mm and 10 mm, protruding 5 and 6 mm) closes the -z pole.
struct CabbageSpec {
  double core_diameter = 0.160;
  int veins = 8;
  int spheres_per_vein = 25;
  double vein_start_polar_deg = 160.0;  // polar angle from +z, near the stem
  double vein_end_polar_deg = 30.0;
  double vein_radius_at_stem = 12.0e-3;
  double vein_radius_at_tip = 5.0e-3;
  double protrusion_at_stem = 4.0e-3;  // beyond the core surface
  double protrusion_at_tip = 2.0e-3;
  double stem_radius = 15.0e-3, stem_protrusion = 5.0e-3;
  double stem_cut_radius = 10.0e-3, stem_cut_protrusion = 6.0e-3;
};
ClumpTemplate cabbage(const CabbageSpec& spec = {});

// The sliding test's group: four cabbages, stems down, in a 2x2 square whose spacing makes the
// facing equatorial veins of neighbours touch.
ClumpTemplate cabbage_group4(const ClumpTemplate& cabbage);

struct ShippedTemplate {
  std::string name;     // also the CSV file name in cases/templates/ without ".csv"
  std::string summary;
  ClumpTemplate (*make)();
};
const std::vector<ShippedTemplate>& shipped_templates();

// Throws std::invalid_argument listing the known names when name is not one of them.
ClumpTemplate make_shipped_template(const std::string& name);

}  // namespace repose
