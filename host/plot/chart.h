// Small PNG charts for reports and measurements (stb_image_write; text by stb_easy_font, scaled
// to stay legible): axes with ticks and labels (the y label written upwards), lines clipped to
// the plot area, markers, bands, filled response maps with contour lines and a colour bar, and
// raster pictures placed in data coordinates (a heap's silhouette).
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace repose {

using Colour = std::array<uint8_t, 3>;
namespace colours {
inline constexpr Colour white{255, 255, 255}, black{0, 0, 0}, grey{150, 150, 150}, light{225, 225, 225},
    red{215, 40, 40}, blue{40, 90, 200}, green{30, 150, 60}, orange{235, 140, 20}, purple{130, 60, 170};
const std::vector<Colour>& series();  // distinct colours for several lines
}  // namespace colours

// How a legend entry shows its series: as the line, the dot, the square or the cross drawn for it,
// as a shaded band, or as a filled polygon (a bar).
enum class Mark { Line, Dot, Square, Cross, Band, Bar };
struct LegendEntry {
  std::string label;
  Colour colour;
  Mark mark = Mark::Line;
};

// What a saved chart shows, as text and counts: tests read it back to catch a repeated tick label,
// a legend entry without its series, or a series drawn outside the plot.
struct ChartRecord {
  std::string title, subtitle, x_label, y_label;
  std::vector<std::string> x_ticks, y_ticks, bar_ticks;  // as printed
  std::string z_label;                  // a 3D picture's vertical axis (its ticks in z_ticks)
  std::vector<std::string> z_ticks;
  std::vector<LegendEntry> legend;
  // Data points drawn inside the plot area, by colour and mark (a polyline's vertices count as Line).
  std::vector<std::pair<LegendEntry, int>> points;
  int points_of(Colour c, Mark m) const;  // 0 when none
  bool legend_covers_data = false;        // the legend box hides a data point
  bool legend_covers_reference = false;   // ... or part of a reference line or band
};

class Chart {
 public:
  // A chart of `width` x `height` pixels showing [x0, x1] x [y0, y1] (ranges may be equal: they
  // are widened). `colour_bar` keeps room on the right for the response map's colour bar.
  Chart(int width, int height, double x0, double x1, double y0, double y1, bool colour_bar = false);
  // A picture: one unit of x as long as one of y, as large as fits in max_width x max_height.
  static Chart equal_scale(int max_width, int max_height, double x0, double x1, double y0, double y1);

  void title(const std::string& text);
  void subtitle(const std::string& text);  // a second line under the title (a measured value)
  void labels(const std::string& x_label, const std::string& y_label);
  // Filled map of f over the plot area (blue low .. red high) with contour lines at `levels`
  // (grey) and at `highlight` (thick, black); with colour_bar, the bar with its values and label.
  void response_map(const std::function<double(double, double)>& f, const std::vector<double>& levels,
                    const std::vector<double>& highlight, const std::string& bar_label = "");
  // A raster in data coordinates: cell (c, r) covers [x0 + c cell, x0 + (c+1) cell] x [y0 + r cell, ..]
  // (row 0 at the bottom); `colour` gives a cell's colour, or nothing to leave it.
  void raster(int columns, int rows, double x0, double y0, double cell,
              const std::function<std::optional<Colour>(int column, int row)>& colour);
  // Lines are clipped to the plot area.
  void polyline(const std::vector<double>& x, const std::vector<double>& y, Colour c, int thickness = 1);
  void band(const std::vector<double>& x, const std::vector<double>& low, const std::vector<double>& high, Colour c);
  void horizontal(double y, Colour c, int thickness = 1);
  void horizontal_band(double y_low, double y_high, Colour c);
  void vertical(double x, Colour c, int thickness = 1);
  void marker(double x, double y, Colour c, int radius = 4);
  void square(double x, double y, Colour c, int half = 3);
  void error_bar(double x, double y_low, double y_high, Colour c);
  void cross(double x, double y, Colour c, int size = 8);
  // A filled polygon in data coordinates (a bar, a facet of a 3D surface), its edge drawn in
  // `edge`; counted as one data point of `mark` at its centre.
  void polygon(const std::vector<double>& x, const std::vector<double>& y, Colour fill, Colour edge,
               Mark mark = Mark::Bar);
  // A picture whose axes the caller draws itself (a 3D surface): no frame, ticks or axis labels
  // at save (labels() still names them in the record); the record takes the ticks the caller
  // printed.
  void hide_axes(std::vector<std::string> x_ticks, std::vector<std::string> y_ticks, std::string z_label,
                 std::vector<std::string> z_ticks);
  // Inside the plot, in the corner that hides the fewest data points (drawn last, on top).
  void legend(const std::vector<LegendEntry>& entries);
  void legend_above(const std::vector<LegendEntry>& entries);  // in a row under the title
  void text_at(double x, double y, const std::string& text, Colour c);  // data coordinates
  // Draws the frame, ticks and texts last so they sit on top; throws naming the path on failure.
  void save(const std::string& path);

  // For tests: the plot area in pixels (left, top, right, bottom) and a pixel's colour.
  std::array<int, 4> plot_area() const;
  Colour pixel(int column, int row) const;
  // What the chart shows (complete after save).
  const ChartRecord& record() const { return record_; }
  // Keeps the record of every chart saved from now on in this process, by path (for tests of code
  // that draws and saves its own figures); recorded(path) then gives it, or throws.
  static void keep_records();
  static ChartRecord recorded(const std::string& path);

 private:
  double px(double x) const;
  double py(double y) const;
  void set(int c, int r, Colour colour);
  void blend(int c, int r, Colour colour, double alpha);
  void segment(double c0, double r0, double c1, double r1, Colour colour, int thickness);
  void clipped_segment(double c0, double r0, double c1, double r1, Colour colour, int thickness);
  void text(double c, double r, const std::string& s, Colour colour, double scale, bool upwards = false);
  double text_width(const std::string& s, double scale) const;
  void draw_colour_bar();
  void count_point(double c, double r, Colour colour, Mark mark);
  void draw_legend_box();
  void draw_legend_mark(double c, double r, const LegendEntry& e);

  int w_, h_;
  double x0_, x1_, y0_, y1_;
  int left_ = 130, right_ = 30, top_ = 76, bottom_ = 74;
  bool colour_bar_ = false;
  bool axes_ = true;
  double bar_lo_ = 0, bar_hi_ = 0;
  std::string bar_label_;
  std::string title_, subtitle_, x_label_, y_label_;
  std::vector<uint8_t> pixels_;
  std::vector<LegendEntry> box_legend_;           // drawn at save, where it hides the least
  std::vector<std::array<int, 2>> data_pixels_;  // where data points were drawn (legend placement)
  // Rows and columns that reference lines and bands cross edge to edge ({first, last} pixel): the
  // legend avoids them where the data leave it a choice.
  std::vector<std::array<int, 2>> reference_rows_, reference_cols_;
  std::vector<std::array<int, 3>> band_columns_;  // a model band's {column, first row, last row}
  double reference_overlap(double c, double r, double box_w, double box_h) const;
  ChartRecord record_;
};

// Ticks at 1, 2 or 5 times a power of ten within [lo, hi], about `target` of them.
std::vector<double> nice_ticks(double lo, double hi, int target = 6);
// Tick labels for `ticks`, with as many digits as it takes to tell neighbours apart.
std::vector<std::string> tick_labels(const std::vector<double>& ticks);

}  // namespace repose
