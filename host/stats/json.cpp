#include "stats/json.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "stats/errors.h"

namespace repose::stats {

namespace {

const char* kind_name(Json::Kind k) {
  switch (k) {
    case Json::Kind::null: return "null";
    case Json::Kind::boolean: return "a boolean";
    case Json::Kind::number: return "a number";
    case Json::Kind::string: return "a string";
    case Json::Kind::array: return "an array";
    case Json::Kind::object: return "an object";
  }
  return "?";
}

}  // namespace

class JsonParser {
 public:
  JsonParser(const std::string& text, const std::string& source)
      : text_(text), source_(std::make_shared<const std::string>(source)) {}

  Json parse_document() {
    Json v = value();
    skip_space();
    if (pos_ != text_.size()) error("unexpected text after the JSON value");
    return v;
  }

 private:
  [[noreturn]] void error(const std::string& what) const { throw InputError(*source_, line_, col_, what); }

  void advance() {
    if (text_[pos_] == '\n') {
      ++line_;
      col_ = 1;
    } else {
      ++col_;
    }
    ++pos_;
  }
  void skip_space() {
    while (pos_ < text_.size() && (text_[pos_] == ' ' || text_[pos_] == '\n' || text_[pos_] == '\t' || text_[pos_] == '\r'))
      advance();
  }
  char peek() {
    skip_space();
    if (pos_ >= text_.size()) error("unexpected end of file");
    return text_[pos_];
  }
  void expect(char c) {
    if (peek() != c) error(std::string("expected '") + c + "'");
    advance();
  }
  Json located() {
    Json j;
    j.line_ = line_;
    j.column_ = col_;
    j.source_ = source_;
    return j;
  }

  Json value() {
    char c = peek();
    Json j = located();
    if (c == '{') {
      j.kind_ = Json::Kind::object;
      advance();
      if (peek() == '}') {
        advance();
        return j;
      }
      for (;;) {
        if (peek() != '"') error("expected a key in double quotes");
        std::string key = string_literal();
        expect(':');
        j.members_.emplace_back(std::move(key), value());
        if (peek() == ',') {
          advance();
          continue;
        }
        expect('}');
        return j;
      }
    }
    if (c == '[') {
      j.kind_ = Json::Kind::array;
      advance();
      if (peek() == ']') {
        advance();
        return j;
      }
      for (;;) {
        j.items_.push_back(value());
        if (peek() == ',') {
          advance();
          continue;
        }
        expect(']');
        return j;
      }
    }
    if (c == '"') {
      j.kind_ = Json::Kind::string;
      j.string_ = string_literal();
      return j;
    }
    if (literal("true")) { j.kind_ = Json::Kind::boolean; j.bool_ = true; return j; }
    if (literal("false")) { j.kind_ = Json::Kind::boolean; j.bool_ = false; return j; }
    if (literal("null")) return j;
    // Number (JSON has no NaN; the writer stores NaN as null).
    size_t start = pos_;
    while (pos_ < text_.size() && std::string("+-0123456789.eE").find(text_[pos_]) != std::string::npos) advance();
    if (pos_ == start) error(std::string("unexpected character '") + c + "'");
    std::string num = text_.substr(start, pos_ - start);
    char* end = nullptr;
    double d = std::strtod(num.c_str(), &end);
    if (end != num.c_str() + num.size()) error("'" + num + "' is not a number");
    j.kind_ = Json::Kind::number;
    j.number_ = d;
    return j;
  }

  bool literal(const char* word) {
    std::string w(word);
    if (text_.compare(pos_, w.size(), w) != 0) return false;
    for (size_t i = 0; i < w.size(); ++i) advance();
    return true;
  }

  std::string string_literal() {
    advance();  // opening quote
    std::string s;
    for (;;) {
      if (pos_ >= text_.size()) error("unterminated string");
      char c = text_[pos_];
      if (c == '"') {
        advance();
        return s;
      }
      if (c == '\\') {
        advance();
        if (pos_ >= text_.size()) error("unterminated string");
        char e = text_[pos_];
        switch (e) {
          case '"': s += '"'; break;
          case '\\': s += '\\'; break;
          case '/': s += '/'; break;
          case 'n': s += '\n'; break;
          case 't': s += '\t'; break;
          case 'r': s += '\r'; break;
          case 'b': s += '\b'; break;
          case 'f': s += '\f'; break;
          case 'u': {
            if (pos_ + 4 >= text_.size()) error("bad \\u escape");
            unsigned code = static_cast<unsigned>(std::strtoul(text_.substr(pos_ + 1, 4).c_str(), nullptr, 16));
            for (int i = 0; i < 4; ++i) advance();
            // Basic multilingual plane only, as UTF-8.
            if (code < 0x80) {
              s += static_cast<char>(code);
            } else if (code < 0x800) {
              s += static_cast<char>(0xC0 | (code >> 6));
              s += static_cast<char>(0x80 | (code & 0x3F));
            } else {
              s += static_cast<char>(0xE0 | (code >> 12));
              s += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
              s += static_cast<char>(0x80 | (code & 0x3F));
            }
            break;
          }
          default: error(std::string("bad escape '\\") + e + "'");
        }
        advance();
        continue;
      }
      s += c;
      advance();
    }
  }

  const std::string& text_;
  std::shared_ptr<const std::string> source_;
  size_t pos_ = 0;
  int line_ = 1, col_ = 1;
};

Json Json::array() {
  Json j;
  j.kind_ = Kind::array;
  return j;
}

Json Json::object() {
  Json j;
  j.kind_ = Kind::object;
  return j;
}

void Json::fail(const std::string& what) const { throw InputError(*source_, line_, column_, what); }

double Json::number() const {
  if (kind_ != Kind::number) fail(std::string("expected a number, found ") + kind_name(kind_));
  return number_;
}

const std::string& Json::string() const {
  if (kind_ != Kind::string) fail(std::string("expected a string, found ") + kind_name(kind_));
  return string_;
}

bool Json::boolean() const {
  if (kind_ != Kind::boolean) fail(std::string("expected true or false, found ") + kind_name(kind_));
  return bool_;
}

const std::vector<Json>& Json::items() const {
  if (kind_ != Kind::array) fail(std::string("expected an array, found ") + kind_name(kind_));
  return items_;
}

const std::vector<std::pair<std::string, Json>>& Json::members() const {
  if (kind_ != Kind::object) fail(std::string("expected an object, found ") + kind_name(kind_));
  return members_;
}

bool Json::has(const std::string& key) const {
  if (kind_ != Kind::object) return false;
  for (const auto& [k, v] : members_)
    if (k == key) return true;
  return false;
}

const Json& Json::at(const std::string& key) const {
  for (const auto& [k, v] : members())
    if (k == key) return v;
  fail("missing key '" + key + "'");
}

Json& Json::push(Json v) {
  if (kind_ != Kind::array) fail("push on a non-array");
  items_.push_back(std::move(v));
  return items_.back();
}

Json& Json::set(const std::string& key, Json v) {
  if (kind_ != Kind::object) fail("set on a non-object");
  for (auto& [k, old] : members_)
    if (k == key) return old = std::move(v);
  members_.emplace_back(key, std::move(v));
  return members_.back().second;
}

// Written by the program's one JSON writer (nlohmann): keys in insertion order, numbers as the
// shortest text that reads back exactly, NaN and infinity as null.
nlohmann::ordered_json Json::to_writer() const {
  switch (kind_) {
    case Kind::null: return nullptr;
    case Kind::boolean: return bool_;
    case Kind::number: return number_;
    case Kind::string: return string_;
    case Kind::array: {
      nlohmann::ordered_json a = nlohmann::ordered_json::array();
      for (const auto& v : items_) a.push_back(v.to_writer());
      return a;
    }
    case Kind::object: {
      nlohmann::ordered_json o = nlohmann::ordered_json::object();
      for (const auto& [k, v] : members_) o[k] = v.to_writer();
      return o;
    }
  }
  return nullptr;
}

std::string Json::dump(int indent) const { return to_writer().dump(indent > 0 ? indent : -1) + "\n"; }

Json Json::parse(const std::string& text, const std::string& source) {
  return JsonParser(text, source).parse_document();
}

}  // namespace repose::stats
