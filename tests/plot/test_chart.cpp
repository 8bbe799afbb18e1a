// The shared chart: lines stay inside the plot area, the response map has a colour bar that runs
// from its lowest to its highest value, and a picture keeps one unit of x as long as one of y.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>

#include "plot/chart.h"

using namespace repose;

namespace {

// Saves `chart` as a PNG in the temporary folder and returns what it recorded (records are kept).
ChartRecord saved_record(Chart& chart, const std::string& name) {
  std::string path = (std::filesystem::temp_directory_path() / name).string();
  chart.save(path);
  return Chart::recorded(path);
}

}  // namespace

TEST_CASE("chart lines are clipped to the plot area", "[plot]") {
  Chart chart(600, 400, 0, 1, 0, 1);
  // A line from far left-below to far right-above, and one entirely outside.
  chart.polyline({-5, 6}, {-3, 4}, colours::red, 3);
  chart.polyline({2, 3}, {2, 3}, colours::blue, 3);
  chart.vertical(0.5, colours::green, 1);
  auto [left, top, right, bottom] = chart.plot_area();
  int inside = 0;
  for (int r = 0; r < 400; ++r)
    for (int c = 0; c < 600; ++c) {
      Colour p = chart.pixel(c, r);
      bool in = c >= left - 1 && c <= right + 1 && r >= top - 1 && r <= bottom + 1;
      if (p == colours::red || p == colours::blue) {
        INFO("pixel " << c << "," << r);
        CHECK(in);
        inside += in;
      }
    }
  CHECK(inside > 100);  // the first line was drawn where it crosses the plot
}

TEST_CASE("a response map's colour bar spans its values, low at the bottom", "[plot]") {
  Chart chart(700, 500, 0, 1, 0, 1, true);
  chart.response_map([](double x, double y) { return 10 + 5 * x + y; }, {}, {});
  auto [left, top, right, bottom] = chart.plot_area();
  CHECK(700 - right >= 130);  // room kept for the bar
  std::string path = (std::filesystem::temp_directory_path() / "repose_test_chart.png").string();
  chart.save(path);
  // The bar's column, just right of the plot: bluish at the bottom, reddish at the top.
  Colour low = chart.pixel(right + 34, bottom - 2), high = chart.pixel(right + 34, top + 2);
  CHECK(low[2] > low[0]);
  CHECK(high[0] > high[2]);
  // The map itself: its lowest value (x = 0, y = 0) blue, its highest (1, 1) red.
  CHECK(chart.pixel(left + 1, bottom - 1)[2] > chart.pixel(left + 1, bottom - 1)[0]);
  CHECK(chart.pixel(right - 1, top + 1)[0] > chart.pixel(right - 1, top + 1)[2]);
  CHECK(std::filesystem::file_size(path) > 1000);
  std::filesystem::remove(path);
}

TEST_CASE("a picture at equal scale keeps its aspect and fits the size asked", "[plot]") {
  for (auto [w, h] : {std::pair{0.4, 0.13}, {0.1, 0.17}}) {
    Chart chart = Chart::equal_scale(1400, 1000, 0, w, 0, h);
    auto [left, top, right, bottom] = chart.plot_area();
    INFO(w << " x " << h << " m: plot " << right - left << " x " << bottom - top << " px");
    CHECK(double(bottom - top) / double(right - left) == Approx(h / w).epsilon(0.01));
    CHECK(right - left <= 1400);
    CHECK(bottom - top <= 1000);
  }
}

namespace {

// How many pixels of the rectangle [col0, col1) x [row0, row1) have the colour (a legend's sample).
int pixels_of(const Chart& chart, Colour colour, int col0, int col1, int row0, int row1) {
  int n = 0;
  for (int row = row0; row < row1; ++row)
    for (int col = col0; col < col1; ++col) n += chart.pixel(col, row) == colour;
  return n;
}

}  // namespace

TEST_CASE("tick labels tell neighbours apart however narrow the range", "[plot]") {
  Chart chart(600, 400, 0, 1, 0.44001, 0.44019);
  chart.save((std::filesystem::temp_directory_path() / "repose_test_ticks.png").string());
  const auto& y = chart.record().y_ticks;
  REQUIRE(y.size() >= 3);
  for (size_t i = 1; i < y.size(); ++i) CHECK(y[i] != y[i - 1]);
  CHECK(y.front().rfind("0.4400", 0) == 0);
  CHECK(tick_labels({0, 0.2, 0.4}) == std::vector<std::string>{"0", "0.2", "0.4"});
}

TEST_CASE("among corners free of data the legend takes the one clear of bands and reference lines", "[plot]") {
  Chart::keep_records();
  Chart chart(600, 400, 0, 1, 0, 1);
  // A measured band across the top and a chosen value's line on the right: of the four empty
  // corners only the bottom left is clear of both.
  chart.horizontal_band(0.85, 0.95, colours::green);
  chart.horizontal(0.9, colours::green);
  chart.vertical(0.8, colours::red);
  chart.marker(0.5, 0.5, colours::black);
  chart.legend({{"runs", colours::black, Mark::Dot}, {"measured", colours::green}, {"chosen", colours::red}});
  ChartRecord r = saved_record(chart, "repose_test_legend_bands.png");
  CHECK_FALSE(r.legend_covers_data);
  CHECK_FALSE(r.legend_covers_reference);
  auto [left, top, right, bottom] = chart.plot_area();
  CHECK(pixels_of(chart, colours::black, left + 5, left + 60, bottom - 80, bottom) > 20);  // the "runs" sample
}

TEST_CASE("the legend keeps clear of a model's band where the data leave it a choice", "[plot]") {
  Chart::keep_records();
  Chart chart(600, 400, 0, 1, 0, 1);
  // A calibration curve's +-2 sd band rises from the bottom left to the top right, wide at both
  // ends; the only points sit mid-plot, so all four corners are free of data and the top left
  // and bottom right are the ones clear of the band.
  std::vector<double> x, low, high;
  for (int i = 0; i <= 20; ++i) {
    x.push_back(0.05 * i);
    low.push_back(0.05 * i - 0.25);
    high.push_back(0.05 * i + 0.25);
  }
  chart.band(x, low, high, colours::blue);
  chart.marker(0.5, 0.5, colours::black);
  chart.legend({{"runs", colours::black, Mark::Dot}, {"model +- 2 sd", colours::blue, Mark::Band}});
  ChartRecord r = saved_record(chart, "repose_test_legend_model_band.png");
  CHECK_FALSE(r.legend_covers_data);
  CHECK_FALSE(r.legend_covers_reference);
  auto [left, top, right, bottom] = chart.plot_area();
  CHECK(pixels_of(chart, colours::black, left + 5, left + 60, top + 3, top + 80) > 20);  // the "runs" sample, top left
  CHECK(pixels_of(chart, colours::black, right - 200, right - 3, top + 3, top + 80) == 0);  // none over the band
}

TEST_CASE("the legend keeps clear of error bars as of points", "[plot]") {
  Chart::keep_records();
  Chart chart(600, 400, 0, 1, 0, 1);
  // Points crowd the left corners; the top right holds only the upper end of an error bar whose
  // point sits mid-height, so the bottom right is the corner free of data.
  for (int i = 0; i < 10; ++i) {
    chart.marker(0.05 + 0.02 * i, 0.95 - 0.01 * i, colours::blue);
    chart.marker(0.05 + 0.02 * i, 0.05 + 0.01 * i, colours::blue);
  }
  chart.marker(0.95, 0.5, colours::red);
  chart.error_bar(0.95, 0.4, 0.98, colours::red);
  chart.legend({{"runs", colours::blue, Mark::Dot}, {"mean +- se", colours::red, Mark::Dot}});
  CHECK_FALSE(saved_record(chart, "repose_test_legend_bars.png").legend_covers_data);
  auto [left, top, right, bottom] = chart.plot_area();
  CHECK(pixels_of(chart, colours::blue, right - 200, right, bottom - 80, bottom) > 20);  // the "runs" sample
}

TEST_CASE("the legend takes the corner free of data, and records what each entry shows", "[plot]") {
  Chart::keep_records();
  Chart chart(600, 400, 0, 1, 0, 1);
  // Points crowd the top right and top left; the bottom right stays empty.
  for (int i = 0; i < 10; ++i) {
    chart.marker(0.75 + 0.02 * i, 0.95 - 0.01 * i, colours::red);
    chart.square(0.05 + 0.02 * i, 0.95 - 0.01 * i, colours::blue);
  }
  chart.polyline({0, 0.3}, {0, 0.3}, colours::green);
  chart.legend({{"runs", colours::red, Mark::Dot}, {"chosen", colours::blue, Mark::Square}, {"fit", colours::green}});
  ChartRecord r = saved_record(chart, "repose_test_legend.png");
  CHECK_FALSE(r.legend_covers_data);
  REQUIRE(r.legend.size() == 3);
  CHECK(r.points_of(colours::red, Mark::Dot) == 10);
  CHECK(r.points_of(colours::blue, Mark::Square) == 10);
  CHECK(r.points_of(colours::green, Mark::Line) == 2);
  CHECK(r.points_of(colours::red, Mark::Line) == 0);
  // The legend box is white-ish in the bottom right: the dot sample of "runs" is red there.
  auto [left, top, right, bottom] = chart.plot_area();
  CHECK(pixels_of(chart, colours::red, right - 200, right, bottom - 80, bottom) > 20);
}
