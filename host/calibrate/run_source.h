// Where a campaign's runs come from: simulated and kept in the campaign database (Executor and
// RunStore), or, in tests, a seeded function of the parameters. The campaign's logic (designs, the
// loop, the verification) sees only this, so the statistics are tested on the same code that runs
// simulations.
#pragma once
#include <string>
#include <vector>

#include "calibrate/run_spec.h"

namespace repose::calibrate {

class RunSource {
 public:
  virtual ~RunSource() = default;
  // Makes sure every spec has a result: runs those that have none yet. Throws when a run fails,
  // or when a result is held at other parameters than the spec's.
  virtual void run(const std::vector<RunSpec>& specs, const std::string& label) = 0;
  virtual const RunRecord* find(const std::string& id) const = 0;
  virtual std::string where() const = 0;  // for messages: the database's path
};

}  // namespace repose::calibrate
