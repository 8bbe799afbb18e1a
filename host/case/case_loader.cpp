#include "case/case_loader.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include "case/case_override.h"
#include "case/case_reader.h"
#include "case/particle_factory.h"
#include "case/physical_ranges.h"
#include "util/hash.h"
#include "util/input_file.h"

namespace repose {

bool usable_name(const std::string& name) {
  if (name.empty() || !(std::isalpha((unsigned char)name[0]) || name[0] == '_')) return false;
  return std::all_of(name.begin(), name.end(), [](unsigned char c) {
    return std::isalnum(c) || c == '_' || c == '-';
  });
}

CaseSpec CaseReader::read() {
  spec_.identity = toml_identity(root_);
  Section top(root_, "", file_);
  top.allow_only({"simulation", "contact", "neighbour", "output", "experiment", "air_drag", "material",
                  "interaction", "template", "sphere", "clump", "fill", "lattice", "wall"},
                 "the case file");
  spec_.path = file_;
  read_simulation();
  read_contact();
  read_neighbour();
  read_output();
  read_experiment();
  read_air_drag();
  for (const Section& s : entries("material")) read_material(s);
  if (spec_.materials.empty())
    throw CaseError({file_, "material", 0}, "the case has no [[material]]");
  for (const Section& s : entries("interaction")) read_interaction(s);
  for (const Section& s : entries("template")) read_template(s);
  for (const Section& s : entries("sphere")) read_sphere(s);
  for (const Section& s : entries("clump")) read_clump(s);
  int fill_index = 0;
  for (const Section& s : entries("fill")) read_fill(s, fill_index++);
  for (const Section& s : entries("lattice")) read_lattice(s);
  int wall_index = 0;
  for (const Section& s : entries("wall")) read_wall(s, wall_index++);
  check_experiment_walls();
  if (spec_.spheres.empty() && spec_.bodies.empty() && spec_.fills.empty() && spec_.lattices.empty())
    throw CaseError({file_, "", 0}, "the case has no particles: add [[sphere]], [[clump]], [[fill]] or [[lattice]]");
  check_interactions_cover_use();
  expand_particles(spec_);
  check_time_step();
  check_case_ranges(spec_);
  return std::move(spec_);
}

// The parsed document as sorted "dotted.key = value" lines ("material.0.density = 850"),
// numbers in their shortest exact form: no comments or layout of the source.
std::string CaseReader::toml_identity(const toml::table& root) {
  std::string lines;
  flatten(root, "", lines);
  return lines;
}

std::string CaseReader::value_text(const toml::node& node) {
  if (auto a = node.as_array()) {
    std::string text = "[";
    for (size_t k = 0; k < a->size(); ++k) text += (k ? ", " : "") + value_text(*a->get(k));
    return text + "]";
  }
  if (auto t = node.as_table()) {
    std::string text;
    flatten(*t, "", text);
    return "{" + text + "}";
  }
  if (node.is_floating_point()) return shortest_number(node.as_floating_point()->get());
  std::ostringstream text;
  text << toml::toml_formatter(node, toml::format_flags::none);
  return text.str();
}

void CaseReader::flatten(const toml::table& table, const std::string& prefix, std::string& lines) {
  for (const auto& [key, node] : table) {
    std::string path = prefix + std::string(key.str());
    if (auto t = node.as_table()) {
      flatten(*t, path + ".", lines);
    } else if (auto a = node.as_array(); a && a->is_array_of_tables()) {
      for (size_t k = 0; k < a->size(); ++k) flatten(*a->get(k)->as_table(), path + "." + std::to_string(k) + ".", lines);
    } else {
      lines += path + " = " + value_text(node) + "\n";
    }
  }
}

std::string CaseReader::shortest_number(double v) {
  char text[32];
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(text, sizeof text, "%.*g", digits, v);
    if (std::strtod(text, nullptr) == v) break;
  }
  return text;
}

// A file the case reads goes into its identity by content, so an edited template or mesh is
// a different case (a campaign does not mix two geometries).
void CaseReader::note_input_file(const std::string& as_written, const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  spec_.identity += "# file " + as_written + " fnv1a " + fnv1a_hex(bytes.str()) + "\n";
}

// The elements of an array of tables ([[material]] ...), each as a Section "material[i]".
std::vector<Section> CaseReader::entries(const std::string& name) {
  std::vector<Section> sections;
  const toml::node* node = root_.get(name);
  if (!node) return sections;
  Section top(root_, "", file_);
  if (node->is_table())
    top.fail(name, "write [[" + name + "]] (one entry of a list), not [" + name + "]");
  if (!node->is_array()) top.wrong_type(name, "[[" + name + "]] entries");
  const toml::array& array = *node->as_array();
  for (size_t i = 0; i < array.size(); ++i) {
    std::string prefix = name + "[" + std::to_string(i) + "]";
    if (!array.get(i)->is_table())
      throw CaseError({file_, prefix, line_of(*array.get(i))},
                      std::string("expected a table, got ") + type_name(*array.get(i)));
    sections.emplace_back(*array.get(i)->as_table(), prefix, file_);
  }
  return sections;
}

std::optional<Section> CaseReader::table(const std::string& name) {
  return Section(root_, "", file_).sub(name);
}


CaseOverride parse_override(const std::string& text) {
  size_t equals = text.find('=');
  if (equals == std::string::npos || equals == 0)
    throw CaseError({"", "override " + text, 0}, "expected KEY=VALUE, as simulation.end_time=0.5");
  return {text.substr(0, equals), text.substr(equals + 1)};
}

CaseSpec load_case_from_string(const std::string& toml_text, const std::string& virtual_path,
                               const std::vector<CaseOverride>& overrides) {
  toml::table root;
  try {
    root = toml::parse(std::string_view(toml_text), std::string_view(virtual_path));
  } catch (const toml::parse_error& error) {
    throw CaseError({virtual_path, "", int(error.source().begin.line)},
                    "TOML syntax: " + std::string(error.description()), int(error.source().begin.column));
  }
  for (const CaseOverride& o : overrides) apply_override(root, o.key, o.value, virtual_path);
  return CaseReader(root, virtual_path).read();
}

std::string case_hash(const CaseSpec& spec) { return fnv1a_hex(spec.identity); }

CaseSpec load_case(const std::string& path, const std::vector<CaseOverride>& overrides) {
  // A case is a short TOML text; particles and meshes go in the CSV and STL files it names.
  if (auto why = why_not_input_file(path, 16u << 20); !why.empty())
    throw CaseError({path, "", 0}, "not a case file: " + why);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw CaseError({path, "", 0}, std::string("cannot read the case file: ") + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  return load_case_from_string(text.str(), path, overrides);
}

}  // namespace repose
