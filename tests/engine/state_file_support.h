// A simulation's state file as bytes, for tests that compare whole runs byte for byte.
#pragma once
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <unistd.h>

#include "engine/simulation.h"
#include "io/state_file.h"

namespace repose::test {

inline std::string state_file_bytes(const Simulation& sim, const std::string& name) {
  std::string path =
      (std::filesystem::temp_directory_path() / ("repose_test_" + std::to_string(::getpid()) + "_" + name)).string();
  write_state_file(path, sim.state(), sim.step(), sim.time());
  std::ifstream in(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), {});
  std::remove(path.c_str());
  return bytes;
}

}  // namespace repose::test
