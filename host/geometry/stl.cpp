#include "geometry/stl.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <tuple>

#include <glm/geometric.hpp>

#include "util/input_error.h"
#include "util/input_file.h"

namespace repose {
namespace {

constexpr size_t kBinaryHeaderBytes = 80;
constexpr size_t kBinaryPreambleBytes = 84;  // header + uint32 triangle count
constexpr size_t kBinaryTriangleBytes = 50;  // normal, 3 vertices (12 floats) + uint16 attribute

// Collects triangles, deduplicating vertices and setting degenerate ones aside.
class MeshBuilder {
 public:
  explicit MeshBuilder(StlFile& out) : out_(out) {}

  void add(const std::array<glm::dvec3, 3>& corners, int line) {
    ++out_.triangles_in_file;
    std::array<uint32_t, 3> ids{};
    for (int k = 0; k < 3; ++k) ids[k] = vertex_id(corners[k]);
    const size_t index = out_.triangles_in_file;
    if (ids[0] == ids[1] || ids[1] == ids[2] || ids[2] == ids[0]) {
      out_.degenerate.push_back({index, line, "two corners are the same point"});
      return;
    }
    const glm::dvec3 n = glm::cross(corners[1] - corners[0], corners[2] - corners[0]);
    double longest2 = std::max({glm::dot(corners[1] - corners[0], corners[1] - corners[0]),
                                glm::dot(corners[2] - corners[1], corners[2] - corners[1]),
                                glm::dot(corners[0] - corners[2], corners[0] - corners[2])});
    const double twice_area = glm::length(n);
    // Relative test: sin(angle) below 1e-12 means the corners are collinear to rounding.
    if (!(twice_area > 1e-12 * longest2)) {
      out_.degenerate.push_back({index, line, "corners are collinear (zero area)"});
      return;
    }
    out_.mesh.triangles.push_back(ids);
    out_.mesh.normals.push_back(n / twice_area);
  }

 private:
  uint32_t vertex_id(const glm::dvec3& v) {
    auto key = std::make_tuple(v.x, v.y, v.z);
    auto it = ids_.find(key);
    if (it != ids_.end()) return it->second;
    uint32_t id = static_cast<uint32_t>(out_.mesh.vertices.size());
    out_.mesh.vertices.push_back(v);
    ids_.emplace(key, id);
    return id;
  }

  StlFile& out_;
  std::map<std::tuple<double, double, double>, uint32_t> ids_;
};

void finish(StlFile& file, const std::string& source_name) {
  if (file.triangles_in_file == 0) throw InputError(source_name, 0, 0, "STL contains no triangles");
  if (file.mesh.triangles.empty())
    throw InputError(source_name, 0, 0,
                     "all " + std::to_string(file.triangles_in_file) +
                         " triangles are degenerate (zero area); first: triangle " +
                         std::to_string(file.degenerate.front().index) + ": " + file.degenerate.front().reason);
}

float read_float(const unsigned char* p) {
  uint32_t bits = uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

uint32_t read_count(const std::string& bytes) {
  const auto* p = reinterpret_cast<const unsigned char*>(bytes.data()) + kBinaryHeaderBytes;
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

StlFile parse_binary(const std::string& bytes, const std::string& source_name) {
  StlFile file;
  file.binary = true;
  std::string header = bytes.substr(0, kBinaryHeaderBytes);
  header = header.substr(0, header.find('\0'));
  while (!header.empty() && std::isspace(static_cast<unsigned char>(header.back()))) header.pop_back();
  file.solid_name = header;
  const uint32_t count = read_count(bytes);
  MeshBuilder builder(file);
  const auto* base = reinterpret_cast<const unsigned char*>(bytes.data()) + kBinaryPreambleBytes;
  for (uint32_t t = 0; t < count; ++t) {
    const unsigned char* record = base + size_t(t) * kBinaryTriangleBytes;
    std::array<glm::dvec3, 3> corners;
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) {
        float value = read_float(record + 12 + 12 * k + 4 * c);
        if (!std::isfinite(value))
          throw InputError(source_name, 0, 0,
                           "binary STL triangle " + std::to_string(t + 1) + " has a non-finite coordinate");
        corners[k][c] = static_cast<double>(value);
      }
    builder.add(corners, 0);
  }
  finish(file, source_name);
  return file;
}

// Whitespace-separated tokens of an ASCII STL with their line and column.
class Tokenizer {
 public:
  Tokenizer(const std::string& text, const std::string& source_name) : text_(text), name_(source_name) {}

  struct Token {
    std::string text;  // empty at end of file
    int line = 0, column = 0;
  };

  Token next() {
    while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) advance();
    Token token{"", line_, column_};
    size_t start = pos_;
    while (pos_ < text_.size() && !std::isspace(static_cast<unsigned char>(text_[pos_]))) advance();
    token.text = text_.substr(start, pos_ - start);
    return token;
  }

  // The rest of the current line, trimmed (the solid's name).
  std::string rest_of_line() {
    size_t end = text_.find('\n', pos_);
    if (end == std::string::npos) end = text_.size();
    std::string rest = text_.substr(pos_, end - pos_);
    while (pos_ < end) advance();
    auto first = rest.find_first_not_of(" \t\r");
    auto last = rest.find_last_not_of(" \t\r");
    return first == std::string::npos ? "" : rest.substr(first, last - first + 1);
  }

  [[noreturn]] void fail(const Token& at, const std::string& message) const {
    throw InputError(name_, at.line, at.column, message);
  }

  // Keywords are matched without regard to case: some exporters write "FACET NORMAL".
  static bool is(const Token& t, const char* keyword) {
    if (t.text.size() != std::strlen(keyword)) return false;
    for (size_t i = 0; i < t.text.size(); ++i)
      if (std::tolower(static_cast<unsigned char>(t.text[i])) != keyword[i]) return false;
    return true;
  }

  void expect(const char* keyword) {
    Token t = next();
    if (!is(t, keyword)) fail(t, std::string("expected '") + keyword + "', found " + describe(t));
  }

  double number(const char* what) {
    Token t = next();
    double value = 0;
    const char* first = t.text.data();
    const char* last = first + t.text.size();
    if (first != last && *first == '+') ++first;
    auto [ptr, ec] = std::from_chars(first, last, value);
    if (t.text.empty() || ec != std::errc() || ptr != last)
      fail(t, std::string("expected a number (") + what + "), found " + describe(t));
    if (!std::isfinite(value)) fail(t, std::string(what) + " '" + t.text + "' is not finite");
    return value;
  }

  static std::string describe(const Token& t) {
    return t.text.empty() ? std::string("end of file") : "'" + t.text + "'";
  }

 private:
  void advance() {
    if (text_[pos_] == '\n') {
      ++line_;
      column_ = 1;
    } else {
      ++column_;
    }
    ++pos_;
  }

  const std::string& text_;
  const std::string& name_;
  size_t pos_ = 0;
  int line_ = 1, column_ = 1;
};

StlFile parse_ascii(const std::string& bytes, const std::string& source_name) {
  StlFile file;
  MeshBuilder builder(file);
  Tokenizer tokens(bytes, source_name);
  Tokenizer::Token t = tokens.next();
  if (!Tokenizer::is(t, "solid")) tokens.fail(t, "expected 'solid', found " + Tokenizer::describe(t));
  file.solid_name = tokens.rest_of_line();
  // Some exporters write several solids one after another; all their facets are read.
  while (true) {
    t = tokens.next();
    if (Tokenizer::is(t, "endsolid")) {
      tokens.rest_of_line();
      Tokenizer::Token after = tokens.next();
      if (after.text.empty()) break;
      if (!Tokenizer::is(after, "solid"))
        tokens.fail(after, "expected 'solid' or end of file after 'endsolid', found " + Tokenizer::describe(after));
      tokens.rest_of_line();
      continue;
    }
    if (!Tokenizer::is(t, "facet"))
      tokens.fail(t, "expected 'facet' or 'endsolid', found " + Tokenizer::describe(t) +
                         (t.text.empty() ? " (file truncated?)" : ""));
    const int facet_line = t.line;
    tokens.expect("normal");
    for (const char* what : {"normal x", "normal y", "normal z"}) tokens.number(what);
    tokens.expect("outer");
    tokens.expect("loop");
    std::array<glm::dvec3, 3> corners;
    for (int k = 0; k < 3; ++k) {
      tokens.expect("vertex");
      corners[k].x = tokens.number("vertex x");
      corners[k].y = tokens.number("vertex y");
      corners[k].z = tokens.number("vertex z");
    }
    Tokenizer::Token end_loop = tokens.next();
    if (!Tokenizer::is(end_loop, "endloop"))
      tokens.fail(end_loop, "expected 'endloop' after three vertices, found " + Tokenizer::describe(end_loop));
    tokens.expect("endfacet");
    builder.add(corners, facet_line);
  }
  finish(file, source_name);
  return file;
}

// "solid" at the start and no control bytes other than whitespace in the first kilobyte: text.
bool looks_like_ascii(const std::string& bytes) {
  size_t first = bytes.find_first_not_of(" \t\r\n");
  if (first == std::string::npos || bytes.size() < first + 5) return false;
  for (size_t i = 0; i < 5; ++i)
    if (std::tolower(static_cast<unsigned char>(bytes[first + i])) != "solid"[i]) return false;
  size_t probe = std::min<size_t>(bytes.size(), 1024);
  for (size_t i = 0; i < probe; ++i) {
    unsigned char c = static_cast<unsigned char>(bytes[i]);
    if (c < 32 && c != '\n' && c != '\r' && c != '\t') return false;
  }
  return true;
}

}  // namespace

StlFile parse_stl(const std::string& bytes, const std::string& source_name) {
  if (bytes.empty()) throw InputError(source_name, 0, 0, "file is empty");
  if (bytes.size() >= kBinaryPreambleBytes) {
    uint64_t expected = kBinaryPreambleBytes + uint64_t(read_count(bytes)) * kBinaryTriangleBytes;
    if (expected == bytes.size()) return parse_binary(bytes, source_name);
  }
  if (looks_like_ascii(bytes)) return parse_ascii(bytes, source_name);
  if (bytes.size() < kBinaryPreambleBytes)
    throw InputError(source_name, 0, 0,
                     "truncated binary STL: " + std::to_string(bytes.size()) +
                         " bytes, fewer than the 84 of the header and triangle count");
  const uint32_t count = read_count(bytes);
  const uint64_t expected = kBinaryPreambleBytes + uint64_t(count) * kBinaryTriangleBytes;
  throw InputError(source_name, 0, 0,
                   "binary STL size mismatch: the header announces " + std::to_string(count) +
                       " triangles (" + std::to_string(expected) + " bytes) but the file has " +
                       std::to_string(bytes.size()) + " bytes (" +
                       (bytes.size() < expected ? "truncated" : "bad triangle count or trailing data") + ")");
}

StlFile read_stl(const std::string& path) {
  if (auto why = why_not_input_file(path); !why.empty()) throw InputError(path, 0, 0, why);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, 0, "cannot open file");
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(path, 0, 0, "read error");
  return parse_stl(bytes, path);
}

MeshSummary summarize_mesh(const TriangleMesh& mesh) {
  MeshSummary s;
  s.triangle_count = mesh.triangles.size();
  s.vertex_count = mesh.vertices.size();
  if (!mesh.vertices.empty()) {
    s.lower = s.upper = mesh.vertices[0];
    for (const auto& v : mesh.vertices) {
      s.lower = glm::min(s.lower, v);
      s.upper = glm::max(s.upper, v);
    }
  }
  // Directed edge counts per undirected edge (lower id first).
  std::map<std::pair<uint32_t, uint32_t>, std::pair<int, int>> edges;
  for (const auto& t : mesh.triangles) {
    const glm::dvec3& a = mesh.vertices[t[0]];
    const glm::dvec3& b = mesh.vertices[t[1]];
    const glm::dvec3& c = mesh.vertices[t[2]];
    s.area += 0.5 * glm::length(glm::cross(b - a, c - a));
    s.volume += glm::dot(a, glm::cross(b, c)) / 6.0;
    for (int k = 0; k < 3; ++k) {
      uint32_t from = t[k], to = t[(k + 1) % 3];
      auto& count = edges[{std::min(from, to), std::max(from, to)}];
      (from < to ? count.first : count.second)++;
    }
  }
  for (const auto& [edge, count] : edges) {
    int uses = count.first + count.second;
    if (uses == 1) ++s.boundary_edges;
    else if (uses > 2) ++s.non_manifold_edges;
    else if (count.first != 1) ++s.misoriented_edges;
  }
  s.watertight = !mesh.triangles.empty() && s.boundary_edges == 0 && s.non_manifold_edges == 0 &&
                 s.misoriented_edges == 0;
  return s;
}

}  // namespace repose
