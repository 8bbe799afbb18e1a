#include "case/toml_section.h"

#include <cmath>

namespace repose {

std::string quoted_list(const std::vector<std::string>& words) {
  std::string text;
  for (const auto& word : words) text += (text.empty() ? "'" : ", '") + word + "'";
  return text;
}

const char* type_name(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a float";
    case toml::node_type::boolean: return "a boolean";
    case toml::node_type::array: return "an array";
    case toml::node_type::table: return "a table";
    default: return "a date or time";
  }
}

double positive(const Section& s, std::string_view k, double value) {
  if (!(value > 0)) s.fail(k, format_number(value) + " must be greater than 0");
  return value;
}
double non_negative(const Section& s, std::string_view k, double value) {
  if (value < 0) s.fail(k, format_number(value) + " must not be negative");
  return value;
}

Vec3d unit_vector(const Section& s, std::string_view k, const Vec3d& v) {
  double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (!(length > 0)) s.fail(k, "must not be the zero vector");
  return {v[0] / length, v[1] / length, v[2] / length};
}

}  // namespace repose
