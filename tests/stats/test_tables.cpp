// Bad input gives a typed exception whose message names file, line and column: missing
// column, non-numeric or empty cell, ragged row, unknown factor, reversed range, fewer runs
// than model terms, malformed fit files.
#include <catch2/catch.hpp>

#include "stats/anova.h"
#include "stats/csv_table.h"
#include "stats/dataset.h"
#include "stats/errors.h"
#include "stats/fit_file.h"
#include "stats/json.h"
#include "stats/model_terms.h"

using namespace repose::stats;

namespace {

const char* kTable =
    "# a comment line, skipped\n"
    "Run,A,B,Y,Note\n"
    "1,-1,-1,3.5,first\n"
    "\n"
    "2,1,-1,4.25,\"with, comma\"\n"
    "3,-1,1,x5,third\n"
    "4,1,1,,fourth\n";

}  // namespace

TEST_CASE("CSV: comments, blank lines, quoted cells and line numbers", "[stats][table]") {
  Table t = parse_csv(kTable, "runs.csv");
  CHECK(t.header_line == 2);
  CHECK(t.rows() == 4);
  CHECK(t.row_lines == std::vector<int>{3, 5, 6, 7});
  CHECK(t.cells[1][4] == "with, comma");
  CHECK(t.numeric_column("A") == std::vector<double>{-1, 1, -1, 1});
  // Round trip through the writer.
  Table back = parse_csv(format_csv(t, {"note"}), "again.csv");
  CHECK(back.cells == t.cells);
}

TEST_CASE("CSV: a non-numeric cell names file, line and column", "[stats][table]") {
  Table t = parse_csv(kTable, "runs.csv");
  try {
    t.numeric_column("Y");
    FAIL("expected a TableError");
  } catch (const TableError& e) {
    CHECK(e.file() == "runs.csv");
    CHECK(e.line() == 6);
    CHECK(e.column() == 4);
    CHECK(std::string(e.what()) == "runs.csv:6:4: 'x5' in column 'Y' is not a number");
  }
}

TEST_CASE("CSV: empty cell, missing column, ragged row, unreadable file", "[stats][table]") {
  Table t = parse_csv("A,Y\n1,2\n3,\n", "t.csv");
  CHECK_THROWS_WITH(t.numeric_column("Y"), "t.csv:3:2: empty cell in column 'Y'");
  CHECK_THROWS_WITH(t.numeric_column("Z"), "t.csv:1: no column named 'Z' (columns: A, Y)");
  CHECK_THROWS_AS(parse_csv("A,Y\n1,2,3\n", "r.csv"), TableError);
  CHECK_THROWS_WITH(parse_csv("A,Y\n1,2,3\n", "r.csv"), Catch::Contains("r.csv:2: row has 3 cells, header has 2"));
  CHECK_THROWS_WITH(parse_csv("A,A\n", "d.csv"), Catch::Contains("duplicate column 'A'"));
  CHECK_THROWS_WITH(parse_csv("# only a comment\n", "e.csv"), Catch::Contains("no header"));
  CHECK_THROWS_WITH(parse_csv("A,\"Y\n", "q.csv"), Catch::Contains("q.csv:1:3: unterminated"));
  CHECK_THROWS_AS(read_csv("/nonexistent/table.csv"), TableError);
}

TEST_CASE("data sets: unknown factor, reversed range, response listed as a factor", "[stats][table]") {
  Table t = parse_csv("A,B,Y\n-1,-1,1\n1,-1,2\n-1,1,3\n1,1,5\n0,0,2.5\n", "d.csv");
  CHECK_THROWS_AS(dataset_from_table(t, {"A", "C"}, "Y"), TableError);
  CHECK_THROWS_WITH(dataset_from_table(t, {"A", "C"}, "Y"), Catch::Contains("no column named 'C'"));
  CHECK_THROWS_WITH(dataset_from_table(t, {"A", "B"}, "W"), Catch::Contains("d.csv:1: no column named 'W'"));
  CHECK_THROWS_AS(dataset_from_table(t, {"A", "B"}, "Y", {{"A", 1, 0}, {"B", 0, 1}}), DesignError);
  CHECK_THROWS_WITH(dataset_from_table(t, {"A", "B"}, "Y", {{"A", 1, 0}, {"B", 0, 1}}),
                    Catch::Contains("range reversed"));
  CHECK_THROWS_WITH(dataset_from_table(t, {"A", "Y"}, "Y"), Catch::Contains("both a factor and the response"));
  DataSet d = dataset_from_table(t, {"A", "B"}, "Y", {{"A", -1, 1}, {"B", 0, 2}});
  CHECK(d.coded(1, 1) == -2);  // actual -1 coded with 0..2
}

TEST_CASE("models: fewer runs than terms is refused with the counts", "[stats][table]") {
  Table t = parse_csv("A,B,Y\n-1,-1,1\n1,-1,2\n-1,1,3\n1,1,5\n0,0,2.5\n", "d.csv");
  DataSet d = dataset_from_table(t, {"A", "B"}, "Y");
  CHECK_THROWS_AS(analyse(d.coded, d.y, build_model(ModelKind::quadratic, 2)), ModelError);
  CHECK_THROWS_WITH(analyse(d.coded, d.y, build_model(ModelKind::quadratic, 2)),
                    Catch::Contains("fewer runs (5) than model terms (6)"));
  // The interaction model fits (4 terms, 5 runs) and has no pure error (no replicates).
  ResponseSurface rs = analyse(d.coded, d.y, build_model(ModelKind::interaction, 2));
  CHECK(rs.residual.df == 1);
  CHECK_FALSE(rs.lack_of_fit.has_value());
  CHECK(rs.coef[0] == Approx(2.7));
}

TEST_CASE("fit files: malformed JSON and missing keys name line and column", "[stats][table]") {
  CHECK_THROWS_WITH(Json::parse("{\n  \"a\": [1, 2,\n}", "f.json"), Catch::Contains("f.json:3:1:"));
  CHECK_THROWS_WITH(Json::parse("{\"a\": tru}", "f.json"), Catch::Contains("f.json:1:7: unexpected character"));
  Json j = Json::parse("{\n \"format\": \"repose-fit/1\",\n \"response\": \"Y\"\n}", "fit.json");
  CHECK_THROWS_WITH(saved_fit_from_json(j), Catch::Contains("fit.json:1:1: missing key 'factors'"));
  Json wrong = Json::parse("{\"format\": \"something\"}", "w.json");
  CHECK_THROWS_WITH(saved_fit_from_json(wrong), Catch::Contains("not a repose fit file"));
  Json num = Json::parse("{\"x\": \"3\"}", "n.json");
  CHECK_THROWS_WITH(num.at("x").number(), Catch::Contains("n.json:1:7: expected a number, found a string"));
  // Round trip of numbers keeps every bit.
  Json o = Json::object();
  o.set("v", 0.1 + 0.2);
  CHECK(Json::parse(o.dump(), "rt.json").at("v").number() == 0.1 + 0.2);
}

TEST_CASE("fit files: a fit written and read back evaluates identically", "[stats][table]") {
  Table t = parse_csv("A,B,Y\n-1,-1,1\n1,-1,2\n-1,1,3\n1,1,5\n0,0,2.5\n0,0,2.7\n", "d.csv");
  DataSet d = dataset_from_table(t, {"A", "B"}, "Y");
  d.ranges = {{"A", 0.2, 0.4}, {"B", 10, 20}};
  ResponseSurface rs = analyse(d.coded, d.y, build_model(ModelKind::interaction, 2));
  Json j = fit_to_json(rs, d, "d.csv", "interaction", {});
  SavedFit s = saved_fit_from_json(Json::parse(j.dump(), "fit.json"));
  CHECK(s.factor_names == std::vector<std::string>{"A", "B"});
  CHECK(s.ranges[1].high == 20);
  Eigen::VectorXd x(2);
  x << 0.3, -0.7;
  CHECK(s.coded(x) == rs.predict(x));
  CHECK(s.y_min == 1);
  CHECK(s.y_max == 5);
  CHECK(s.coded_min[0] == -1);
}
