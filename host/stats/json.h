// A small JSON value with a parser that remembers where each value was (line, column), so a
// malformed or incomplete fit file is reported at the place to fix. It is written by the
// program's one JSON writer, nlohmann (dump): insertion order, numbers that read back exactly.
#pragma once
#include <map>
#include <nlohmann/json.hpp>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace repose::stats {

class Json {
 public:
  enum class Kind { null, boolean, number, string, array, object };

  Json() = default;
  Json(bool b) : kind_(Kind::boolean), bool_(b) {}
  Json(double d) : kind_(Kind::number), number_(d) {}
  Json(int i) : kind_(Kind::number), number_(i) {}
  Json(const char* s) : kind_(Kind::string), string_(s) {}
  Json(std::string s) : kind_(Kind::string), string_(std::move(s)) {}
  static Json array();
  static Json object();

  Kind kind() const { return kind_; }
  bool is_null() const { return kind_ == Kind::null; }

  // Typed access; throws InputError naming `source`, line and column on a type mismatch.
  double number() const;
  const std::string& string() const;
  bool boolean() const;
  const std::vector<Json>& items() const;
  const Json& at(const std::string& key) const;  // throws when the key is missing
  bool has(const std::string& key) const;
  const std::vector<std::pair<std::string, Json>>& members() const;

  // Building.
  Json& push(Json v);                        // arrays
  Json& set(const std::string& key, Json v);  // objects, keeps insertion order

  std::string dump(int indent = 2) const;
  static Json parse(const std::string& text, const std::string& source);

  int line() const { return line_; }
  int column() const { return column_; }
  const std::string& source() const { return *source_; }

 private:
  friend class JsonParser;
  [[noreturn]] void fail(const std::string& what) const;
  nlohmann::ordered_json to_writer() const;

  Kind kind_ = Kind::null;
  bool bool_ = false;
  double number_ = 0;
  std::string string_;
  std::vector<Json> items_;
  std::vector<std::pair<std::string, Json>> members_;
  int line_ = 0, column_ = 0;
  std::shared_ptr<const std::string> source_ = std::make_shared<const std::string>();
};

}  // namespace repose::stats
