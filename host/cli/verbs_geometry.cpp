// `repose template`, `repose clump`, `repose stl`, `repose heap-angle`: particle shapes, wall
// meshes and the angle-of-repose measurement (host/geometry, host/measure) from the command
// line. Input errors name the file, line and column; main() prints them and exits non-zero.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cli/cli_checks.h"
#include "cli/verbs.h"
#include "io/provenance.h"
#include "util/atomic_file.h"
#include "experiments/repose.h"
#include "geometry/clump.h"
#include "geometry/sphere_csv.h"
#include "geometry/stl.h"
#include "geometry/stl_shapes.h"
#include "geometry/templates.h"
#include "measure/bed_height.h"
#include "measure/heap_angle.h"
#include "measure/heap_grains.h"
#include "measure/heap_json.h"
#include "measure/heap_profile.h"
#include "measure/heap_views.h"
#include "measure/heap_png.h"
#include "measure/heap_scatter.h"

namespace repose::cli {

namespace {

constexpr double kDefaultDensity = 1000.0;

using Json = nlohmann::ordered_json;

Json vec3_json(const glm::dvec3& v) { return Json::array({v.x, v.y, v.z}); }

// Row-major: rows[a][b] = m[b][a] in glm's column-major storage.
Json mat3_rows_json(const glm::dmat3& m) {
  Json rows = Json::array();
  for (int row = 0; row < 3; ++row) rows.push_back(vec3_json(glm::dvec3(m[0][row], m[1][row], m[2][row])));
  return rows;
}

Json clump_json(const std::string& file, const ClumpTemplate& clump, double density, const MassProperties& p) {
  Json j;
  j["file"] = file;
  j["sub_spheres"] = clump.spheres.size();
  j["explicit"] = p.is_explicit;
  if (!p.is_explicit) j["density"] = density;
  j["volume"] = p.volume;
  j["mass"] = p.mass;
  j["centre_of_mass"] = vec3_json(p.centre_of_mass);
  j["inertia"] = mat3_rows_json(p.inertia);
  j["principal_moments"] = vec3_json(p.principal_moments);
  j["principal_axes"] = Json::array();
  for (int k = 0; k < 3; ++k) j["principal_axes"].push_back(vec3_json(p.principal_axes[k]));
  return j;
}

Json mesh_json(const std::string& file, const StlFile& stl, const MeshSummary& s) {
  Json j;
  j["file"] = file;
  j["format"] = stl.binary ? "binary" : "ascii";
  j["solid"] = stl.solid_name;
  j["triangles_in_file"] = stl.triangles_in_file;
  j["triangles"] = s.triangle_count;
  j["vertices"] = s.vertex_count;
  j["degenerate"] = Json::array();
  for (const auto& d : stl.degenerate) {
    Json row;
    row["triangle"] = d.index;
    if (d.line) row["line"] = d.line;
    row["reason"] = d.reason;
    j["degenerate"].push_back(row);
  }
  j["lower"] = vec3_json(s.lower);
  j["upper"] = vec3_json(s.upper);
  j["area"] = s.area;
  j["watertight"] = s.watertight;
  j["boundary_edges"] = s.boundary_edges;
  j["non_manifold_edges"] = s.non_manifold_edges;
  j["misoriented_edges"] = s.misoriented_edges;
  if (s.watertight) j["volume"] = s.volume;
  return j;
}

// ---------------------------------------------------------------------------------------
int run_template(int argc, char** argv) {
  CLI::App app{"Write a shipped clump template (sphere centres and radii, metres) as CSV."};
  std::string name, out;
  bool list = false;
  app.add_option("name", name, "template name (see --list)");
  app.add_option("--out", out, "CSV file to write (x,y,z,radius)")->check(non_empty_path());
  app.add_flag("--list", list, "list the shipped templates");
  REPOSE_PARSE(app, argc, argv);
  if (list) {
    for (const ShippedTemplate& t : shipped_templates()) std::printf("%-22s %s\n", t.name.c_str(), t.summary.c_str());
    return 0;
  }
  if (name.empty() || out.empty()) {
    std::fprintf(stderr, "repose template: give a NAME and --out FILE.csv (or --list)\n");
    return 2;
  }
  const ClumpTemplate clump = make_shipped_template(name);
  write_sphere_csv(out, clump.spheres);
  std::printf("wrote %s: %zu sub-spheres to %s\n", name.c_str(), clump.spheres.size(), out.c_str());
  return 0;
}

// ---------------------------------------------------------------------------------------
int run_clump(int argc, char** argv) {
  CLI::App app{"Mass properties of a clump (multi-sphere body) from a CSV of sub-spheres."};
  std::string file, principal_out;
  double density = kDefaultDensity;
  bool json = false;
  std::optional<double> mass;
  std::vector<double> com, inertia;
  UnionIntegration integration;
  app.add_option("file", file, "CSV with x,y,z,radius columns (metres)")->required();
  app.add_option("--density", density, "kg/m^3, applied to the union volume (default 1000)")->check(finite_positive());
  app.add_flag("--json", json, "print JSON instead of text");
  app.add_option("--depth", integration.refine_depth,
                 "edge refinement depth of the integration (default 4: ~1e-5 relative; 6: ~1e-6)");
  app.add_option("--principal-out", principal_out,
                 "write the template re-expressed in its principal frame to this CSV");
  app.add_option("--mass", mass, "explicit mass, kg (with --com and --inertia, as EDEM allows)")->check(finite_positive());
  app.add_option("--com", com, "explicit centre of mass x,y,z (m)")->expected(3)->delimiter(',');
  app.add_option("--inertia", inertia, "explicit inertia Ixx,Iyy,Izz,Ixy,Ixz,Iyz about the centre of mass (kg m^2)")
      ->expected(6)
      ->delimiter(',');
  REPOSE_PARSE(app, argc, argv);

  ClumpTemplate clump;
  clump.name = file;
  clump.spheres = read_sphere_csv(file);
  const bool any_explicit = mass || !com.empty() || !inertia.empty();
  if (any_explicit) {
    if (!mass || com.size() != 3 || inertia.size() != 6)
      throw std::invalid_argument("explicit properties need all of --mass, --com x,y,z and --inertia (6 values)");
    ExplicitMassProperties e;
    e.mass = *mass;
    e.centre_of_mass = {com[0], com[1], com[2]};
    e.inertia[0][0] = inertia[0];
    e.inertia[1][1] = inertia[1];
    e.inertia[2][2] = inertia[2];
    e.inertia[0][1] = e.inertia[1][0] = inertia[3];
    e.inertia[0][2] = e.inertia[2][0] = inertia[4];
    e.inertia[1][2] = e.inertia[2][1] = inertia[5];
    clump.explicit_properties = e;
  }
  const MassProperties p = compute_mass_properties(clump, density, integration);
  if (!principal_out.empty()) write_sphere_csv(principal_out, to_principal_frame(clump, p).clump.spheres);

  if (json) {
    std::printf("%s\n", clump_json(file, clump, density, p).dump(2).c_str());
    return 0;
  }
  std::printf("clump %s: %zu sub-spheres\n", file.c_str(), clump.spheres.size());
  if (p.is_explicit)
    std::printf("mass properties given explicitly (density unused)\n");
  else
    std::printf("density %.6g kg/m^3 on the union volume (overlaps counted once)\n", density);
  std::printf("volume             %.9e m^3\n", p.volume);
  std::printf("mass               %.9e kg\n", p.mass);
  std::printf("centre of mass     % .9e % .9e % .9e m\n", p.centre_of_mass.x, p.centre_of_mass.y, p.centre_of_mass.z);
  std::printf("inertia tensor about the centre of mass, kg m^2:\n");
  for (int row = 0; row < 3; ++row)
    std::printf("                   % .9e % .9e % .9e\n", p.inertia[0][row], p.inertia[1][row], p.inertia[2][row]);
  std::printf("principal moments  % .9e % .9e % .9e kg m^2\n", p.principal_moments[0], p.principal_moments[1],
              p.principal_moments[2]);
  for (int k = 0; k < 3; ++k)
    std::printf("principal axis %d   % .9f % .9f % .9f\n", k + 1, p.principal_axes[k].x, p.principal_axes[k].y,
                p.principal_axes[k].z);
  if (!principal_out.empty()) std::printf("principal-frame template written to %s\n", principal_out.c_str());
  return 0;
}

// ---------------------------------------------------------------------------------------
int run_stl(int argc, char** argv) {
  CLI::App app{"Read an STL mesh (ASCII or binary) and report its size, bounds, area and closure."};
  std::string file;
  bool json = false;
  app.add_option("file", file, "STL file")->required();
  app.add_flag("--json", json, "print JSON instead of text");
  REPOSE_PARSE(app, argc, argv);

  const StlFile stl = read_stl(file);
  const MeshSummary s = summarize_mesh(stl.mesh);
  if (json) {
    std::printf("%s\n", mesh_json(file, stl, s).dump(2).c_str());
    return 0;
  }
  std::printf("stl %s: %s, solid '%s'\n", file.c_str(), stl.binary ? "binary" : "ASCII", stl.solid_name.c_str());
  std::printf("triangles    %zu (%zu in the file)\n", s.triangle_count, stl.triangles_in_file);
  std::printf("vertices     %zu (after merging equal corners)\n", s.vertex_count);
  for (size_t i = 0; i < stl.degenerate.size() && i < 10; ++i) {
    const auto& d = stl.degenerate[i];
    std::printf("degenerate   triangle %zu%s: %s (dropped)\n", d.index,
                d.line ? (" at line " + std::to_string(d.line)).c_str() : "", d.reason.c_str());
  }
  if (stl.degenerate.size() > 10) std::printf("degenerate   ... %zu in all\n", stl.degenerate.size());
  std::printf("bounds       [% .6g, % .6g] x [% .6g, % .6g] x [% .6g, % .6g]\n", s.lower.x, s.upper.x, s.lower.y,
              s.upper.y, s.lower.z, s.upper.z);
  std::printf("area         %.9g\n", s.area);
  if (s.watertight)
    std::printf("watertight   yes (closed, consistently oriented), enclosed volume %.9g\n", s.volume);
  else
    std::printf("watertight   no: %zu boundary, %zu non-manifold, %zu misoriented edges\n", s.boundary_edges,
                s.non_manifold_edges, s.misoriented_edges);
  return 0;
}

// ---------------------------------------------------------------------------------------
std::string slope_text(const SlopeFit& f, const char* coordinate) {
  char buf[256];
  if (!f.valid) return "not measured: " + f.problem;
  std::snprintf(buf, sizeof buf, "%7.3f deg  (%zu points, %s from %.4g to %.4g m, R^2 %.4f)", f.angle_deg,
                f.line.points, coordinate, f.from, f.to, f.line.r_squared);
  return buf;
}

std::string profile_text(const SlopeProfile& p, const char* coordinate) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "run-out %.4g m (toe at %s = %.4g m), convexity ", p.runout, coordinate, p.toe);
  if (!p.valid) return buf + ("not measured: " + p.problem);
  char c[64];
  std::snprintf(c, sizeof c, "%+.3f (%zu columns)", p.convexity, p.points);
  return buf + std::string(c);
}

// What `repose heap-angle` measured on one input: a sphere CSV or a PNG silhouette.
struct HeapAngleRun {
  std::string file, view;
  bool photo = false;
  std::vector<Sphere> spheres;
  HeapAngleOptions options;
  HeapAngle m;
  HeapProfile profile;
  std::optional<double> bed;  // a sphere CSV's bed height
  size_t apart = 0;           // with --resting-only: the spheres left out
  std::optional<HeapViewsAngle> around;
  std::optional<AxisymmetricHeapAngle> axisymmetric;
};

void print_heap_text(const HeapAngleRun& r) {
  const HeapAngle& m = r.m;
  if (r.photo)
    std::printf("heap %s: photograph, pixel %.4g mm (%d x %d px), floor z = %.6g m\n", r.file.c_str(), m.image.pixel * 1e3,
                m.image.width, m.image.height, m.floor_z);
  else
    std::printf("heap %s: %zu spheres, camera along %s, pixel %.4g mm (%d x %d px), floor z = %.6g m\n", r.file.c_str(),
                r.spheres.size(), r.view.c_str(), m.image.pixel * 1e3, m.image.width, m.image.height, m.floor_z);
  if (r.apart) std::printf("left out     %zu spheres apart from the heap (not resting on the floor)\n", r.apart);
  const char* horizontal = r.photo ? "u" : r.options.view == ViewAxis::Y ? "x" : "y";
  std::printf("height       %.6g m, crest at %s = %.6g m, %zu hole pixels filled, fit band %g-%g of the height\n",
              m.heap_height, horizontal, m.crest, m.holes_filled, r.options.band_low, r.options.band_high);
  std::printf("left slope   %s\n", slope_text(m.left, horizontal).c_str());
  std::printf("right slope  %s\n", slope_text(m.right, horizontal).c_str());
  std::printf("mean angle   %7.3f deg\n", m.mean_deg);
  std::printf("left shape   %s\n", profile_text(r.profile.left, horizontal).c_str());
  std::printf("right shape  %s\n", profile_text(r.profile.right, horizontal).c_str());
  if (r.bed)
    std::printf("bed height   %.6g m (twice the spheres' volume-weighted mean height above the floor: of a bed, "
                "before the lift)\n", *r.bed);
  if (const auto& v = r.around) {
    std::printf("%zu views     about (%.6g, %.6g) m: %s\n", v->azimuth_deg.size(), v->centre.x, v->centre.y,
                describe_views(*v).c_str());
    for (size_t k = 0; k < v->azimuth_deg.size(); ++k)
      std::printf("  view %5.1f deg  left %7.3f  right %7.3f\n", v->azimuth_deg[k], v->left_deg[k], v->right_deg[k]);
  }
  if (const auto& a = r.axisymmetric) {
    std::printf("3D fit       centre (%.6g, %.6g) m: %s", a->centre.x, a->centre.y, describe_sector_fit(*a).c_str());
    if (a->valid_sectors > 0) std::printf(", range %.3f-%.3f deg", a->min_deg, a->max_deg);
    std::printf("\n");
    for (const SectorFit& s : a->sectors)
      std::printf("  sector %5.1f-%5.1f deg  %s\n", s.from_deg, s.to_deg, slope_text(s.fit, "r").c_str());
  }
}

// Heap-angle results as JSON: the front view and its profile, then the bed, the other views and
// the 3D sectors when measured.
Json heap_angle_json(const HeapAngleRun& r) {
  const HeapAngle& m = r.m;
  Json j;
  j["file"] = r.file;
  j["spheres"] = r.spheres.size();
  j["spheres_apart"] = r.apart;
  j["photograph"] = r.photo;
  j["view"] = r.view;
  j["pixel"] = m.image.pixel;
  j["floor_z"] = m.floor_z;
  j["heap_height"] = m.heap_height;
  j["crest"] = m.crest;
  j["band_low"] = r.options.band_low;
  j["band_high"] = r.options.band_high;
  j["left"] = slope_json(m.left);
  j["right"] = slope_json(m.right);
  j["mean_deg"] = m.mean_deg;
  j["left_profile"] = profile_json(r.profile.left);
  j["right_profile"] = profile_json(r.profile.right);
  if (r.bed) j["bed_height"] = *r.bed;
  if (r.around) j["views"] = views_json(*r.around);
  if (r.axisymmetric) j["axisymmetric"] = axisymmetric_json(*r.axisymmetric);
  j["provenance"] = version_json();
  j["provenance"]["input_fnv1a"] = file_fnv1a(r.file);
  return j;
}

// The diagnosis measures of one side as measured-data rows (measure,value): what a user copies
// into the data CSV next to the case, the condition and the replicate.
void print_measure_rows(const HeapAngleRun& r, const std::string& side) {
  const SlopeFit& fit = side == "left" ? r.m.left : r.m.right;
  if (side != "both" && !fit.valid) throw std::runtime_error(r.file + ": no " + side + " slope: " + fit.problem);
  if (side == "both" && !std::isfinite(r.m.mean_deg)) throw std::runtime_error(r.file + ": the heap has no measurable slope");
  double angle = side == "both" ? r.m.mean_deg : fit.angle_deg;
  std::printf("measure,value\n");
  std::map<std::string, double> values = heap_measures(angle, r.bed.value_or(0), r.profile, side);
  for (const std::string& name : heap_measure_names())
    if (name != "bed_height" || r.bed) std::printf("%s,%.7g\n", name.c_str(), values.at(name));
}

// Several saved heaps of one rig: each one's readings, then their fill-to-fill spread and the
// front view's variance split by cause (measure/heap_scatter.h).
void print_heap_scatter(const std::vector<std::string>& files, const HeapReadingOptions& options) {
  std::vector<HeapReading> readings;
  std::printf("%-40s %8s %10s %9s %9s %8s %8s\n", "heap", "front", "views", "views sd", "turned sd", "height", "run-out");
  for (const std::string& file : files) {
    if (file.size() > 4 && file.compare(file.size() - 4, 4, ".png") == 0)
      throw std::runtime_error(file + ": several heaps are re-measured from their spheres (CSV), not from pictures");
    readings.push_back(read_heap(read_sphere_csv(file), options));
    const HeapReading& r = readings.back();
    std::printf("%-40s %8.3f %10.3f %9.3f %9.3f %8.4f %8.4f\n", file.c_str(), r.front, r.views_mean, r.views_sd,
                r.turned_sd, r.height, r.runout);
  }
  const HeapScatter s = heap_scatter(readings);
  auto row = [](const char* what, const SampleSpread& v, const char* unit) {
    std::printf("%-34s mean %9.4g %s, sd %8.3g, SE %8.3g (n %d)\n", what, v.mean, unit, v.sd, v.se(), v.n);
  };
  std::printf("over %zu heaps (side %s, fit band %g-%g of the height):\n", readings.size(), options.side.c_str(),
              options.angle.band_low, options.angle.band_high);
  row("front view (one photograph)", s.front, "deg");
  if (options.views > 1) {
    std::printf("%-34s sd %8.3g deg (each view's sd between heaps, pooled over the %d views)\n", "any one view", s.one_view_sd,
                options.views);
    row(printf_text("mean of %d views", options.views).c_str(), s.views_mean, "deg");
  }
  row("heap height", s.height, "m  ");
  row("run-out", s.runout, "m  ");
  std::printf("one photograph's sd by cause: line fit on a few bodies %.3g deg (cameras turned +-%g deg), camera side %s, "
              "packing (heap to heap) %.3g deg\n",
              s.fit_sd, options.turn_deg,
              options.views > 1 ? printf_text("%.3g deg (%d views)", s.camera_sd, options.views).c_str() : "not measured (--views 1)",
              s.packing_sd);
}

// What `repose heap-angle` was asked for, as its options give it.
struct HeapAngleRequest {
  std::vector<std::string> files;
  std::string view = "y", png, json, side = "both";
  bool axisymmetric = false, light_heap = false, data_rows = false, resting_only = false;
  int views = 1, threshold = 128;
  double turn = 2.0;
  HeapAngleOptions options;
  AxisymmetricOptions axi;
  std::vector<double> band, centre;
  std::optional<double> floor_z;
};

void add_heap_angle_options(CLI::App& app, HeapAngleRequest& q) {
  app.add_option("file", q.files,
                 "CSV with x,y,z,radius columns (metres), z up; or a PNG silhouette (photograph). Several CSVs "
                 "(refilled heaps of one rig): each one's front view, --views mean and small camera turns, then "
                 "their mean, sd and the sd's causes")
      ->required();
  app.add_option("--turn", q.turn, "several heaps: the front camera is also turned by +-TURN and +-TURN/2 degrees (default 2)")
      ->check(CLI::Range(0.01, 45.0));
  app.add_option("--threshold", q.threshold, "PNG: pixels darker than this grey level (0-255) are the heap (default 128)")
      ->check(CLI::Range(1, 255));
  app.add_flag("--light-heap", q.light_heap, "PNG: the heap is the lighter part of the picture");
  app.add_option("--side", q.side, "the slope a lab measures: left, right or both (their mean; default)")
      ->check(CLI::IsMember({"left", "right", "both"}));
  app.add_flag("--measures", q.data_rows,
               "print only the diagnosis measures of --side as 'measure,value' lines, for a measured-data CSV "
               "(repose_angle, heap_height, runout, profile_convexity; bed_height of a sphere CSV: a bed before the lift)");
  app.add_option("--view", q.view, "camera looks along x or y (image horizontal = the other one)")
      ->check(CLI::IsMember({"x", "y"}));
  app.add_option("--png", q.png, "write the picture: silhouette, boundary, fitted lines");
  app.add_option("--json", q.json, "write the results as JSON to this file");
  app.add_flag("--axisymmetric", q.axisymmetric, "also fit the surface in angular sectors (cylinder-lift heaps)");
  app.add_flag("--resting-only", q.resting_only,
               "CSV: measure only the spheres resting on the floor, directly or through touching spheres (not those "
               "left on a hopper or a gate above the heap; `repose experiment repose` measures so)");
  app.add_option("--views", q.views, "also photograph from N directions over half a turn about the heap axis; mean and sd of all slopes")
      ->check(CLI::Range(1, 180));
  app.add_option("--pixel", q.options.pixel, "pixel size, m (default: heap extent / 1600); a PNG needs it (from a scale in the photo)")
      ->check(finite_positive());
  app.add_option("--band", q.band, "fit band as fractions of the heap height: LOW,HIGH (default 0.1,0.8)")
      ->expected(2)
      ->delimiter(',');
  app.add_option("--floor", q.floor_z, "floor height z, m (default: lowest sphere bottom; a PNG's: its lowest heap pixel, "
                                       "z from the picture's bottom edge)")
      ->check(finite_number());
  app.add_option("--visible-from", q.options.visible_from,
                 "hide the picture before this horizontal coordinate, m (an opaque box's front wall hides what it holds)")
      ->check(finite_number());
  app.add_option("--sectors", q.axi.sectors, "3D fit: number of sectors (default 8)")->check(whole_number(1, 360));
  app.add_option("--bin", q.axi.bin_width, "3D fit: radial bin width, m (default: heap radius / 25)")->check(finite_positive());
  app.add_option("--centre,--center", q.centre, "3D fit: heap axis x,y (default: volume-weighted medians)")->expected(2)->delimiter(',');
}

// Reads the heap q.files[0] (a sphere CSV or a PNG silhouette) and measures what was asked.
HeapAngleRun measure_request(HeapAngleRequest& q) {
  const std::string& file = q.files.front();
  HeapAngleRun r;
  r.file = file;
  r.view = q.view;
  r.photo = file.size() > 4 && file.compare(file.size() - 4, 4, ".png") == 0;
  if (r.photo && !(q.options.pixel > 0)) throw std::runtime_error(file + ": a PNG silhouette needs --pixel (m per pixel)");
  if (r.photo && (q.views > 1 || q.axisymmetric))
    throw std::runtime_error(file + ": --views and --axisymmetric need the heap's spheres (a CSV), not one picture");
  if (q.options.visible_from && (q.views > 1 || q.axisymmetric))
    throw std::runtime_error("--visible-from hides part of the front view only: not with --views or --axisymmetric");
  if (!r.photo) r.spheres = read_sphere_csv(file);
  if (!r.photo && q.resting_only) r.apart = keep_resting(r.spheres, q.floor_z.value_or(lowest_bottom(r.spheres)));
  const HeapAngleOptions& options = q.options;
  q.axi.floor_z = q.floor_z;
  q.axi.band_low = options.band_low;
  q.axi.band_high = options.band_high;
  if (q.centre.size() == 2) q.axi.centre = glm::dvec2(q.centre[0], q.centre[1]);
  r.options = options;
  if (r.photo) {
    BinaryImage image = read_silhouette_png(file, options.pixel, q.threshold, q.light_heap);
    double floor = q.floor_z ? *q.floor_z : lowest_foreground(image);
    r.m = measure_heap_image(std::move(image), floor, options);
  } else {
    r.m = measure_heap_angle(r.spheres, options);
    r.bed = uniform_bed_height(r.spheres, q.floor_z);
  }
  r.profile = measure_heap_profile(r.m);
  if (q.views > 1)
    r.around = measure_heap_angle_views(r.spheres, q.views, options, q.centre.size() == 2 ? q.axi.centre : std::nullopt);
  if (q.axisymmetric) r.axisymmetric = measure_axisymmetric_heap_angle(r.spheres, q.axi);
  return r;
}

int run_heap_angle(int argc, char** argv) {
  CLI::App app{"Angle of repose of a settled heap from its front-view silhouette (and a 3D sector fit); several "
               "heaps of one rig: their readings, spread and its causes."};
  HeapAngleRequest q;
  add_heap_angle_options(app, q);
  REPOSE_PARSE(app, argc, argv);
  q.options.view = q.view == "x" ? ViewAxis::X : ViewAxis::Y;
  q.options.floor_z = q.floor_z;
  if (q.band.size() == 2) {
    q.options.band_low = q.band[0];
    q.options.band_high = q.band[1];
  }
  if (q.files.size() > 1) {
    if (!q.png.empty() || !q.json.empty() || q.axisymmetric || q.data_rows)
      return usage_error("--png, --json, --axisymmetric and --measures take one heap; several heaps give their spread");
    print_heap_scatter(q.files, {q.options, q.side, q.views, q.turn});
    return 0;
  }
  HeapAngleRun r = measure_request(q);
  if (q.data_rows) print_measure_rows(r, q.side);
  else print_heap_text(r);
  if (!q.png.empty()) {
    write_heap_angle_png(q.png, r.m, r.photo ? "u" : r.options.view == ViewAxis::Y ? "x" : "y", slope_caption(r.m, q.side));
    if (!q.data_rows) std::printf("picture      %s\n", q.png.c_str());
  }
  if (!q.json.empty()) {
    write_file_atomically(q.json, heap_angle_json(r).dump(2) + "\n");
    if (!q.data_rows) std::printf("results      %s\n", q.json.c_str());
  }
  return 0;
}

// `repose mesh hopper`: a conical hopper as ASCII STL, in the unit its numbers are given in (a
// case's `scale` converts: 0.001 for millimetres).
int run_mesh(int argc, char** argv) {
  CLI::App app{"Write a wall mesh as ASCII STL. Shapes: hopper (a cone open at both ends, axis z, outlet at z = 0)."};
  std::string shape, out;
  double top = 0, outlet = 0, height = 0;
  int sides = 48;
  app.add_option("shape", shape, "hopper")->required()->check(CLI::IsMember({"hopper"}));
  app.add_option("--top-diameter", top, "diameter of the top opening")->required()->check(finite_positive());
  app.add_option("--outlet-diameter", outlet, "diameter of the outlet")->required()->check(finite_positive());
  app.add_option("--height", height, "height from the outlet to the top")->required()->check(finite_positive());
  app.add_option("--sides", sides, "facets around (default 48)")->check(whole_number(3, 100000));
  app.add_option("--out", out, "the STL file")->required();
  CLI11_PARSE(app, argc, argv);
  TriangleMesh mesh = hopper_mesh(0.5 * top, 0.5 * outlet, height, sides);
  write_file_atomically(out, [&](std::ostream& o) { write_ascii_stl(o, mesh, shape); });
  std::printf("wrote %s: %s, %zu triangles, top %g, outlet %g, height %g (the case's `scale` makes metres)\n", out.c_str(),
              shape.c_str(), mesh.triangles.size(), top, outlet, height);
  return 0;
}

}  // namespace

std::vector<Verb> geometry_verbs() {
  return {
      {"template", "write a shipped clump template (cabbage, cotton stalk, groups) as CSV", run_template},
      {"clump", "volume, mass, centre of mass, inertia and principal axes of a clump CSV", run_clump},
      {"stl", "read an STL mesh: triangles, bounds, area, watertightness", run_stl},
      {"mesh", "write a wall mesh as ASCII STL: a conical hopper", run_mesh},
      {"heap-angle", "angle of repose of a settled heap from its front view (and 3D sectors)", run_heap_angle},
  };
}

}  // namespace repose::cli
