// Typed errors of the statistics library. Each names what the user must fix: a table cell
// (file, line, column), a design request, a model that the data cannot support, or a
// calibration curve that cannot be inverted. The CLI prints what() and exits non-zero.
#pragma once
#include <stdexcept>
#include <string>

namespace repose::stats {

class StatsError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A problem located in an input file. line and column are 1-based; 0 means "not applicable"
// (e.g. a whole-file problem has neither, a missing column names the header line only).
class InputError : public StatsError {
 public:
  InputError(std::string file, int line, int column, const std::string& what)
      : StatsError(locate(file, line, column) + what), file_(std::move(file)), line_(line),
        column_(column) {}
  const std::string& file() const { return file_; }
  int line() const { return line_; }
  int column() const { return column_; }

 private:
  static std::string locate(const std::string& file, int line, int column) {
    // append() rather than operator+ chains: GCC 12 gives false -Wrestrict warnings on those.
    std::string s = file.empty() ? std::string("<input>") : file;
    if (line > 0) s.append(":").append(std::to_string(line));
    if (column > 0) s.append(":").append(std::to_string(column));
    s.append(": ");
    return s;
  }
  std::string file_;
  int line_, column_;
};

// A CSV table that cannot be read or used as asked (missing column, non-numeric cell, ...).
class TableError : public InputError {
 public:
  using InputError::InputError;
};

// A design that cannot be built as requested (reversed range, unknown generator letter, ...).
class DesignError : public StatsError {
 public:
  using StatsError::StatsError;
};

// A model the data cannot support (fewer runs than terms, aliased terms, ...).
class ModelError : public StatsError {
 public:
  using StatsError::StatsError;
};

// A calibration curve that cannot be inverted at the requested value.
class CurveError : public StatsError {
 public:
  using StatsError::StatsError;
};

}  // namespace repose::stats
