// The one error type for a problem located in an input file (an STL, a sphere CSV, a data table,
// a fit file): it names the file, and the line and column when known, in the compiler style
// "file:line:column: message" that editors can jump to. (Case files and measured data have their
// own, CaseError and DataError, which also name the key or column.)
#pragma once
#include <stdexcept>
#include <string>

namespace repose {

// What every error in what the user gave derives from (a case, a data file, a flag, an output
// folder, a state file to restart from): `repose` then exits with code 2, and with 1 for a
// failure while working (README, "Exit codes").
class BadInput : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class InputError : public BadInput {
 public:
  // line and column are 1-based; 0 means "not applicable" and is left out of the message; a file
  // without a name (text parsed from memory) shows as "<input>".
  InputError(std::string file, int line, int column, const std::string& message)
      : BadInput(format(file, line, column, message)),
        file_(std::move(file)),
        line_(line),
        column_(column) {}

  const std::string& file() const { return file_; }
  int line() const { return line_; }
  int column() const { return column_; }

 private:
  static std::string format(const std::string& file, int line, int column, const std::string& message) {
    // append() rather than operator+ chains: GCC 12 gives false -Wrestrict warnings on those.
    std::string where = file.empty() ? std::string("<input>") : file;
    if (line > 0) where.append(":").append(std::to_string(line));
    if (line > 0 && column > 0) where.append(":").append(std::to_string(column));
    where.append(": ").append(message);
    return where;
  }

  std::string file_;
  int line_;
  int column_;
};

}  // namespace repose
