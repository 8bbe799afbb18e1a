// Reading one TOML table of an input file (a case, a calibration plan) with every problem located:
// a Section knows its key path for messages ("fill[2].box") and reports problems as CaseError
// "FILE:LINE: KEY: what is wrong" at the offending value's line, or the table's when the value is
// missing; unknown keys come with the nearest allowed key (did you mean ...).
#pragma once
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "case/case_error.h"
#include "case/spelling.h"

namespace repose {

// 'a', 'b', 'c': words as messages list them.
std::string quoted_list(const std::vector<std::string>& words);
// "a string", "an integer", ...: what a TOML value is, for messages.
const char* type_name(const toml::node& node);
inline int line_of(const toml::node& node) { return int(node.source().begin.line); }

// One TOML table being read: knows its key path for messages ("fill[2].box") and reports
// problems at the line of the offending value, or of the table when the value is missing.
class Section {
 public:
  Section(const toml::table& table, std::string prefix, const std::string& file)
      : table_(table), prefix_(std::move(prefix)), file_(file) {}

  std::string key(std::string_view k) const {
    return prefix_.empty() ? std::string(k) : prefix_ + "." + std::string(k);
  }
  SourceRef where() const { return {file_, prefix_, line_of(table_)}; }
  SourceRef where(std::string_view k) const {
    const toml::node* node = table_.get(k);
    return {file_, key(k), line_of(node ? *node : table_)};
  }
  [[noreturn]] void fail(std::string_view k, const std::string& problem) const {
    throw CaseError(where(k), problem);
  }
  [[noreturn]] void fail(const std::string& problem) const { throw CaseError(where(), problem); }

  // Unknown keys are reported first, the earliest in the file, with the nearest allowed key.
  void allow_only(const std::vector<std::string>& allowed, const std::string& context) const {
    const toml::key* unknown = nullptr;
    for (auto&& [k, node] : table_) {
      if (std::find(allowed.begin(), allowed.end(), k.str()) != allowed.end()) continue;
      if (!unknown || k.source().begin.line < unknown->source().begin.line) unknown = &k;
    }
    if (!unknown) return;
    throw CaseError({file_, key(unknown->str()), int(unknown->source().begin.line)},
                    "unknown key in " + context + did_you_mean(unknown->str(), allowed) +
                        " (allowed: " + quoted_list(allowed) + ")");
  }

  bool has(std::string_view k) const { return table_.contains(k); }
  const toml::table& table() const { return table_; }
  const std::string& file() const { return file_; }

  [[noreturn]] void missing(std::string_view k, const std::string& hint = "") const {
    fail(k, "missing required value" + hint);
  }
  [[noreturn]] void wrong_type(std::string_view k, const std::string& expected) const {
    fail(k, "expected " + expected + ", got " + type_name(*table_.get(k)));
  }

  std::optional<double> number(std::string_view k) const {
    const toml::node* node = table_.get(k);
    if (!node) return std::nullopt;
    if (!node->is_number()) wrong_type(k, "a number");
    double value = node->is_integer() ? double(node->as_integer()->get()) : node->as_floating_point()->get();
    if (!std::isfinite(value)) fail(k, "must be a finite number");
    return value;
  }
  double required_number(std::string_view k, const std::string& hint = "") const {
    if (auto value = number(k)) return *value;
    missing(k, hint);
  }
  std::optional<int64_t> integer(std::string_view k) const {
    const toml::node* node = table_.get(k);
    if (!node) return std::nullopt;
    if (!node->is_integer()) wrong_type(k, "an integer");
    return node->as_integer()->get();
  }
  std::optional<std::string> text(std::string_view k) const {
    const toml::node* node = table_.get(k);
    if (!node) return std::nullopt;
    if (!node->is_string()) wrong_type(k, "a string");
    return node->as_string()->get();
  }
  std::string required_text(std::string_view k, const std::string& hint = "") const {
    if (auto value = text(k)) return *value;
    missing(k, hint);
  }
  std::optional<bool> boolean(std::string_view k) const {
    const toml::node* node = table_.get(k);
    if (!node) return std::nullopt;
    if (!node->is_boolean()) wrong_type(k, "true or false");
    return node->as_boolean()->get();
  }
  std::optional<Vec3d> vector3(std::string_view k) const {
    const toml::node* node = table_.get(k);
    if (!node) return std::nullopt;
    const toml::array* array = node->as_array();
    if (!array || array->size() != 3 || !all_numbers(*array))
      fail(k, std::string("expected an array of 3 numbers [x, y, z], got ") +
                  (array ? std::to_string(array->size()) + "-element array" : type_name(*node)));
    Vec3d value;
    for (size_t i = 0; i < 3; ++i) {
      const toml::node& element = *array->get(i);
      value[i] = element.is_integer() ? double(element.as_integer()->get())
                                      : element.as_floating_point()->get();
      if (!std::isfinite(value[i])) fail(k, "must hold finite numbers");
    }
    return value;
  }
  Vec3d required_vector3(std::string_view k) const {
    if (auto value = vector3(k)) return *value;
    missing(k, " (an array of 3 numbers [x, y, z])");
  }
  std::optional<Section> sub(std::string_view k) const {
    const toml::node* node = table_.get(k);
    if (!node) return std::nullopt;
    if (!node->is_table()) wrong_type(k, "a table such as { key = value, ... }");
    return Section(*node->as_table(), key(k), file_);
  }

  // One of a fixed set of words, mapped to an enum.
  template <class Enum>
  Enum choice(std::string_view k, const std::vector<std::pair<std::string, Enum>>& options,
              Enum fallback) const {
    auto value = text(k);
    if (!value) return fallback;
    std::vector<std::string> words;
    for (const auto& [word, option] : options) {
      if (word == *value) return option;
      words.push_back(word);
    }
    fail(k, "'" + *value + "' is not one of " + quoted_list(words) + did_you_mean(*value, words));
  }

 private:
  static bool all_numbers(const toml::array& array) {
    return std::all_of(array.begin(), array.end(), [](const toml::node& n) { return n.is_number(); });
  }

  const toml::table& table_;
  std::string prefix_;
  const std::string& file_;  // owned by the reader, which outlives its sections
};

// Checked values, failing with a message that states the rule broken.
double positive(const Section& s, std::string_view k, double value);
double non_negative(const Section& s, std::string_view k, double value);
Vec3d unit_vector(const Section& s, std::string_view k, const Vec3d& v);

}  // namespace repose
