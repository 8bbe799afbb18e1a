#include "measure/heap_png.h"

#include <stb/stb_image_write.h>

#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace repose {
namespace {

using Rgb = std::array<uint8_t, 3>;

class Canvas {
 public:
  Canvas(int width, int height) : width_(width), height_(height), pixels_(static_cast<size_t>(width) * height * 3, 255) {}

  // Row 0 is the image's bottom row (z up); PNG rows go top-down, so rows are flipped here.
  void set(int column, int row, Rgb colour) {
    if (column < 0 || row < 0 || column >= width_ || row >= height_) return;
    size_t k = (static_cast<size_t>(height_ - 1 - row) * width_ + column) * 3;
    pixels_[k] = colour[0];
    pixels_[k + 1] = colour[1];
    pixels_[k + 2] = colour[2];
  }

  // A thick segment between two points in pixel coordinates, sampled at quarter-pixel steps.
  void segment(double c0, double r0, double c1, double r1, Rgb colour, int half_thickness) {
    const double steps = std::ceil(4.0 * std::max(std::abs(c1 - c0), std::abs(r1 - r0))) + 1;
    for (int i = 0; i <= static_cast<int>(steps); ++i) {
      const double t = i / steps;
      const int c = static_cast<int>(std::floor(c0 + t * (c1 - c0)));
      const int r = static_cast<int>(std::floor(r0 + t * (r1 - r0)));
      for (int dc = -half_thickness; dc <= half_thickness; ++dc)
        for (int dr = -half_thickness; dr <= half_thickness; ++dr) set(c + dc, r + dr, colour);
    }
  }

  void save(const std::string& path) const {
    if (!stbi_write_png(path.c_str(), width_, height_, 3, pixels_.data(), width_ * 3))
      throw std::runtime_error(path + ": cannot write PNG");
  }

 private:
  int width_, height_;
  std::vector<uint8_t> pixels_;
};

}  // namespace

void write_heap_angle_png(const std::string& path, const HeapAngle& m) {
  const BinaryImage& image = m.image;
  Canvas canvas(image.width, image.height);
  const std::vector<uint8_t> boundary = outer_boundary(image);
  for (int r = 0; r < image.height; ++r)
    for (int c = 0; c < image.width; ++c) {
      const size_t k = static_cast<size_t>(r) * image.width + c;
      if (boundary[k]) canvas.set(c, r, {0, 0, 0});
      else if (image.data[k]) canvas.set(c, r, {200, 200, 200});
    }
  const int thickness = image.width / 1600;  // half-thickness in pixels: 0 up to 1600 px wide
  auto to_column = [&](double u) { return (u - image.origin_u) / image.pixel; };
  auto to_row = [&](double z) { return (z - image.origin_z) / image.pixel; };
  const double floor_row = to_row(m.floor_z);
  canvas.segment(0, floor_row, image.width - 1, floor_row, {0, 160, 0}, 0);

  // Each fitted line is drawn from the floor to the crest height, like the seeds' figures; the
  // boundary points that entered the fit are drawn on top, so crest and toe show as excluded.
  auto draw_fit = [&](const SlopeFit& fit, Rgb colour) {
    if (!fit.valid || fit.line.slope == 0) return;
    const double top_z = m.floor_z + m.heap_height;
    const double u_floor = (m.floor_z - fit.line.intercept) / fit.line.slope;
    const double u_top = (top_z - fit.line.intercept) / fit.line.slope;
    canvas.segment(to_column(u_floor), floor_row, to_column(u_top), to_row(top_z), colour, thickness);
  };
  draw_fit(m.left, {220, 0, 0});
  draw_fit(m.right, {0, 60, 220});
  for (int c = 0; c < image.width; ++c)
    if (m.fitted_columns[static_cast<size_t>(c)] && m.profile[static_cast<size_t>(c)] >= 0)
      canvas.set(c, m.profile[static_cast<size_t>(c)], {255, 140, 0});
  canvas.save(path);
}

}  // namespace repose
