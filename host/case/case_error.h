// The one exception a case file's problems are reported with, worded for the person who wrote
// the file: "FILE:LINE: KEY: what is wrong" (TOML syntax errors: "FILE:LINE:COLUMN: ...").
#pragma once
#include <cstdio>
#include <stdexcept>
#include <string>

#include "case/case_spec.h"
#include "util/input_error.h"
#include "util/number_text.h"

namespace repose {

class CaseError : public BadInput {
 public:
  CaseError(const SourceRef& where, const std::string& problem, int column = 0)
      : BadInput(format(where, problem, column)),
        where_(where),
        problem_(problem),
        column_(column) {}

  const SourceRef& where() const { return where_; }
  const std::string& problem() const { return problem_; }
  int column() const { return column_; }

  // Line 0 means the value has no line (it came from an override or is missing entirely):
  // the message then reads "FILE: KEY: problem".
  static std::string format(const SourceRef& where, const std::string& problem, int column = 0) {
    // append() rather than operator+: g++ 12 at -O3 raises a false -Wrestrict on the latter.
    std::string text = where.file;
    if (where.line > 0) text.append(":").append(std::to_string(where.line));
    if (where.line > 0 && column > 0) text.append(":").append(std::to_string(column));
    text.append(": ");
    if (!where.key.empty()) text.append(where.key).append(": ");
    return text.append(problem);
  }

 private:
  SourceRef where_;
  std::string problem_;
  int column_ = 0;
};

// A number as case-file messages quote it: 6 significant digits.
inline std::string format_number(double value) { return format_g(value, 6); }

}  // namespace repose
