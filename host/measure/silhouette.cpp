#include "measure/silhouette.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <stb/stb_image.h>

namespace repose {

double horizontal_coordinate(const Sphere& s, ViewAxis view) {
  return view == ViewAxis::Y ? s.centre.x : s.centre.y;
}

BinaryImage render_silhouette(const std::vector<Sphere>& spheres, ViewAxis view, double pixel, double z_floor) {
  if (spheres.empty()) throw std::invalid_argument("render_silhouette: no spheres");
  if (!(pixel > 0) || !std::isfinite(pixel)) throw std::invalid_argument("render_silhouette: pixel size must be positive");
  double u_min = HUGE_VAL, u_max = -HUGE_VAL, z_min = z_floor, z_max = -HUGE_VAL;
  for (const Sphere& s : spheres) {
    const double u = horizontal_coordinate(s, view);
    u_min = std::min(u_min, u - s.radius);
    u_max = std::max(u_max, u + s.radius);
    z_min = std::min(z_min, s.centre.z - s.radius);
    z_max = std::max(z_max, s.centre.z + s.radius);
  }
  constexpr int kMargin = 2;
  BinaryImage image;
  image.pixel = pixel;
  image.origin_u = u_min - kMargin * pixel;
  image.origin_z = z_min - kMargin * pixel;
  const double width = std::ceil((u_max - u_min) / pixel) + 2 * kMargin;
  const double height = std::ceil((z_max - z_min) / pixel) + 2 * kMargin;
  if (width * height > 2.0e8)
    throw std::invalid_argument("render_silhouette: image of " + std::to_string(width) + " x " +
                                std::to_string(height) + " pixels is too large; choose a larger pixel");
  image.width = static_cast<int>(width);
  image.height = static_cast<int>(height);
  image.data.assign(static_cast<size_t>(image.width) * image.height, 0);

  for (const Sphere& s : spheres) {
    const double u = horizontal_coordinate(s, view);
    // Columns whose centre lies within the disc's horizontal extent.
    const int c0 = std::max(0, static_cast<int>(std::ceil((u - s.radius - image.origin_u) / pixel - 0.5)));
    const int c1 = std::min(image.width - 1, static_cast<int>(std::floor((u + s.radius - image.origin_u) / pixel - 0.5)));
    for (int c = c0; c <= c1; ++c) {
      const double du = image.column_centre(c) - u;
      const double half = std::sqrt(std::max(0.0, s.radius * s.radius - du * du));
      const int r0 = std::max(0, static_cast<int>(std::ceil((s.centre.z - half - image.origin_z) / pixel - 0.5)));
      const int r1 = std::min(image.height - 1,
                              static_cast<int>(std::floor((s.centre.z + half - image.origin_z) / pixel - 0.5)));
      for (int r = r0; r <= r1; ++r) image.at(c, r) = 1;
    }
  }
  return image;
}

BinaryImage read_silhouette_png(const std::string& path, double pixel, int threshold, bool light_heap) {
  if (!(pixel > 0) || !std::isfinite(pixel)) throw std::invalid_argument(path + ": the pixel size must be positive");
  int width = 0, height = 0, channels = 0;
  unsigned char* data = stbi_load(path.c_str(), &width, &height, &channels, 1);  // as grey
  if (!data) throw std::runtime_error(path + ": cannot read the picture (" + stbi_failure_reason() + ")");
  BinaryImage image;
  image.width = width;
  image.height = height;
  image.pixel = pixel;
  image.data.assign(size_t(width) * size_t(height), 0);
  for (int row = 0; row < height; ++row)
    for (int col = 0; col < width; ++col) {
      int grey = data[size_t(height - 1 - row) * size_t(width) + size_t(col)];
      image.at(col, row) = (light_heap ? grey >= threshold : grey < threshold) ? 1 : 0;
    }
  stbi_image_free(data);
  return image;
}

double lowest_foreground(const BinaryImage& image) {
  for (int row = 0; row < image.height; ++row)
    for (int col = 0; col < image.width; ++col)
      if (image.at(col, row)) return image.origin_z + row * image.pixel;
  throw std::invalid_argument("heap angle: the silhouette is empty");
}

size_t fill_holes(BinaryImage& image) {
  const int w = image.width, h = image.height;
  std::vector<uint8_t> outside(image.data.size(), 0);
  std::vector<int> stack;
  auto seed = [&](int c, int r) {
    size_t k = static_cast<size_t>(r) * w + c;
    if (!image.data[k] && !outside[k]) {
      outside[k] = 1;
      stack.push_back(static_cast<int>(k));
    }
  };
  for (int c = 0; c < w; ++c) {
    seed(c, 0);
    seed(c, h - 1);
  }
  for (int r = 0; r < h; ++r) {
    seed(0, r);
    seed(w - 1, r);
  }
  while (!stack.empty()) {
    const int k = stack.back();
    stack.pop_back();
    const int c = k % w, r = k / w;
    if (c > 0) seed(c - 1, r);
    if (c + 1 < w) seed(c + 1, r);
    if (r > 0) seed(c, r - 1);
    if (r + 1 < h) seed(c, r + 1);
  }
  size_t filled = 0;
  for (size_t k = 0; k < image.data.size(); ++k)
    if (!image.data[k] && !outside[k]) {
      image.data[k] = 1;
      ++filled;
    }
  return filled;
}

std::vector<uint8_t> outer_boundary(const BinaryImage& image) {
  const int w = image.width, h = image.height;
  std::vector<uint8_t> boundary(image.data.size(), 0);
  auto background = [&](int c, int r) { return c < 0 || r < 0 || c >= w || r >= h || !image.at(c, r); };
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c)
      if (image.at(c, r) &&
          (background(c - 1, r) || background(c + 1, r) || background(c, r - 1) || background(c, r + 1)))
        boundary[static_cast<size_t>(r) * w + c] = 1;
  return boundary;
}

std::vector<int> top_profile(const BinaryImage& image) {
  std::vector<int> profile(static_cast<size_t>(image.width), -1);
  for (int c = 0; c < image.width; ++c)
    for (int r = image.height - 1; r >= 0; --r)
      if (image.at(c, r)) {
        profile[static_cast<size_t>(c)] = r;
        break;
      }
  return profile;
}

}  // namespace repose
