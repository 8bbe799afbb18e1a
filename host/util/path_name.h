// Names that become part of a path (a case's name in its frames and default folder, a plan's in
// its folder) must stay inside the folder they are put in: case files are shared between people,
// and "../../x" would write anywhere.
#pragma once
#include <string>

namespace repose {

// "" when `name` can be one part of a path; otherwise why not.
inline std::string why_not_path_name(const std::string& name) {
  if (name.empty()) return "an empty name cannot name files";
  if (name == "." || name == "..") return "'" + name + "' names a folder, not a file";
  for (unsigned char c : name) {
    if (c == '/' || c == '\\') return "'" + name + "' holds a path separator: a name must stay inside its folder";
    if (c < 0x20 || c == 0x7f) return "the name holds a control character";
  }
  if (name.size() > 200) return "a name of " + std::to_string(name.size()) + " characters is too long for a file name";
  return "";
}

}  // namespace repose
