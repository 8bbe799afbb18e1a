#include "geometry/sphere_csv.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <istream>
#include <optional>
#include <ostream>
#include <stdexcept>

#include "util/atomic_file.h"
#include "util/input_error.h"
#include "util/input_file.h"

namespace repose {
namespace {

struct Field {
  std::string text;  // trimmed
  int column;        // 1-based character column of the field's first character in the line
};

std::vector<Field> split_fields(const std::string& line) {
  std::vector<Field> fields;
  size_t start = 0;
  while (true) {
    size_t end = line.find(',', start);
    if (end == std::string::npos) end = line.size();
    size_t a = start, b = end;
    while (a < b && std::isspace(static_cast<unsigned char>(line[a]))) ++a;
    while (b > a && std::isspace(static_cast<unsigned char>(line[b - 1]))) --b;
    fields.push_back({line.substr(a, b - a), static_cast<int>(a) + 1});
    if (end == line.size()) break;
    start = end + 1;
  }
  return fields;
}

std::optional<double> parse_number(const std::string& text) {
  const char* first = text.data();
  const char* last = text.data() + text.size();
  if (first != last && *first == '+') ++first;  // from_chars rejects a leading '+'
  if (first == last) return std::nullopt;
  double value = 0.0;
  auto [ptr, ec] = std::from_chars(first, last, value);
  if (ec != std::errc() || ptr != last) return std::nullopt;
  return value;
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

bool is_skipped(const std::string& line) {
  auto first = std::find_if(line.begin(), line.end(),
                            [](unsigned char c) { return !std::isspace(c); });
  return first == line.end() || *first == '#';
}

}  // namespace

std::vector<Sphere> parse_sphere_csv(std::istream& in, const std::string& source_name) {
  static const std::array<const char*, 4> kNames = {"x", "y", "z", "radius"};
  std::array<int, 4> index{-1, -1, -1, -1};  // field index of x, y, z, radius
  size_t field_count = 0;
  bool have_header = false;
  bool saw_any_line = false;
  std::vector<Sphere> spheres;

  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (!line.empty()) saw_any_line = true;
    if (is_skipped(line)) continue;
    auto fields = split_fields(line);

    if (!have_header) {
      for (size_t i = 0; i < fields.size(); ++i) {
        std::string name = lower(fields[i].text);
        // A unit suffix may name the metres the values are in (heap.csv writes x_m ... radius_m).
        if (name.size() > 2 && name.compare(name.size() - 2, 2, "_m") == 0) name.resize(name.size() - 2);
        if (name == "r") name = "radius";
        for (size_t k = 0; k < kNames.size(); ++k)
          if (name == kNames[k]) {
            if (index[k] >= 0)
              throw InputError(source_name, line_no, fields[i].column,
                               "header names column '" + name + "' twice");
            index[k] = static_cast<int>(i);
          }
      }
      for (size_t k = 0; k < kNames.size(); ++k)
        if (index[k] < 0) {
          if (parse_number(fields[0].text))
            throw InputError(source_name, line_no, 1,
                             "missing header line: expected column names such as x,y,z,radius");
          throw InputError(source_name, line_no, 1,
                           std::string("header lacks column '") + kNames[k] +
                               "' (expected x,y,z,radius)");
        }
      field_count = fields.size();
      have_header = true;
      continue;
    }

    if (fields.size() != field_count) {
      int column = fields.size() > field_count ? fields[field_count].column
                                               : static_cast<int>(line.size()) + 1;
      throw InputError(source_name, line_no, column,
                       "expected " + std::to_string(field_count) + " fields as in the header, found " +
                           std::to_string(fields.size()));
    }
    std::array<double, 4> values{};
    for (size_t k = 0; k < kNames.size(); ++k) {
      const Field& f = fields[static_cast<size_t>(index[k])];
      auto value = parse_number(f.text);
      std::string what = "field " + std::to_string(index[k] + 1) + " ('" + kNames[k] + "')";
      if (!value)
        throw InputError(source_name, line_no, f.column,
                         what + ": '" + f.text + "' is not a number");
      if (!std::isfinite(*value))
        throw InputError(source_name, line_no, f.column, what + ": '" + f.text + "' is not finite");
      values[k] = *value;
    }
    if (values[3] <= 0.0) {
      const Field& f = fields[static_cast<size_t>(index[3])];
      throw InputError(source_name, line_no, f.column,
                       std::string("radius ") + f.text +
                           (values[3] < 0.0 ? " is negative" : " is zero") +
                           " (radii must be positive)");
    }
    spheres.push_back({{values[0], values[1], values[2]}, values[3]});
  }
  if (in.bad()) throw InputError(source_name, 0, 0, "read error");
  if (!saw_any_line) throw InputError(source_name, 0, 0, "file is empty");
  if (!have_header) throw InputError(source_name, 0, 0, "no header line (only comments or blank lines)");
  if (spheres.empty()) throw InputError(source_name, line_no, 0, "no spheres after the header");
  return spheres;
}

std::vector<Sphere> read_sphere_csv(const std::string& path) {
  if (auto why = why_not_input_file(path, 256u << 20); !why.empty()) throw InputError(path, 0, 0, why);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, 0, "cannot open file");
  return parse_sphere_csv(in, path);
}

void write_sphere_csv(std::ostream& out, const std::vector<Sphere>& spheres) {
  auto shortest = [](double v) {
    char buf[32];
    auto [ptr, ec] = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, ptr);
  };
  out << "x,y,z,radius\n";
  for (const auto& s : spheres)
    out << shortest(s.centre.x) << ',' << shortest(s.centre.y) << ',' << shortest(s.centre.z)
        << ',' << shortest(s.radius) << '\n';
}

void write_sphere_csv(const std::string& path, const std::vector<Sphere>& spheres) {
  write_file_atomically(path, [&](std::ostream& out) { write_sphere_csv(out, spheres); });
}

}  // namespace repose
