// The campaign database (SQLite): the plan it belongs to and one row per finished run, each
// inserted in its own transaction, so a campaign killed at any moment keeps every finished run
// and no half row. A database made for another plan is refused with what changed.
#pragma once
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "calibrate/plan.h"
#include "calibrate/run_spec.h"
#include "util/file_lock.h"

struct sqlite3;

namespace repose::calibrate {

class RunStore {
 public:
  // Opens (creating if needed) the database at `path` for `plan`. With `fresh`, an existing
  // database is replaced. Throws std::runtime_error when the stored plan differs, or when another
  // campaign has the database open (a lock on PATH.lock, held until this store closes).
  RunStore(const std::string& path, const CampaignPlan& plan, bool fresh);
  ~RunStore();
  RunStore(const RunStore&) = delete;
  RunStore& operator=(const RunStore&) = delete;

  bool has(const std::string& run_id) const;
  const RunRecord* find(const std::string& run_id) const;
  // Commits one run (its own transaction); throws on a duplicate id or a write failure.
  void insert(const RunRecord& record);
  std::size_t size() const { return runs_.size(); }
  const std::map<std::string, RunRecord>& runs() const { return runs_; }  // by id
  // The runs of a database made for this same plan, read without locking or writing (for
  // `--check`); empty when there is none or it belongs to another plan.
  static std::map<std::string, RunRecord> read_only(const std::string& path, const CampaignPlan& plan);
  const std::string& path() const { return path_; }

 private:
  void open(const CampaignPlan& plan, bool fresh);
  bool adopt_plan_row(const std::string& stored_hash, const std::string& stored_canonical, const CampaignPlan& plan,
                      const std::string& canonical);
  void exec(const std::string& sql);
  void load_runs();

  std::string path_;
  std::string hash_;
  std::vector<std::string> factor_names_;
  std::vector<std::string> rig_names_;  // to give each stored run its rig (from its id's "@NAME")
  sqlite3* db_ = nullptr;
  std::unique_ptr<FileLock> lock_;  // PATH.lock while this store is open
  std::map<std::string, RunRecord> runs_;
};

}  // namespace repose::calibrate
