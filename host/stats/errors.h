// Typed errors of the statistics library. Each names what the user must fix: a table cell
// (file, line, column), a design request, a model that the data cannot support, or a
// calibration curve that cannot be inverted. The CLI prints what() and exits non-zero.
#pragma once
#include <stdexcept>
#include <string>

#include "util/input_error.h"

namespace repose::stats {

class StatsError : public BadInput {  // what the user must fix: exit code 2
 public:
  using BadInput::BadInput;
};

// A problem located in an input file (a whole-file problem has neither line nor column, a
// missing column names the header line only): the program's one located-input error.
using InputError = repose::InputError;

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
