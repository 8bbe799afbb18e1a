// Small PNG charts for campaign reports (stb_image_write, text by stb_easy_font): axes with
// ticks and labels, lines, markers, bands, and filled response maps with contour lines.
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace repose::calibrate {

using Colour = std::array<uint8_t, 3>;
namespace colours {
inline constexpr Colour black{0, 0, 0}, grey{150, 150, 150}, light{225, 225, 225}, red{215, 40, 40},
    blue{40, 90, 200}, green{30, 150, 60}, orange{235, 140, 20}, purple{130, 60, 170};
const std::vector<Colour>& series();  // distinct colours for several lines
}  // namespace colours

class Chart {
 public:
  // A chart of `width` x `height` pixels showing [x0, x1] x [y0, y1] (ranges may be equal:
  // they are widened).
  Chart(int width, int height, double x0, double x1, double y0, double y1);

  void title(const std::string& text);
  void labels(const std::string& x_label, const std::string& y_label);
  // Filled map of f over the plot area (blue low .. red high) with contour lines at `levels`
  // (grey) and at `highlight` (thick, black).
  void response_map(const std::function<double(double, double)>& f, const std::vector<double>& levels,
                    const std::vector<double>& highlight);
  void polyline(const std::vector<double>& x, const std::vector<double>& y, Colour c, int thickness = 1);
  void band(const std::vector<double>& x, const std::vector<double>& low, const std::vector<double>& high, Colour c);
  void horizontal(double y, Colour c, int thickness = 1);
  void horizontal_band(double y_low, double y_high, Colour c);
  void vertical(double x, Colour c, int thickness = 1);
  void marker(double x, double y, Colour c, int radius = 4);
  void cross(double x, double y, Colour c, int size = 8);
  void legend(const std::vector<std::pair<std::string, Colour>>& entries);
  void text_at(double x, double y, const std::string& text, Colour c);  // data coordinates
  // Draws the frame and tick labels last so they sit on top; throws naming the path on failure.
  void save(const std::string& path);

 private:
  double px(double x) const;
  double py(double y) const;
  void set(int c, int r, Colour colour);
  void blend(int c, int r, Colour colour, double alpha);
  void segment(double c0, double r0, double c1, double r1, Colour colour, int thickness);
  void text(double c, double r, const std::string& s, Colour colour, double scale);
  double text_width(const std::string& s, double scale) const;

  int w_, h_;
  double x0_, x1_, y0_, y1_;
  int left_ = 90, right_ = 20, top_ = 56, bottom_ = 60;
  std::string title_, x_label_, y_label_;
  std::vector<uint8_t> pixels_;
};

}  // namespace repose::calibrate
