// Front-view silhouettes of sphere sets, as a camera with a long lens sees a settled heap:
// orthographic projection along a horizontal axis, z up, one bit per pixel.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "geometry/sphere.h"

namespace repose {

// The camera looks along +y (horizontal image axis u = x) or along +x (u = y); z is up.
enum class ViewAxis { X, Y };

struct BinaryImage {
  int width = 0, height = 0;
  double pixel = 0.0;                  // edge of a square pixel, m
  double origin_u = 0.0, origin_z = 0.0;  // lower-left corner of pixel (0, 0), m
  std::vector<uint8_t> data;           // row-major, row 0 at the bottom; 1 = foreground

  uint8_t at(int column, int row) const { return data[static_cast<size_t>(row) * width + column]; }
  uint8_t& at(int column, int row) { return data[static_cast<size_t>(row) * width + column]; }
  double column_centre(int column) const { return origin_u + (column + 0.5) * pixel; }
  double row_top(int row) const { return origin_z + (row + 1) * pixel; }
};

double horizontal_coordinate(const Sphere& s, ViewAxis view);

// Renders the spheres' silhouette: a pixel is foreground when its centre lies inside a sphere's
// projected disc. The image spans the projected spheres and z_floor (whichever is lower) with a
// two-pixel background margin all round, so the background outside the heap is connected.
BinaryImage render_silhouette(const std::vector<Sphere>& spheres, ViewAxis view, double pixel, double z_floor);

// A photograph's silhouette, already thresholded by the user or thresholded here: a PNG (any
// channels) whose pixels darker than `threshold` (0-255, luminance) are the heap, or lighter with
// `light_heap`. `pixel` is the size of one pixel in m (from a scale in the photograph). The image's
// bottom-left corner is (u, z) = (0, 0): PNG rows run downwards, so they are flipped. Throws
// std::runtime_error naming the file when it cannot be read.
BinaryImage read_silhouette_png(const std::string& path, double pixel, int threshold = 128, bool light_heap = false);

// The lowest foreground row's bottom edge, z (m): a photograph's floor when none is given.
// Throws std::invalid_argument for an empty image.
double lowest_foreground(const BinaryImage& image);

// Fills holes: background pixels that cannot be reached from the image border through
// 4-connected background (MATLAB's imfill(BW, 'holes') with its default 2D connectivity).
// Returns the number of pixels filled.
size_t fill_holes(BinaryImage& image);

// Outer boundary: foreground pixels with a 4-neighbour in the background (after fill_holes this
// is the outline that bwboundaries traces). Same size as the image; 1 on the boundary.
std::vector<uint8_t> outer_boundary(const BinaryImage& image);

// Top profile: for each column, the highest foreground row, or -1 for an empty column.
std::vector<int> top_profile(const BinaryImage& image);

}  // namespace repose
