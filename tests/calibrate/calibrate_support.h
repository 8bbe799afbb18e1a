// Shared by the calibration tests: scratch folders, small drop-test plans (each simulation well
// under a second), the campaign database read back as comparable rows, and the binary run as a
// child process that a test can kill.
#pragma once
#include <signal.h>
#include <sqlite3.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "../cli_support.h"

namespace repose::test {

inline std::string scratch_dir(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() / ("repose_calibrate_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

inline void write_text(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
}

inline std::string read_text_file(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

inline std::string drop_case_path() { return std::string(REPOSE_SOURCE_DIR) + "/cases/calibrate/drop_stalk.toml"; }

// A 2-factor rotatable CCD (4 + 4 + 3 centre points) and 2 verification runs on the drop test
// from 0.1 m at 3 % of the Rayleigh time (e jitters by +-0.15 % with the step's phase at impact,
// ~0.2 s per simulation): 13 simulations.
inline std::string small_ccd_plan(const std::string& extra_high = "0.55") {
  return "[campaign]\nexperiment = \"drop\"\ncase = \"" + drop_case_path() + "\"\n\n"
         "[response]\nname = \"restitution\"\nmeasured = 0.44\nmeasured_sd = 0.02\nmeasured_n = 25\ntolerance = 0.01\n\n"
         "[set]\n\"experiment.drop_height\" = 0.1\n\"simulation.rayleigh_fraction\" = 0.03\n\n"
         "[[factor]]\nname = \"e\"\nkey = \"interaction.stalk/steel.restitution\"\nlow = 0.35\nhigh = " + extra_high + "\n\n"
         "[[factor]]\nname = \"G\"\nkey = \"material.stalk.shear_modulus\"\nlow = 0.5e6\nhigh = 2.0e6\n\n"
         "[design]\ntype = \"ccd\"\ncentre = 3\nmodel = \"quadratic\"\n\n[verification]\nruns = 2\n";
}

// Rows of the runs table without the columns that say where and when a run ran.
inline std::map<std::string, std::string> database_rows(const std::string& path) {
  std::map<std::string, std::string> rows;
  sqlite3* db = nullptr;
  if (sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) {
    sqlite3_close(db);
    return rows;
  }
  sqlite3_stmt* q = nullptr;
  if (sqlite3_prepare_v2(db, "SELECT run_id, plan_hash, phase, point, replicate, seed, factors, responses FROM runs", -1, &q,
                         nullptr) == SQLITE_OK) {
    while (sqlite3_step(q) == SQLITE_ROW) {
      std::string row;
      for (int c = 1; c < 8; ++c) {
        auto t = sqlite3_column_text(q, c);
        row += std::string(t ? reinterpret_cast<const char*>(t) : "") + "|";
      }
      rows[reinterpret_cast<const char*>(sqlite3_column_text(q, 0))] = row;
    }
  }
  sqlite3_finalize(q);
  sqlite3_close(db);
  return rows;
}

// Runs one SQL statement on a database, its ?s bound to `texts` in order; true when it ran.
inline bool sql_exec(const std::string& path, const std::string& sql, const std::vector<std::string>& texts = {}) {
  sqlite3* db = nullptr;
  bool ok = sqlite3_open(path.c_str(), &db) == SQLITE_OK;
  sqlite3_stmt* q = nullptr;
  ok = ok && sqlite3_prepare_v2(db, sql.c_str(), -1, &q, nullptr) == SQLITE_OK;
  for (size_t i = 0; ok && i < texts.size(); ++i)
    ok = sqlite3_bind_text(q, int(i + 1), texts[i].c_str(), -1, SQLITE_TRANSIENT) == SQLITE_OK;
  ok = ok && sqlite3_step(q) == SQLITE_DONE;
  sqlite3_finalize(q);
  sqlite3_close(db);
  return ok;
}

// The first column of the first row a query returns ("" when none).
inline std::string sql_text(const std::string& path, const std::string& sql) {
  sqlite3* db = nullptr;
  std::string out;
  sqlite3_stmt* q = nullptr;
  if (sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) == SQLITE_OK &&
      sqlite3_prepare_v2(db, sql.c_str(), -1, &q, nullptr) == SQLITE_OK && sqlite3_step(q) == SQLITE_ROW)
    if (auto t = sqlite3_column_text(q, 0)) out = reinterpret_cast<const char*>(t);
  sqlite3_finalize(q);
  sqlite3_close(db);
  return out;
}

inline int count_runs(const std::string& path) {
  if (!std::filesystem::exists(path)) return 0;
  sqlite3* db = nullptr;
  int n = -1;
  if (sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) == SQLITE_OK) {
    sqlite3_busy_timeout(db, 2000);
    sqlite3_stmt* q = nullptr;
    if (sqlite3_prepare_v2(db, "SELECT COUNT(*) FROM runs", -1, &q, nullptr) == SQLITE_OK && sqlite3_step(q) == SQLITE_ROW)
      n = sqlite3_column_int(q, 0);
    sqlite3_finalize(q);
  }
  sqlite3_close(db);
  return n;
}

inline bool have_program(const std::string& name) {
  return std::system(("command -v " + name + " > /dev/null 2>&1").c_str()) == 0;
}

}  // namespace repose::test
