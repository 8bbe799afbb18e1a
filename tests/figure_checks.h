// What every figure must show, read back from its chart's record (plot/chart.h): a title and axis
// labels, tick labels that differ from their neighbours, a legend entry for each series it lists
// that was really drawn (its colour and mark among the data points), and a legend that hides no
// data point. Shared by the test folders whose code saves figures.
#pragma once
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "plot/chart.h"

namespace repose::test {

inline void check_ticks(const std::vector<std::string>& ticks, const char* axis) {
  INFO(axis << " ticks");
  CHECK(ticks.size() >= 2);
  for (size_t k = 1; k < ticks.size(); ++k) {
    INFO(ticks[k - 1] << " | " << ticks[k]);
    CHECK(ticks[k] != ticks[k - 1]);
  }
}

// `series`: the legend labels the figure must have, each drawn.
inline void check_figure(const ChartRecord& r, const std::vector<std::string>& series) {
  INFO("figure '" << r.title << "'");
  CHECK(!r.title.empty());
  CHECK(!r.x_label.empty());
  CHECK(!r.y_label.empty());
  check_ticks(r.x_ticks, "x");
  check_ticks(r.y_ticks, "y");
  for (const LegendEntry& e : r.legend) {
    INFO("legend entry '" << e.label << "'");
    CHECK(!e.label.empty());
    CHECK(r.points_of(e.colour, e.mark) > 0);
  }
  for (const std::string& label : series) {
    bool listed = false;
    for (const LegendEntry& e : r.legend) listed = listed || e.label == label;
    INFO("series '" << label << "'");
    CHECK(listed);
  }
  CHECK(!r.legend_covers_data);
}

}  // namespace repose::test
