// The stats verbs of the `repose` binary, end to end: design -> fit -> optimize and curve on
// files in a scratch directory; failures exit non-zero, name file/line/column, and leave no
// output file behind.
#include <catch2/catch.hpp>

#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "stats/csv_table.h"
#include "stats/fit_file.h"
#include "stats/json.h"

using namespace repose::stats;
namespace fs = std::filesystem;

namespace {

struct Scratch {
  fs::path dir;
  Scratch() {
    char tmpl[] = "/tmp/repose-stats-cli-XXXXXX";
    dir = ::mkdtemp(tmpl);
  }
  ~Scratch() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
  std::string path(const std::string& name) const { return (dir / name).string(); }
  void write(const std::string& name, const std::string& text) const { std::ofstream(path(name)) << text; }
  std::string read(const std::string& name) const {
    std::ifstream f(path(name));
    std::ostringstream ss;
    ss << f.rdbuf();
    return ss.str();
  }
  bool exists(const std::string& name) const { return fs::exists(dir / name); }
  bool has_temporaries() const {
    for (const auto& e : fs::directory_iterator(dir))
      if (e.path().filename().string().find(".tmp.") != std::string::npos) return true;
    return false;
  }
};

struct Result {
  int code = -1;
  std::string out, err;
};

Result run_repose(const Scratch& s, const std::string& args) {
  std::string cmd = "cd '" + s.dir.string() + "' && '" + REPOSE_BINARY + "' " + args +
                    " >stdout.txt 2>stderr.txt";
  int status = std::system(cmd.c_str());
  Result r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = s.read("stdout.txt");
  r.err = s.read("stderr.txt");
  INFO(args + "\n--- stdout\n" + r.out + "\n--- stderr\n" + r.err);
  return r;
}

}  // namespace

TEST_CASE("cli: design, fit and optimize round trip", "[stats][cli]") {
  Scratch s;
  const std::string factors = "--factors e:0.40:0.44,mu_s:0.2:0.4,mu_r:0.02:0.04";
  Result d1 = run_repose(s, "design --type ccd " + factors + " --seed 3 --out d1.csv");
  REQUIRE(d1.code == 0);
  CHECK(d1.out.find("20 runs, 8 factorial, 6 axial, 6 centre") != std::string::npos);
  Result d2 = run_repose(s, "design --type ccd " + factors + " --seed 3 --out d2.csv");
  REQUIRE(d2.code == 0);
  Table t1 = read_csv(s.path("d1.csv")), t2 = read_csv(s.path("d2.csv"));
  CHECK(t1.cells == t2.cells);  // same seed, same run order
  CHECK(t1.rows() == 20);

  // A known quadratic (coded units) plus a small deterministic wobble as the response.
  t1.columns.push_back("Y");
  std::vector<double> a = t1.numeric_column("e_coded"), b = t1.numeric_column("mu_s_coded"),
                      c = t1.numeric_column("mu_r_coded");
  for (int i = 0; i < t1.rows(); ++i) {
    double y = 2 + 0.5 * a[i] - b[i] + 0.3 * a[i] * b[i] + 0.8 * b[i] * b[i] + 0.4 * c[i] * c[i] +
               0.01 * ((i * 7) % 5 - 2);
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6f", y);
    t1.cells[i].push_back(buf);
  }
  s.write("runs.csv", format_csv(t1));
  Result fit = run_repose(s, "fit runs.csv --response Y --factors e,mu_s,mu_r --coded 0.40:0.44,0.2:0.4,0.02:0.04 "
                         "--model quadratic --json fit.json");
  REQUIRE(fit.code == 0);
  for (const char* expected : {"Sum of Squares", "Lack of Fit", "Pure Error", "Adeq Precision",
                               "Final equation in terms of actual factors", "wrote fit.json"})
    CHECK(fit.out.find(expected) != std::string::npos);
  SavedFit saved = read_fit_file(s.path("fit.json"));  // reads past the provenance it records
  CHECK(s.read("fit.json").find("\"provenance\"") != std::string::npos);
  CHECK(saved.coded.coefficient(Term{{0, 2, 0}}) == Approx(0.8).margin(0.02));
  CHECK(saved.coded.coefficient(Term{{1, 0, 0}}) == Approx(0.5).margin(0.02));

  Result opt = run_repose(s, "optimize fit.json --minimize --fix e=0.42 --tolerance 0.05 --json opt.json "
                         "--compare mu_s=0.4,mu_r=0.03");
  REQUIRE(opt.code == 0);
  CHECK(opt.out.find("Near-optimal set") != std::string::npos);
  CHECK(opt.out.find("NOT near-optimal") != std::string::npos);
  Json o = Json::parse(s.read("opt.json"), "opt.json");
  // Minimum of the true surface at e = 0.42: B = 1 / 1.6 coded -> mu_s = 0.3625, mu_r = 0.03.
  CHECK(o.at("optimum").items()[0].number() == Approx(0.42));
  CHECK(o.at("optimum").items()[1].number() == Approx(0.3625).margin(0.002));
  CHECK(o.at("optimum").items()[2].number() == Approx(0.03).margin(0.001));
  CHECK(o.at("set_size").number() > 0);
  CHECK_FALSE(s.has_temporaries());

  // Backward reduction keeps hierarchy and reports what it dropped.
  Result red = run_repose(s, "fit runs.csv --response Y --factors e_coded,mu_s_coded,mu_r_coded --model quadratic --reduce 0.05");
  REQUIRE(red.code == 0);
  CHECK(red.out.find("Removed (p > 0.05):") != std::string::npos);

  // Actual columns taken as coded would be a wrong fit (e's effect came out at p = 0.32): refused,
  // with the coded columns and the --coded ranges that would do.
  Result trap = run_repose(s, "fit runs.csv --response Y --factors e,mu_s,mu_r --model quadratic --json never.json");
  CHECK(trap.code != 0);
  CHECK(trap.err.find("are not coded") != std::string::npos);
  CHECK(trap.err.find("--factors e_coded,mu_s_coded,mu_r_coded") != std::string::npos);
  CHECK(trap.err.find("--coded 0.4:0.44,0.2:0.4,0.02:0.04") != std::string::npos);
  CHECK_FALSE(s.exists("never.json"));
  // The coded columns and the actual ones with --coded give the same fit: e is significant.
  Result coded = run_repose(s, "fit runs.csv --response Y --factors e_coded,mu_s_coded,mu_r_coded --model quadratic");
  REQUIRE(coded.code == 0);
  CHECK(coded.out.find("A-e_coded") != std::string::npos);
  CHECK(coded.out.find("< 0.0001") != std::string::npos);
}

TEST_CASE("cli: bad tables and requests fail clearly and write nothing", "[stats][cli]") {
  Scratch s;
  s.write("bad.csv", "# two\n# comments\nA,Y\n1,2\n-1,abc\n0,1\n");
  Result r = run_repose(s, "fit bad.csv --response Y --factors A --model linear --json never.json");
  CHECK(r.code != 0);
  CHECK(r.err.find("bad.csv:5:2: 'abc' in column 'Y' is not a number") != std::string::npos);
  CHECK_FALSE(s.exists("never.json"));

  r = run_repose(s, "fit bad.csv --response Z --factors A --json never.json");
  CHECK(r.code != 0);
  CHECK(r.err.find("bad.csv:3: no column named 'Z'") != std::string::npos);
  CHECK_FALSE(s.exists("never.json"));

  s.write("few.csv", "A,B,Y\n-1,-1,1\n1,-1,2\n-1,1,3\n1,1,4\n");
  r = run_repose(s, "fit few.csv --response Y --factors A,B --model quadratic");
  CHECK(r.code != 0);
  CHECK(r.err.find("fewer runs (4) than model terms (6)") != std::string::npos);

  r = run_repose(s, "design --type ccd --factors e:0.44:0.40,mu_s:0.2:0.4 --out never.csv");
  CHECK(r.code != 0);
  CHECK(r.err.find("range reversed") != std::string::npos);
  CHECK_FALSE(s.exists("never.csv"));

  r = run_repose(s, "design --type pb12 --factors a:0:1 --centre 3 --out pb.csv");
  CHECK(r.code == 0);
  CHECK(read_csv(s.path("pb.csv")).rows() == 15);

  s.write("broken.json", "{\n  \"format\": \"repose-fit/1\",\n  \"response\": 3\n}\n");
  r = run_repose(s, "optimize broken.json --minimize");
  CHECK(r.code != 0);
  CHECK(r.err.find("broken.json:3:15: expected a string") != std::string::npos);

  r = run_repose(s, "design --type nonsense --factors a:0:1");
  CHECK(r.code != 0);
  CHECK_FALSE(s.has_temporaries());
}

TEST_CASE("cli: calibration curve inversion and its refusals", "[stats][cli]") {
  Scratch s;
  std::string sweep = "e,h\n";
  for (int i = 1; i <= 9; ++i) sweep += std::to_string(0.1 * i) + "," + std::to_string(500 * 0.01 * i * i) + "\n";
  s.write("sweep.csv", sweep);
  Result r = run_repose(s, "curve sweep.csv --x e --y h --at 125");
  REQUIRE(r.code == 0);
  CHECK(r.out.find("e = 0.5 at h = 125") != std::string::npos);
  r = run_repose(s, "curve sweep.csv --x e --y h --at 900");
  CHECK(r.code != 0);
  CHECK(r.err.find("sweep.csv: y = 900 lies outside the swept range") != std::string::npos);
  r = run_repose(s, "curve sweep.csv --x e --y missing --at 1");
  CHECK(r.code != 0);
  CHECK(r.err.find("sweep.csv:1: no column named 'missing'") != std::string::npos);
}

TEST_CASE("cli: optimize searches the factorial cube by default, the axial range on request", "[stats][cli]") {
  Scratch s;
  Result d = run_repose(s, "design --type ccd --factors A:-1:1,B:-1:1 --seed 1 --out d.csv");
  REQUIRE(d.code == 0);
  // A bowl whose bottom lies at B = 1.5 coded: outside the cube, inside the axial range (1.414).
  Table t = read_csv(s.path("d.csv"));
  t.columns.push_back("Y");
  std::vector<double> a = t.numeric_column("A_coded"), b = t.numeric_column("B_coded");
  for (int i = 0; i < t.rows(); ++i) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6f", 3 + a[i] * a[i] + (b[i] - 1.3) * (b[i] - 1.3) + 0.001 * (i % 3));
    t.cells[i].push_back(buf);
  }
  s.write("runs.csv", format_csv(t));
  REQUIRE(run_repose(s, "fit runs.csv --response Y --factors A_coded,B_coded --model quadratic --json fit.json").code == 0);
  Result cube = run_repose(s, "optimize fit.json --minimize --json cube.json");
  REQUIRE(cube.code == 0);
  CHECK(cube.out.find("B_coded [-1, 1]") != std::string::npos);
  double b_cube = Json::parse(s.read("cube.json"), "cube.json").at("optimum").items()[1].number();
  CHECK(b_cube == Approx(1.0).margin(1e-3));  // pressed against the cube's face
  Result axial = run_repose(s, "optimize fit.json --minimize --within axial --json axial.json");
  REQUIRE(axial.code == 0);
  double b_axial = Json::parse(s.read("axial.json"), "axial.json").at("optimum").items()[1].number();
  CHECK(b_axial == Approx(1.3).margin(0.01));  // the bowl's bottom, inside +-1.414
}

TEST_CASE("cli: fit --figures and ascent-plot write Design-Expert's views", "[stats][cli]") {
  Scratch s;
  Result fit = run_repose(s, "fit " + std::string(REPOSE_SOURCE_DIR) +
                                 "/tests/stats/data/cotton_table3_pb.csv --response Y --factors A,B,C,D,E,F "
                                 "--model linear --figures views");
  REQUIRE(fit.code == 0);
  for (const char* f : {"views/pareto.png", "views/half_normal.png", "views/surface_3d.png"}) CHECK(s.exists(f));
  s.write("path.csv", "step,angle\n1,13.4\n2,15.3\n2,15.9\n3,17.1\n");
  Result plot = run_repose(s, "ascent-plot path.csv --response angle --target 17.56 --png ascent.png");
  REQUIRE(plot.code == 0);
  CHECK(plot.out.find("step 2: angle = 15.6 (2 runs)") != std::string::npos);
  CHECK(s.exists("ascent.png"));
}
