// Angle of repose of a settled heap, measured the way both seeds did it from a photograph:
// front view -> binary image -> hole filling -> outer boundary -> straight-line fit of each
// slope with the crest and the toe left out. For axisymmetric heaps (bottomless-cylinder test)
// also a 3D fit: surface height by radial bins in angular sectors, one line per sector.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "geometry/sphere.h"
#include "measure/line_fit.h"
#include "measure/silhouette.h"

namespace repose {

struct SlopeFit {
  bool valid = false;
  std::string problem;     // why not valid
  double angle_deg = 0.0;  // atan(|rise| / run), positive for a slope falling away from the crest
  LineFit line;            // height z (m) against the horizontal coordinate (m)
  double from = 0.0, to = 0.0;  // horizontal range of the fitted points, m
};

struct HeapAngleOptions {
  ViewAxis view = ViewAxis::Y;
  double pixel = 0.0;             // m; 0: the longest extent of the heap / 1600
  double band_low = 0.10;         // fit only boundary points between these fractions of the
  double band_high = 0.80;        // heap height above the floor (drops the toe and the crest)
  std::optional<double> floor_z;  // default: the lowest sphere bottom
  // The picture's columns before this horizontal coordinate (m) are hidden, as the front wall of
  // an opaque box hides the bodies it holds: the crest and slopes are found in what is left.
  std::optional<double> visible_from;
};

struct HeapAngle {
  SlopeFit left, right;       // left: smaller horizontal coordinate than the crest
  double mean_deg = 0.0;      // mean of the valid sides (NaN if none)
  double floor_z = 0.0;
  double heap_height = 0.0;   // top of the profile above the floor, m
  double crest = 0.0;         // horizontal coordinate of the crest, m
  size_t holes_filled = 0;    // pixels
  BinaryImage image;          // after hole filling
  std::vector<int> profile;   // top row per column (-1: empty)
  std::vector<uint8_t> fitted_columns;  // 1 = left-slope point, 2 = right-slope point
  std::optional<double> visible_from;   // the options': columns before it were hidden
};

// The 2D measurement. Each slope uses the columns that are contiguous with the crest (a body
// that rolled away does not count) and whose top lies within the band. A slope with fewer than
// three such columns is reported as not valid. Throws std::invalid_argument for an empty heap or
// inconsistent options.
HeapAngle measure_heap_angle(const std::vector<Sphere>& spheres, const HeapAngleOptions& options = {});

// The lowest sphere bottom, z (m): a heap's floor when none is given.
double lowest_bottom(const std::vector<Sphere>& spheres);

// The same measurement of a silhouette already in pixels (a thresholded photograph,
// read_silhouette_png): hole filling, top profile, crest, slope fits. floor_z in the image's
// coordinates (m); options' view, pixel and floor are not used. Throws std::invalid_argument for an
// empty silhouette or one whose top is not above the floor.
HeapAngle measure_heap_image(BinaryImage image, double floor_z, const HeapAngleOptions& options = {});

// The heap's vertical axis: volume-weighted medians of the sphere centres' x and y.
glm::dvec2 heap_centre(const std::vector<Sphere>& spheres);

struct AxisymmetricOptions {
  int sectors = 8;
  double bin_width = 0.0;         // m; 0: the heap's largest radius / 25
  double band_low = 0.10, band_high = 0.80;
  std::optional<double> floor_z;
  std::optional<glm::dvec2> centre;  // default: volume-weighted medians of x and y
};

struct SectorFit {
  double from_deg = 0.0, to_deg = 0.0;  // azimuth range, degrees from +x towards +y
  SlopeFit fit;                          // height against radius
};

struct AxisymmetricHeapAngle {
  glm::dvec2 centre{0.0};
  double floor_z = 0.0, heap_height = 0.0;
  std::vector<SectorFit> sectors;
  int valid_sectors = 0;
  double mean_deg = 0.0;    // over valid sectors (NaN if none)
  double spread_deg = 0.0;  // sample standard deviation over valid sectors (0 for one)
  double min_deg = 0.0, max_deg = 0.0;
};

// The 3D fit. In each sector, the surface height of a radial bin is the highest sphere top
// (z + r) among the spheres whose centre falls in it, taken at that sphere's radius. Bins are
// used outward from the centre until two consecutive bins are empty (stragglers beyond a gap do
// not count), and only those whose height lies within the band.
AxisymmetricHeapAngle measure_axisymmetric_heap_angle(const std::vector<Sphere>& spheres,
                                                      const AxisymmetricOptions& options = {});

// "mean 25.31 deg, spread 1.20 deg over 7 of 8 sectors", or why no sector counted ("no sector
// gave a slope (sector 0-45 deg: only 2 boundary points in the height band)"): never a NaN.
std::string describe_sector_fit(const AxisymmetricHeapAngle& fit);

}  // namespace repose
