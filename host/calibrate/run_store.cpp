#include "calibrate/run_store.h"

#include <sqlite3.h>

#include <chrono>
#include <ctime>
#include <filesystem>
#include <limits>
#include <sstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "util/file_lock.h"

namespace repose::calibrate {

namespace {

// A prepared statement that finalises itself.
class Statement {
 public:
  Statement(sqlite3* db, const std::string& sql) : db_(db) {
    if (sqlite3_prepare_v2(db, sql.c_str(), -1, &stmt_, nullptr) != SQLITE_OK)
      throw std::runtime_error(std::string("database: ") + sqlite3_errmsg(db) + " in: " + sql);
  }
  ~Statement() { sqlite3_finalize(stmt_); }
  void bind(int i, const std::string& s) { sqlite3_bind_text(stmt_, i, s.c_str(), int(s.size()), SQLITE_TRANSIENT); }
  void bind(int i, double v) { sqlite3_bind_double(stmt_, i, v); }
  void bind(int i, sqlite3_int64 v) { sqlite3_bind_int64(stmt_, i, v); }
  bool step() {
    int rc = sqlite3_step(stmt_);
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) return false;
    throw std::runtime_error(std::string("database: ") + sqlite3_errmsg(db_));
  }
  std::string text(int col) const {
    auto p = sqlite3_column_text(stmt_, col);
    return p ? reinterpret_cast<const char*>(p) : "";
  }
  double real(int col) const { return sqlite3_column_double(stmt_, col); }
  sqlite3_int64 integer(int col) const { return sqlite3_column_int64(stmt_, col); }

 private:
  sqlite3* db_;
  sqlite3_stmt* stmt_ = nullptr;
};

std::string utc_now() {
  std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

// DB.lock for as long as the store is open: two campaigns on one database would run the same
// runs twice and collide on inserting them.
std::unique_ptr<FileLock> lock_database(const std::string& path) {
  try {
    return std::make_unique<FileLock>(path + ".lock");
  } catch (const FileBusy& busy) {
    throw FileBusy(path + " is in use by another campaign (" + busy.holder() +
                       "): wait for it to finish, or give this one another --db", busy.holder());
  }
}

}  // namespace

RunStore::RunStore(const std::string& path, const CampaignPlan& plan, bool fresh)
    : path_(path), factor_names_(plan.factor_names()) {
  for (const auto& rig : plan.rigs) rig_names_.push_back(rig.name);
  namespace fs = std::filesystem;
  if (fs::path(path).has_parent_path()) fs::create_directories(fs::path(path).parent_path());
  lock_ = lock_database(path);
  try {
    open(plan, fresh);
  } catch (...) {
    sqlite3_close(db_);
    throw;
  }
}

void RunStore::open(const CampaignPlan& plan, bool fresh) {
  namespace fs = std::filesystem;
  const std::string& path = path_;
  if (fresh)
    for (const char* suffix : {"", "-journal", "-wal", "-shm"}) fs::remove(path + suffix);
  if (sqlite3_open(path.c_str(), &db_) != SQLITE_OK) {
    std::string msg = db_ ? sqlite3_errmsg(db_) : "out of memory";
    throw std::runtime_error(path + ": cannot open the campaign database: " + msg);
  }
  sqlite3_busy_timeout(db_, 10000);
  // Rollback journal with full sync: a committed run survives a kill (and a power cut).
  exec("PRAGMA journal_mode=DELETE; PRAGMA synchronous=FULL;");
  exec("CREATE TABLE IF NOT EXISTS plan(id INTEGER PRIMARY KEY CHECK (id = 1), hash TEXT NOT NULL, "
       "canonical TEXT NOT NULL, plan_file TEXT, created TEXT);"
       "CREATE TABLE IF NOT EXISTS runs(run_id TEXT PRIMARY KEY, plan_hash TEXT NOT NULL, phase TEXT NOT NULL, "
       "point INTEGER NOT NULL, replicate INTEGER NOT NULL, seed INTEGER NOT NULL, factors TEXT NOT NULL, "
       "responses TEXT NOT NULL, wall_s REAL, host TEXT, rank INTEGER, finished_at TEXT);");
  const std::string canonical = canonical_plan_text(plan);
  hash_ = plan_hash(canonical);
  {
    Statement q(db_, "SELECT hash, canonical, plan_file FROM plan WHERE id = 1");
    if (q.step()) {
      if (q.text(0) != hash_ && !adopt_plan_row(q.text(0), q.text(1), plan, canonical))
        throw std::runtime_error(path + ": this database belongs to another version of the plan (" + q.text(2) +
                                 "); changed since: " + describe_plan_change(q.text(1), canonical) +
                                 ". Restore the plan, or start over with --new (discards the " +
                                 "finished runs) or another --db.");
    } else {
      Statement ins(db_, "INSERT INTO plan(id, hash, canonical, plan_file, created) VALUES (1, ?, ?, ?, ?)");
      ins.bind(1, hash_);
      ins.bind(2, canonical);
      ins.bind(3, plan.path);
      ins.bind(4, utc_now());
      ins.step();
    }
  }
  load_runs();
}

RunStore::~RunStore() { sqlite3_close(db_); }

namespace {

// The hash that databases made before the plan hashed its parsed base case stored for `canonical`
// (they hashed the case's text as campaign.case_content_hash); "" when it has no case hash.
std::string case_text_era_hash(const std::string& canonical, const CampaignPlan& plan) {
  const std::string key = "campaign.case_hash = ";
  size_t at = canonical.find(key);
  if (at == std::string::npos) return "";
  size_t end = canonical.find('\n', at);
  size_t case_lines = canonical.find(kCaseLinePrefix);
  return plan_hash(canonical.substr(0, at) + "campaign.case_content_hash = " + plan_hash(plan.rigs[0].case_text) +
                   canonical.substr(end, case_lines == std::string::npos ? std::string::npos : case_lines - end));
}

// Whether `stored` is `canonical` but for an adaptive budget or a verification count that is no
// longer part of the text where the runs do not depend on it (canonical_plan_text).
bool same_but_counts(const std::string& stored, const std::string& canonical) {
  std::istringstream in(stored);
  std::string without, line;
  while (std::getline(in, line)) {
    bool count = line.rfind("adaptive.budget = ", 0) == 0 || line.rfind("verification.runs = ", 0) == 0;
    if (!count || canonical.find(line.substr(0, line.find(" = ") + 3)) != std::string::npos) without += line + "\n";
  }
  return without == canonical;
}

}  // namespace

// A database whose plan row an earlier version of Repose wrote for this same plan is adopted (its
// row rewritten to today's text) when its runs are the same ones: a row that hashed the case's
// text, held a raised or lowered count, or took the base case's values of the factors, which
// no run uses (canonical_plan_text_as_given), or any of these together.
bool RunStore::adopt_plan_row(const std::string& stored_hash, const std::string& stored_canonical,
                              const CampaignPlan& plan, const std::string& canonical) {
  for (const std::string& text : {canonical, canonical_plan_text_as_given(plan)}) {
    if (plan_hash(text) != stored_hash && case_text_era_hash(text, plan) != stored_hash &&
        !same_but_counts(stored_canonical, text))
      continue;
    Statement up(db_, "UPDATE plan SET hash = ?, canonical = ? WHERE id = 1");
    up.bind(1, hash_);
    up.bind(2, canonical);
    up.step();
    return true;
  }
  return false;
}

void RunStore::exec(const std::string& sql) {
  char* err = nullptr;
  if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &err) != SQLITE_OK) {
    std::string msg = err ? err : "unknown error";
    sqlite3_free(err);
    throw std::runtime_error(path_ + ": database: " + msg);
  }
}

namespace {

// Every row of the runs table, each run given its rig from its id's "@NAME".
std::map<std::string, RunRecord> read_runs(sqlite3* db, const std::vector<std::string>& factor_names,
                                           const std::vector<std::string>& rig_names) {
  std::map<std::string, RunRecord> runs;
  Statement q(db, "SELECT run_id, phase, point, replicate, seed, factors, responses, wall_s, host, rank FROM runs");
  while (q.step()) {
    RunRecord r;
    r.spec.id = q.text(0);
    r.spec.phase = q.text(1);
    r.spec.point = int(q.integer(2));
    r.spec.replicate = int(q.integer(3));
    r.spec.seed = uint64_t(q.integer(4));
    auto factors = nlohmann::json::parse(q.text(5));
    for (const auto& name : factor_names) r.spec.x.push_back(factors.at(name).get<double>());
    const auto responses = nlohmann::json::parse(q.text(6));  // named: items() does not extend its life
    for (auto& [k, v] : responses.items())
      r.responses[k] = v.is_null() ? std::numeric_limits<double>::quiet_NaN() : v.get<double>();  // NaN is stored as null
    r.wall_s = q.real(7);
    r.host = q.text(8);
    r.rank = int(q.integer(9));
    const size_t at = r.spec.id.rfind('@');
    for (size_t i = 1; at != std::string::npos && i < rig_names.size(); ++i)
      if (r.spec.id.compare(at + 1, std::string::npos, rig_names[i]) == 0) r.spec.rig = int(i);
    runs[r.spec.id] = r;
  }
  return runs;
}

}  // namespace

void RunStore::load_runs() { runs_ = read_runs(db_, factor_names_, rig_names_); }

std::map<std::string, RunRecord> RunStore::read_only(const std::string& path, const CampaignPlan& plan) {
  std::map<std::string, RunRecord> runs;
  if (!std::filesystem::exists(path)) return runs;
  sqlite3* db = nullptr;
  if (sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) {
    sqlite3_close(db);
    return runs;
  }
  std::vector<std::string> rigs;
  for (const auto& rig : plan.rigs) rigs.push_back(rig.name);
  try {
    sqlite3_busy_timeout(db, 2000);
    Statement q(db, "SELECT hash FROM plan WHERE id = 1");
    // Runs of another plan (another version of this one) say nothing about this plan's cost.
    if (q.step() && (q.text(0) == plan_hash(canonical_plan_text(plan)) ||
                     q.text(0) == plan_hash(canonical_plan_text_as_given(plan))))
      runs = read_runs(db, plan.factor_names(), rigs);
  } catch (const std::exception&) {
    runs.clear();  // not a campaign database: nothing to learn from it
  }
  sqlite3_close(db);
  return runs;
}

bool RunStore::has(const std::string& id) const { return runs_.count(id) > 0; }

const RunRecord* RunStore::find(const std::string& id) const {
  auto it = runs_.find(id);
  return it == runs_.end() ? nullptr : &it->second;
}

void RunStore::insert(const RunRecord& r) {
  nlohmann::ordered_json factors = nlohmann::ordered_json::object(), responses = nlohmann::ordered_json::object();
  for (size_t i = 0; i < factor_names_.size(); ++i) factors[factor_names_[i]] = r.spec.x[i];
  for (const auto& [k, v] : r.responses) responses[k] = v;
  Statement ins(db_, "INSERT INTO runs(run_id, plan_hash, phase, point, replicate, seed, factors, responses, wall_s, "
                     "host, rank, finished_at) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  ins.bind(1, r.spec.id);
  ins.bind(2, hash_);
  ins.bind(3, r.spec.phase);
  ins.bind(4, sqlite3_int64(r.spec.point));
  ins.bind(5, sqlite3_int64(r.spec.replicate));
  ins.bind(6, sqlite3_int64(r.spec.seed));
  ins.bind(7, factors.dump());
  ins.bind(8, responses.dump());
  ins.bind(9, r.wall_s);
  ins.bind(10, r.host);
  ins.bind(11, sqlite3_int64(r.rank));
  ins.bind(12, utc_now());
  ins.step();  // autocommit: this row is its own transaction
  runs_[r.spec.id] = r;
}

}  // namespace repose::calibrate
