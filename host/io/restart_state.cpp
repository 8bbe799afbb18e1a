#include "io/restart_state.h"

#include "io/state_validation.h"
#include "util/input_error.h"
#include "util/number_text.h"

namespace repose {

RestartPoint read_restart_state(const std::string& path, const Model& model, const std::string& case_hash) {
  auto refuse = [&](const std::string& what) { throw InputError(path, 0, 0, what); };
  RestartPoint start;
  start.state = read_state_file(path, start.info);
  const StateFileInfo& info = start.info;
  if (!info.restartable())
    refuse("a version " + std::to_string(info.version) + " state file, without the checksum and case identity of "
           "version " + std::to_string(kRestartableStateVersion) + " on: it reads (for cmp), but a run cannot continue from it");
  if (info.case_hash != case_hash)
    refuse("written by a run of case " + (info.case_hash.empty() ? std::string("(not recorded)") : info.case_hash) +
           ", not of this case (" + case_hash + ", with its --set values): continue with the case and --set values "
           "it was run with");
  if (info.time != double(info.step) * model.dt)
    refuse("written with another time step than this case's (t = " + format_g(info.time, 6) + " s at step " +
           std::to_string(info.step) + "): restart with the case and --set values it was run with");
  if (std::string misfit = state_misfit(start.state, model); !misfit.empty())
    refuse("does not fit the case: " + misfit);
  return start;
}

}  // namespace repose
