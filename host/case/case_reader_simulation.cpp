// The [simulation], [contact], [neighbour], [output], [experiment] and [air_drag] tables of a case
// file, and its time step checked against the Rayleigh time.
#include "case/case_reader.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "case/case_error.h"
#include "case/experiment_keys.h"
#include "case/spelling.h"
#include "case/time_step.h"
#include "util/path_name.h"

namespace repose {

void CaseReader::read_simulation() {
  auto s = table("simulation");
  if (!s)
    throw CaseError({file_, "simulation", 0},
                    "missing [simulation] table (end_time and dt or rayleigh_fraction are required)");
  s->allow_only({"name", "seed", "end_time", "dt", "rayleigh_fraction", "gravity", "integrator"},
                "[simulation]");
  spec_.name = s->text("name").value_or(std::filesystem::path(file_).stem().string());
  // The name becomes file and folder names (frames/NAME_00000.vtp, out/NAME): it must stay inside.
  if (std::string why = why_not_path_name(spec_.name); !why.empty()) {
    if (s->has("name")) s->fail("name", why);
    throw CaseError({file_, "simulation.name", 0}, "the case file's name gives the case no usable name (" + why +
                                                       "): give simulation.name");
  }
  if (auto seed = s->integer("seed")) {
    if (*seed < 0) s->fail("seed", "must not be negative");
    spec_.seed = uint64_t(*seed);
  }
  spec_.gravity = s->vector3("gravity").value_or(spec_.gravity);
  double g = std::sqrt(spec_.gravity[0] * spec_.gravity[0] + spec_.gravity[1] * spec_.gravity[1] +
                       spec_.gravity[2] * spec_.gravity[2]);
  if (!(g <= 1e4))  // a geotechnical centrifuge reaches a few hundred g
    s->fail("gravity", "|gravity| = " + format_number(g) + " m/s^2 is " + format_number(g / 9.81) +
                           " g: more than 1e4 m/s^2 is no lab, planet or centrifuge (a unit slip?)");
  spec_.integrator = s->choice<Integrator>(
      "integrator",
      {{"velocity_verlet", Integrator::VelocityVerlet}, {"symplectic_euler", Integrator::SymplecticEuler}},
      Integrator::VelocityVerlet);

  TimeSpec& time = spec_.time;
  time.end_time = s->required_number("end_time", " (simulated time in s)");
  time.end_where = s->where("end_time");
  if (!(time.end_time > 0)) s->fail("end_time", format_number(time.end_time) + " must be greater than 0");
  bool has_dt = s->has("dt"), has_fraction = s->has("rayleigh_fraction");
  if (has_dt && has_fraction) {
    const char* later = line_of(*s->table().get("dt")) > line_of(*s->table().get("rayleigh_fraction"))
                            ? "dt" : "rayleigh_fraction";
    s->fail(later, "give dt or rayleigh_fraction, not both");
  }
  if (!has_dt && !has_fraction)
    s->missing("dt", ": give dt (time step in s) or rayleigh_fraction (of the Rayleigh time)");
  if (has_dt) {
    time.dt = positive(*s, "dt", *s->number("dt"));
    time.where = s->where("dt");
  } else {
    double fraction = positive(*s, "rayleigh_fraction", *s->number("rayleigh_fraction"));
    if (fraction > 1)
      s->fail("rayleigh_fraction", format_number(fraction) +
                                       " is above 1: a step longer than the Rayleigh time is unstable "
                                       "(0.1 to 0.4 is usual)");
    time.rayleigh_fraction = fraction;
    time.where = s->where("rayleigh_fraction");
  }
}

void CaseReader::read_contact() {
  auto s = table("contact");
  if (!s) return;
  s->allow_only({"coulomb_cap", "normal_attraction", "rolling", "rolling_omega", "rolling_lever", "rolling_damping",
                 "cohesion_friction", "cohesion_area"},
                "[contact]");
  ContactOptions& c = spec_.contact;
  c.coulomb_cap = s->choice<CoulombCap>(
      "coulomb_cap", {{"spring_and_damper", CoulombCap::SpringAndDamper}, {"spring", CoulombCap::SpringOnly}},
      c.coulomb_cap);
  c.normal_attraction = s->choice<NormalAttraction>(
      "normal_attraction", {{"allow", NormalAttraction::Allow}, {"clip", NormalAttraction::Clip}},
      c.normal_attraction);
  c.rolling = s->choice<RollingModel>(
      "rolling",
      {{"constant_torque", RollingModel::ConstantTorque}, {"none", RollingModel::None}, {"epsd", RollingModel::ElasticPlastic}},
      c.rolling);
  c.rolling_omega = s->choice<RollingOmega>(
      "rolling_omega", {{"own", RollingOmega::Own}, {"relative", RollingOmega::Relative}}, c.rolling_omega);
  // LIGGGHTS's relative torque takes R* of the touching spheres: its lever is the sphere's.
  RollingLever lever_default =
      c.rolling_omega == RollingOmega::Relative ? RollingLever::Sphere : c.rolling_lever;
  c.rolling_lever = s->choice<RollingLever>(
      "rolling_lever", {{"centre", RollingLever::Centre}, {"sphere", RollingLever::Sphere}}, lever_default);
  if (c.rolling_omega == RollingOmega::Relative && c.rolling_lever == RollingLever::Centre)
    s->fail("rolling_lever", "\"centre\" belongs to EDEM's torque against each body's own spin; "
                             "rolling_omega = \"relative\" (LIGGGHTS cdt) takes R* of the touching spheres");
  c.cohesion_friction = s->choice<CohesionFriction>(
      "cohesion_friction", {{"net", CohesionFriction::Net}, {"contact", CohesionFriction::Contact}},
      c.cohesion_friction);
  c.cohesion_area = s->choice<CohesionArea>(
      "cohesion_area", {{"hertz", CohesionArea::Hertz}, {"intersection", CohesionArea::Intersection}},
      c.cohesion_area);
  if (auto eta = s->number("rolling_damping")) {
    c.rolling_damping = non_negative(*s, "rolling_damping", *eta);
    if (c.rolling != RollingModel::ElasticPlastic)
      s->fail("rolling_damping", "applies to rolling = \"epsd\" only (the constant torque has no dashpot)");
  }
  if (c.rolling == RollingModel::ElasticPlastic && c.rolling_omega == RollingOmega::Relative)
    s->fail("rolling_omega", "\"relative\" belongs to the constant torque; the EPSD spring always acts on the "
                             "relative rolling rotation");
}

void CaseReader::read_neighbour() {
  auto s = table("neighbour");
  if (!s) return;
  s->allow_only({"skin", "rebuild_interval", "body_broad_phase", "wall_grid"}, "[neighbour]");
  if (auto on = s->boolean("body_broad_phase")) spec_.neighbour.body_broad_phase = *on;
  if (auto on = s->boolean("wall_grid")) spec_.neighbour.wall_grid = *on;
  if (auto skin = s->number("skin")) spec_.neighbour.skin = non_negative(*s, "skin", *skin);
  if (auto interval = s->integer("rebuild_interval")) {
    if (*interval < 0 || *interval > 1000000) s->fail("rebuild_interval", "must be 0 (automatic) or a number of steps");
    spec_.neighbour.rebuild_interval = int(*interval);
  }
}

void CaseReader::read_output() {
  auto s = table("output");
  if (!s) return;
  s->allow_only({"interval", "vtk", "checkpoint_interval"}, "[output]");
  if (auto interval = s->number("interval")) spec_.output.interval = non_negative(*s, "interval", *interval);
  if (auto every = s->number("checkpoint_interval"))
    spec_.output.checkpoint_interval = non_negative(*s, "checkpoint_interval", *every);
  spec_.output.vtk = s->boolean("vtk").value_or(spec_.output.vtk);
}

// [experiment]: its type picks the experiment that reads the rest (case/experiment_keys.h).
void CaseReader::read_experiment() {
  auto s = table("experiment");
  if (!s) return;
  ExperimentSpec& ex = spec_.experiment;
  const auto& readers = experiment_key_readers();
  if (readers.empty())
    s->fail("the program has not installed the experiments that read [experiment] (install_experiments())");
  std::vector<std::string> types;
  for (const auto& r : readers) types.push_back(r.type);
  std::string listed;
  for (size_t k = 0; k < types.size(); ++k)
    listed += (k == 0 ? "" : k + 1 == types.size() ? " or " : ", ") + types[k];
  std::string type = s->required_text("type", " (" + listed + ")");
  auto reader = std::find_if(readers.begin(), readers.end(), [&](const auto& r) { return r.type == type; });
  if (reader == readers.end())
    s->fail("type", "unknown experiment '" + type + "' (" + listed + ")" + did_you_mean(type, types));
  ex.type = type;
  std::vector<std::string> allowed{"type", "max_time"};
  allowed.insert(allowed.end(), reader->keys.begin(), reader->keys.end());
  s->allow_only(allowed, "[experiment] of type '" + type + "'");
  ex.where = s->where();
  ex.max_time_where = s->where("max_time");
  if (auto t = s->number("max_time")) ex.max_time = positive(*s, "max_time", *t);
  ex.settings = reader->read(*s);
  for (const std::string& key : reader->wall_keys)
    if (auto name = s->text(key)) named_walls_.push_back({*name, s->where(key)});
}

// Extension air_drag (docs/diagnosis.md).
void CaseReader::read_air_drag() {
  auto s = table("air_drag");
  if (!s) return;
  s->allow_only({"drag_coefficient", "air_density"}, "[air_drag]");
  spec_.air_drag.where = s->where();
  if (auto cd = s->number("drag_coefficient"))
    spec_.air_drag.drag_coefficient = non_negative(*s, "drag_coefficient", *cd);
  if (auto rho = s->number("air_density")) spec_.air_drag.air_density = positive(*s, "air_density", *rho);
}

void CaseReader::check_time_step() {
  RayleighLimit limit = rayleigh_limit(spec_);
  if (!spec_.time.dt || *spec_.time.dt <= limit.time) return;
  throw CaseError(spec_.time.where,
                  format_number(*spec_.time.dt) + " s is above the Rayleigh time " + format_number(limit.time) +
                      " s set by " + limit.where.key + " (line " + std::to_string(limit.where.line) +
                      ", " + (limit.body >= 0 ? "sub-sphere radius " : "radius ") +
                      format_number(limit.radius) + " m, material '" +
                      spec_.materials[size_t(limit.material)].name +
                      "'), where the contact law is unstable; lower dt or give rayleigh_fraction "
                      "(0.1 to 0.4 is usual)");
}

}  // namespace repose
