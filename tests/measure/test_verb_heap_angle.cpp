// `repose heap-angle` on a heap written as CSV: text, JSON and PNG outputs, and its errors.
#include <catch2/catch.hpp>

#include "tests/cli_support.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <sys/wait.h>

#include "geometry/sphere_csv.h"
#include "synthetic_heaps.h"

#include <stb/stb_image_write.h>
#include <vector>

namespace {

using Run = repose::test::CliRun;
Run run(const std::string& arguments) { return repose::test::run_repose(arguments); }

// The number printed right after `label` in text.
double number_after(const std::string& text, const std::string& label) {
  const size_t at = text.find(label);
  REQUIRE(at != std::string::npos);
  return std::stod(text.substr(at + label.size()));
}

std::string temp(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("repose_verbs_" + name)).string();
}

}  // namespace

TEST_CASE("repose heap-angle measures a cone and writes JSON and PNG", "[verbs]") {
  const std::string csv = temp("cone.csv"), json = temp("cone.json"), png = temp("cone.png");
  repose::write_sphere_csv(csv, repose::test::cone_shell(0.2, 28.0, 0.005));
  std::filesystem::remove(json);
  std::filesystem::remove(png);
  const Run r = run("heap-angle " + csv + " --view x --png " + png + " --json " + json + " --axisymmetric");
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK(std::abs(number_after(r.output, "mean angle") - 28.0) < 0.5);
  CHECK_THAT(r.output, Catch::Contains("8 of 8 sectors"));
  CHECK(std::filesystem::file_size(png) > 1000);
  std::ifstream in(json);
  std::stringstream text;
  text << in.rdbuf();
  const nlohmann::json j = nlohmann::json::parse(text.str());
  CHECK(std::abs(j["mean_deg"].get<double>() - 28.0) < 0.5);
  CHECK(j["axisymmetric"].is_object());
}

TEST_CASE("repose heap-angle errors name the file and exit non-zero", "[verbs]") {
  const std::string bad = temp("bad_heap.csv");
  std::ofstream(bad) << "x,y,z,radius\n0,0,0,0.01\n1,2\n";
  Run r = run("heap-angle " + bad);
  CHECK(r.status != 0);
  CHECK_THAT(r.output, Catch::Contains(bad + ":3:4: expected 4 fields as in the header, found 2"));
  r = run("heap-angle " + bad + " --view z");
  CHECK(r.status != 0);
  r = run("heap-angle /nonexistent/heap.csv");
  CHECK(r.status != 0);
  CHECK_THAT(r.output, Catch::Contains("/nonexistent/heap.csv: cannot open file"));
}

TEST_CASE("repose heap-angle measures a photograph's silhouette (PNG) at the given pixel size", "[verbs]") {
  // A dark heap on a light background, as a thresholded photo: 0.5 mm pixels, a 40 mm wide
  // plateau-free ridge rising at 35 deg on the left and falling at 25 deg on the right, 60 mm
  // high, on a 5 mm dark floor strip spanning the picture (the table edge, cut off by --floor).
  const double pixel = 5e-4, height = 0.06;
  const int w = 800, h = 200, floor_rows = 10;
  const double left = height / std::tan(35.0 * M_PI / 180), right = height / std::tan(25.0 * M_PI / 180);
  const double crest_u = 0.03 + left;
  std::vector<unsigned char> grey(size_t(w) * h, 255);
  for (int row = 0; row < h; ++row)      // PNG rows run downwards
    for (int col = 0; col < w; ++col) {
      double u = (col + 0.5) * pixel, z = (h - row - 0.5) * pixel - floor_rows * pixel;
      double top = u < crest_u ? height - (crest_u - u) * height / left : height - (u - crest_u) * height / right;
      if (z < 0 || z < top) grey[size_t(row) * w + col] = 20;
    }
  const std::string png = temp("photo.png");
  REQUIRE(stbi_write_png(png.c_str(), w, h, 1, grey.data(), w));
  Run r = run("heap-angle " + png + " --pixel 0.0005 --floor 0.005 --json " + temp("photo.json"));
  INFO(r.output);
  REQUIRE(r.status == 0);
  // One-pixel steps over a 60 mm slope: the fitted angles within 0.3 deg.
  CHECK(std::abs(number_after(r.output, "left slope") - 35.0) < 0.3);
  CHECK(std::abs(number_after(r.output, "right slope") - 25.0) < 0.3);
  CHECK_THAT(r.output, Catch::Contains("photograph"));
  // Without the pixel size the picture has no scale: refused.
  r = run("heap-angle " + png);
  CHECK(r.status != 0);
  CHECK_THAT(r.output, Catch::Contains("needs --pixel"));
}

TEST_CASE("repose heap-angle re-measures several saved heaps: their spread and its causes", "[verbs]") {
  // Three smooth cones of 26, 30 and 34 deg: the spread is all heap to heap (sd 4 deg).
  std::string files;
  for (double slope : {26.0, 30.0, 34.0}) {
    const std::string csv = temp("cone_" + std::to_string(int(slope)) + ".csv");
    repose::write_sphere_csv(csv, repose::test::cone_shell(0.1, slope, 0.004));
    files += " " + csv;
  }
  Run r = run("heap-angle" + files + " --views 4");
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.output, Catch::Contains("over 3 heaps (side both"));
  CHECK(std::abs(number_after(r.output, "front view (one photograph)        mean") - 30.0) < 0.5);
  CHECK(std::abs(number_after(r.output, "any one view                       sd") - 4.0) < 0.3);
  CHECK(std::abs(number_after(r.output, "packing (heap to heap)") - 4.0) < 0.3);
  CHECK(number_after(r.output, "line fit on a few bodies") < 0.3);
  r = run("heap-angle" + files + " --png " + temp("several.png"));
  CHECK(r.status == 2);
  CHECK_THAT(r.output, Catch::Contains("take one heap"));
  // A picture has no spheres to turn: refused, naming it.
  const std::string png = temp("not_a_heap.png");
  r = run("heap-angle" + files + " " + png);
  CHECK(r.status != 0);
  CHECK_THAT(r.output, Catch::Contains(png + ": several heaps are re-measured from their spheres"));
}
