// The reader of one case file (case_loader.h's load_case): a CaseSpec built section by section,
// each kind of section in a file of its own (case_reader_*.cpp), with the bookkeeping the later
// checks need (which materials meet, which walls [experiment] names). Internal to host/case.
#pragma once
#include <toml++/toml.h>

#include <array>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "case/case_spec.h"
#include "case/toml_section.h"

namespace repose {

// Names usable in override keys ("material.cabbage.density"): no dots, no slashes, and not all
// digits (those are indices).
bool usable_name(const std::string& name);

class CaseReader {
 public:
  CaseReader(const toml::table& root, const std::string& path) : root_(root), file_(path) {}

  // The whole file, its sections in order, then the checks across them (case_loader.cpp).
  CaseSpec read();

 private:
  static std::string toml_identity(const toml::table& root);
  static std::string value_text(const toml::node& node);
  static void flatten(const toml::table& table, const std::string& prefix, std::string& lines);
  static std::string shortest_number(double v);
  void note_input_file(const std::string& as_written, const std::filesystem::path& path);
  std::vector<Section> entries(const std::string& name);
  std::optional<Section> table(const std::string& name);

  // simulation, contact, neighbour, output, experiment, air_drag (case_reader_simulation.cpp)
  void read_simulation();
  void read_contact();
  void read_neighbour();
  void read_output();
  void read_experiment();
  void read_air_drag();
  void check_time_step();

  // materials and interactions (case_reader_materials.cpp)
  void read_material(const Section& s);
  std::vector<std::string> material_names() const;
  int material_index(const Section& s, std::string_view k, const std::string& name) const;
  int material_of(const Section& s) const;
  std::pair<std::string, std::string> name_pair(const Section& s, std::string_view k) const;
  void read_interaction(const Section& s);
  void note_use(std::map<int, SourceRef>& users, int material, const Section& s);
  void check_interactions_cover_use();

  // particles and templates (case_reader_particles.cpp)
  bool fixed_of(const Section& s) const;
  void read_sphere(const Section& s);
  void positive_range(const Section& s, std::string_view k, double& low, double& high);
  int template_of(const Section& s) const;
  void read_template(const Section& s);
  std::array<double, 4> orientation_of(const Section& s) const;
  void read_clump(const Section& s);
  void read_fill(const Section& s, int index);
  void read_lattice(const Section& s);
  void read_lattice_box(const Section& s, LatticeSpec& lattice);
  void finish_lattice(const Section& s, LatticeSpec& lattice);
  void read_body_lattice(const Section& s, LatticeSpec& lattice);
  size_t particles_of(int material) const;

  // walls (case_reader_walls.cpp)
  void read_wall(const Section& s, int index);
  std::vector<std::string> box_open_faces(const Section& s);
  void read_rectangle(const Section& s, WallSpec& wall);
  void read_mesh(const Section& s, WallSpec& wall);
  void read_motion(const Section& s, WallMotion& motion);
  void check_experiment_walls();
 private:
  const toml::table& root_;
  const std::string& file_;
  CaseSpec spec_;
  std::map<int, SourceRef> particle_users_, wall_users_;
  std::vector<std::pair<std::string, SourceRef>> named_walls_;  // [experiment] values naming walls
};

}  // namespace repose
