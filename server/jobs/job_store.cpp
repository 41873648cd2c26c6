#include "jobs/job_store.hpp"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <ctime>
#include <stdexcept>

#include <sqlite3.h>

namespace rupture::server {
namespace {

/// Throws the store's error for SQLite's last failure on `db`: StoreFullError when the disk (or a
/// quota) is full, whether SQLite says so (SQLITE_FULL) or only reports the system's ENOSPC under
/// an I/O error (growing the WAL index, syncing), else std::runtime_error.
[[noreturn]] void throwStoreError(sqlite3* db, int rc, const std::string& message) {
  const int err = db && (rc & 0xff) == SQLITE_IOERR ? sqlite3_system_errno(db) : 0;
  if ((rc & 0xff) == SQLITE_FULL || err == ENOSPC || err == EDQUOT) {
    const bool said = message.find("database or disk is full") != std::string::npos;
    throw StoreFullError(message + (said ? "" : " (No space left on device)"));
  }
  throw std::runtime_error(message);
}

/// A prepared statement with positional binding and typed column access.
class Stmt {
public:
  Stmt(sqlite3* db, const char* sql) : m_db(db) {
    if (sqlite3_prepare_v2(db, sql, -1, &m_stmt, nullptr) != SQLITE_OK) fail("prepare");
  }
  ~Stmt() { sqlite3_finalize(m_stmt); }
  Stmt(const Stmt&) = delete;
  Stmt& operator=(const Stmt&) = delete;

  Stmt& bind(int i, std::int64_t v) { check(sqlite3_bind_int64(m_stmt, i, v)); return *this; }
  Stmt& bind(int i, int v) { check(sqlite3_bind_int64(m_stmt, i, v)); return *this; }
  Stmt& bind(int i, double v) { check(sqlite3_bind_double(m_stmt, i, v)); return *this; }
  Stmt& bind(int i, const std::string& v) {
    check(sqlite3_bind_text(m_stmt, i, v.data(), static_cast<int>(v.size()), SQLITE_TRANSIENT));
    return *this;
  }
  Stmt& bindNull(int i) { check(sqlite3_bind_null(m_stmt, i)); return *this; }

  /// Steps once; true while a row is available.
  bool step() {
    int rc = sqlite3_step(m_stmt);
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) return false;
    fail("step");
    return false;
  }
  void run() { while (step()) {} }
  void reset() { sqlite3_reset(m_stmt); sqlite3_clear_bindings(m_stmt); }

  std::int64_t i64(int c) const { return sqlite3_column_int64(m_stmt, c); }
  double dbl(int c) const { return sqlite3_column_double(m_stmt, c); }
  bool isNull(int c) const { return sqlite3_column_type(m_stmt, c) == SQLITE_NULL; }
  std::string text(int c) const {
    const unsigned char* t = sqlite3_column_text(m_stmt, c);
    return t ? std::string(reinterpret_cast<const char*>(t), sqlite3_column_bytes(m_stmt, c)) : std::string();
  }
  Json json(int c) const { return isNull(c) ? Json() : Json::parse(text(c)); }

private:
  void check(int rc) { if (rc != SQLITE_OK) fail("bind"); }
  [[noreturn]] void fail(const char* what) const {
    throwStoreError(m_db, sqlite3_extended_errcode(m_db), std::string("job store: sqlite ") + what + ": " + sqlite3_errmsg(m_db));
  }
  sqlite3* m_db;
  sqlite3_stmt* m_stmt = nullptr;
};

/// BEGIN IMMEDIATE ... COMMIT, rolled back when an exception leaves the scope.
class Transaction {
public:
  explicit Transaction(sqlite3* db) : m_db(db) { execSql("BEGIN IMMEDIATE"); }
  ~Transaction() {
    if (!m_done) sqlite3_exec(m_db, "ROLLBACK", nullptr, nullptr, nullptr);
  }
  void commit() { execSql("COMMIT"); m_done = true; }

private:
  void execSql(const char* sql) {
    char* err = nullptr;
    if (const int rc = sqlite3_exec(m_db, sql, nullptr, nullptr, &err); rc != SQLITE_OK) {
      std::string msg = err ? err : "unknown";
      sqlite3_free(err);
      throwStoreError(m_db, rc, std::string("job store: ") + sql + ": " + msg);
    }
  }
  sqlite3* m_db;
  bool m_done = false;
};

constexpr const char* kSchema = R"sql(
CREATE TABLE IF NOT EXISTS meta(key TEXT PRIMARY KEY, value TEXT NOT NULL);
INSERT OR IGNORE INTO meta(key, value) VALUES('schema_version', '1');
CREATE TABLE IF NOT EXISTS jobs(
  id          INTEGER PRIMARY KEY AUTOINCREMENT,
  process_id  TEXT NOT NULL,
  name        TEXT NOT NULL DEFAULT '',
  status      TEXT NOT NULL CHECK(status IN ('accepted','running','successful','failed','dismissed')),
  sweep_mode  TEXT NOT NULL,
  swept_paths TEXT NOT NULL,          -- JSON array of dotted paths
  inputs      TEXT NOT NULL,          -- JSON, as posted
  sweep       TEXT NOT NULL,          -- JSON, as posted
  message     TEXT NOT NULL DEFAULT '',
  created     TEXT NOT NULL,
  started     TEXT,
  finished    TEXT,
  updated     TEXT NOT NULL
);
CREATE INDEX IF NOT EXISTS jobs_by_status ON jobs(status);
CREATE TABLE IF NOT EXISTS runs(
  job_id      INTEGER NOT NULL REFERENCES jobs(id) ON DELETE CASCADE,
  idx         INTEGER NOT NULL,
  swept       TEXT NOT NULL,          -- JSON array aligned with jobs.swept_paths
  spec        TEXT NOT NULL,          -- JSON, the full spec
  status      TEXT NOT NULL CHECK(status IN ('accepted','running','successful','failed','dismissed')),
  progress    REAL NOT NULL DEFAULT 0,
  summary     TEXT,                   -- JSON object once successful
  error       TEXT,
  result_path TEXT,                   -- relative to the data directory
  started     TEXT,
  finished    TEXT,
  updated     TEXT NOT NULL,
  attempts    INTEGER NOT NULL DEFAULT 0,
  PRIMARY KEY(job_id, idx)
) WITHOUT ROWID;
CREATE INDEX IF NOT EXISTS runs_by_status ON runs(status, job_id, idx);
CREATE TABLE IF NOT EXISTS idempotency_keys(  -- POST Idempotency-Key -> the job it created
  key          TEXT PRIMARY KEY,
  request_hash TEXT NOT NULL,
  job_id       INTEGER NOT NULL REFERENCES jobs(id) ON DELETE CASCADE,
  created      TEXT NOT NULL
);
)sql";

constexpr const char* kJobColumns =
    "id, process_id, name, status, sweep_mode, swept_paths, inputs, sweep, message, created, started, "
    "finished, updated, study, provenance, request";

constexpr const char* kRunColumns =
    "job_id, idx, swept, spec, status, progress, summary, error, result_path, started, finished, updated, "
    "attempts, replicate, stage, spec_is_patch, rate_from, rate_from_progress, resumes, resumed_from_step";

Status statusFrom(const std::string& text) {
  auto s = parseStatus(text);
  if (!s) throw std::runtime_error("job store: unknown status '" + text + "'");
  return *s;
}

JobRecord readJob(const Stmt& q) {
  JobRecord j;
  j.id = q.i64(0);
  j.processId = q.text(1);
  j.name = q.text(2);
  j.status = statusFrom(q.text(3));
  j.sweepMode = q.text(4);
  j.sweptPaths = q.json(5);
  j.inputs = q.json(6);
  j.sweep = q.json(7);
  j.message = q.text(8);
  j.created = q.text(9);
  j.started = q.text(10);
  j.finished = q.text(11);
  j.updated = q.text(12);
  j.study = q.json(13);
  j.provenance = q.json(14);
  j.request = q.json(15);
  return j;
}

RunRecord readRun(const Stmt& q) {
  RunRecord r;
  r.key = {q.i64(0), static_cast<int>(q.i64(1))};
  r.swept = q.json(2);
  (q.i64(15) != 0 ? r.specPatch : r.spec) = q.json(3);
  r.status = statusFrom(q.text(4));
  r.progress = q.dbl(5);
  r.summary = q.json(6);
  r.error = q.text(7);
  r.resultPath = q.text(8);
  r.started = q.text(9);
  r.finished = q.text(10);
  r.updated = q.text(11);
  r.attempts = static_cast<int>(q.i64(12));
  r.replicate = static_cast<int>(q.i64(13));
  r.stage = q.text(14);
  r.rateFrom = q.text(16);
  r.rateFromProgress = q.dbl(17);
  r.resumes = static_cast<int>(q.i64(18));
  r.resumedFromStep = q.isNull(19) ? -1 : q.i64(19);
  return r;
}

/// Fills the run counts and progress of a job.
void addCounts(sqlite3* db, JobRecord& j) {
  Stmt q(db, "SELECT status, COUNT(*), SUM(progress) FROM runs WHERE job_id = ? GROUP BY status");
  q.bind(1, j.id);
  double done = 0;
  while (q.step()) {
    const Status s = statusFrom(q.text(0));
    const int n = static_cast<int>(q.i64(1));
    j.runsTotal += n;
    switch (s) {
      case Status::Accepted: j.runsAccepted = n; break;
      case Status::Running: j.runsRunning = n; done += q.dbl(2); break;
      case Status::Successful: j.runsSuccessful = n; done += n; break;
      case Status::Failed: j.runsFailed = n; done += q.dbl(2); break;  // as far as it got
      case Status::Dismissed: j.runsDismissed = n; done += q.dbl(2); break;  // what actually ran
    }
  }
  j.progress = j.runsTotal ? std::clamp(done / j.runsTotal, 0.0, 1.0) : 0.0;
  Stmt u(db, "SELECT MAX(updated) FROM runs WHERE job_id = ?");
  u.bind(1, j.id);
  if (u.step() && !u.isNull(0)) j.runsUpdated = u.text(0);
}

}  // namespace

const char* toString(Status status) {
  switch (status) {
    case Status::Accepted: return "accepted";
    case Status::Running: return "running";
    case Status::Successful: return "successful";
    case Status::Failed: return "failed";
    case Status::Dismissed: return "dismissed";
  }
  return "accepted";
}

std::optional<Status> parseStatus(const std::string& text) {
  for (Status s : {Status::Accepted, Status::Running, Status::Successful, Status::Failed, Status::Dismissed}) {
    if (text == toString(s)) return s;
  }
  return std::nullopt;
}

JobStore::JobStore(const std::string& path) {
  const int flags = SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE | SQLITE_OPEN_FULLMUTEX;
  if (sqlite3_open_v2(path.c_str(), &m_db, flags, nullptr) != SQLITE_OK) {
    std::string msg = m_db ? sqlite3_errmsg(m_db) : "out of memory";
    sqlite3_close(m_db);
    throw std::runtime_error("job store: cannot open " + path + ": " + msg);
  }
  sqlite3_busy_timeout(m_db, 5000);
  exec("PRAGMA journal_mode=WAL");
  exec("PRAGMA synchronous=FULL");  // a committed status survives power loss, not only a crash
  exec("PRAGMA foreign_keys=ON");
  exec(kSchema);
  migrate();
}

void JobStore::migrate() {
  // Studies (replicates, refinement): a JSON column per job and a replicate index per run; live
  // progress: the run's stage message. A database from before gets them with their neutral values.
  if (!hasColumn("jobs", "study")) exec("ALTER TABLE jobs ADD COLUMN study TEXT");
  if (!hasColumn("jobs", "provenance")) exec("ALTER TABLE jobs ADD COLUMN provenance TEXT");
  if (!hasColumn("jobs", "request")) exec("ALTER TABLE jobs ADD COLUMN request TEXT");
  if (!hasColumn("runs", "replicate")) exec("ALTER TABLE runs ADD COLUMN replicate INTEGER NOT NULL DEFAULT 0");
  if (!hasColumn("runs", "stage")) exec("ALTER TABLE runs ADD COLUMN stage TEXT NOT NULL DEFAULT ''");
  // 1: runs.spec holds a JSON Patch against the job's base spec (the inputs are stored once per job).
  if (!hasColumn("runs", "spec_is_patch"))
    exec("ALTER TABLE runs ADD COLUMN spec_is_patch INTEGER NOT NULL DEFAULT 0");
  // The run's rate anchor (its first progress above 0, and when), for an ETA from its own rate.
  if (!hasColumn("runs", "rate_from")) exec("ALTER TABLE runs ADD COLUMN rate_from TEXT");
  if (!hasColumn("runs", "rate_from_progress")) exec("ALTER TABLE runs ADD COLUMN rate_from_progress REAL");
  if (!hasColumn("runs", "resumes")) exec("ALTER TABLE runs ADD COLUMN resumes INTEGER NOT NULL DEFAULT 0");
  if (!hasColumn("runs", "resumed_from_step")) exec("ALTER TABLE runs ADD COLUMN resumed_from_step INTEGER");
}

JobStore::~JobStore() { sqlite3_close(m_db); }

bool JobStore::hasColumn(const std::string& table, const std::string& column) {
  Stmt q(m_db, "SELECT 1 FROM pragma_table_info(?) WHERE name = ?");
  q.bind(1, table).bind(2, column);
  return q.step();
}

void JobStore::exec(const std::string& sql) {
  char* err = nullptr;
  if (const int rc = sqlite3_exec(m_db, sql.c_str(), nullptr, nullptr, &err); rc != SQLITE_OK) {
    std::string msg = err ? err : "unknown";
    sqlite3_free(err);
    throwStoreError(m_db, rc, "job store: " + msg);
  }
}

std::int64_t JobStore::createJob(const NewJob& job) { return createJobOnce(job).id; }

std::optional<IdempotentJob> JobStore::jobForIdempotencyKey(const std::string& key) {
  std::lock_guard lock(m_mutex);
  Stmt q(m_db, "SELECT job_id, request_hash FROM idempotency_keys WHERE key = ?");
  q.bind(1, key);
  if (!q.step()) return std::nullopt;
  return IdempotentJob{q.i64(0), q.text(1)};
}

Json jobBaseSpec(const std::string& processId, const Json& inputs) {
  Json base = Json::object();
  base["scenario"] = processId;
  for (const auto& [key, value] : inputs.items()) {
    if (key != "scenario") base[key] = value;
  }
  return base;
}

Json submittedRequest(const JobRecord& job) {
  Json request = job.request.is_object() ? job.request : Json::object();
  if (!job.request.is_object()) {  // a job from before the body was kept: rebuilt from its parts
    if (job.sweep.is_object() && !job.sweep.empty()) {
      request["sweep"] = job.sweep;
      request["sweep_mode"] = job.sweepMode;
    }
    if (!job.name.empty()) request["name"] = job.name;
    if (job.study.is_object()) {
      if (job.study.contains("replicates")) request["replicates"] = job.study["replicates"];
      if (job.study.contains("refine")) request["refine"] = job.study["refine"];
    }
  }
  request["inputs"] = job.inputs;
  return request;
}

Json runSpec(const JobRecord& job, const RunRecord& run) {
  if (!run.spec.is_null() || run.specPatch.is_null()) return run.spec;
  return jobBaseSpec(job.processId, job.inputs).patch(run.specPatch);
}

namespace {

/// Each run's spec as the text of its patch against the job's base spec, computed before the store
/// is locked (a diff walks the whole spec).
std::vector<std::string> specPatches(const std::string& processId, const Json& inputs,
                                     const std::vector<std::pair<Json, Json>>& runs) {
  const Json base = jobBaseSpec(processId, inputs);
  std::vector<std::string> out;
  out.reserve(runs.size());
  for (const auto& run : runs) out.push_back(Json::diff(base, run.second).dump());
  return out;
}

}  // namespace

CreatedJob JobStore::createJobOnce(const NewJob& job) {
  const std::vector<std::string> patches =
      job.runPatches.empty() ? specPatches(job.processId, job.inputs, job.runs) : job.runPatches;
  if (patches.size() != job.runs.size())
    throw std::logic_error("job store: " + std::to_string(patches.size()) + " spec patches for " +
                           std::to_string(job.runs.size()) + " runs");
  std::lock_guard lock(m_mutex);
  const std::string now = utcNow();
  Transaction tx(m_db);
  if (!job.idempotencyKey.empty()) {
    Stmt q(m_db, "SELECT job_id, request_hash FROM idempotency_keys WHERE key = ?");
    q.bind(1, job.idempotencyKey);
    if (q.step()) return CreatedJob{q.i64(0), false, q.text(1)};
  }
  Stmt insertJob(m_db,
                 "INSERT INTO jobs(process_id, name, status, sweep_mode, swept_paths, inputs, sweep, "
                 "message, created, updated, study, provenance, request) VALUES(?, ?, 'accepted', ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  insertJob.bind(1, job.processId).bind(2, job.name).bind(3, job.sweepMode).bind(4, job.sweptPaths.dump())
      .bind(5, job.inputs.dump()).bind(6, job.sweep.dump())
      .bind(7, std::to_string(job.runs.size()) + (job.runs.size() == 1 ? " run queued" : " runs queued"))
      .bind(8, now).bind(9, now);
  if (job.study.is_null()) insertJob.bindNull(10); else insertJob.bind(10, job.study.dump());
  if (job.provenance.is_null()) insertJob.bindNull(11); else insertJob.bind(11, job.provenance.dump());
  // The body as posted, less its inputs (stored once, above): submittedRequest() joins them again.
  if (job.request.is_object()) {
    Json rest = job.request;
    rest.erase("inputs");
    insertJob.bind(12, rest.dump());
  } else {
    insertJob.bindNull(12);
  }
  insertJob.run();
  const std::int64_t id = sqlite3_last_insert_rowid(m_db);
  Stmt insertRun(m_db,
                 "INSERT INTO runs(job_id, idx, swept, spec, status, updated, replicate, spec_is_patch) "
                 "VALUES(?, ?, ?, ?, 'accepted', ?, ?, 1)");
  for (std::size_t k = 0; k < job.runs.size(); ++k) {
    insertRun.reset();
    insertRun.bind(1, id).bind(2, static_cast<int>(k)).bind(3, job.runs[k].first.dump())
        .bind(4, patches[k]).bind(5, now)
        .bind(6, k < job.replicates.size() ? job.replicates[k] : 0);
    insertRun.run();
  }
  if (!job.idempotencyKey.empty()) {
    Stmt insertKey(m_db, "INSERT INTO idempotency_keys(key, request_hash, job_id, created) VALUES(?, ?, ?, ?)");
    insertKey.bind(1, job.idempotencyKey).bind(2, job.requestHash).bind(3, id).bind(4, now);
    insertKey.run();
  }
  tx.commit();
  return CreatedJob{id, true, job.requestHash};
}

std::optional<JobRecord> JobStore::jobLocked(std::int64_t id) {
  Stmt q(m_db, (std::string("SELECT ") + kJobColumns + " FROM jobs WHERE id = ?").c_str());
  q.bind(1, id);
  if (!q.step()) return std::nullopt;
  JobRecord j = readJob(q);
  addCounts(m_db, j);
  return j;
}

std::optional<JobRecord> JobStore::job(std::int64_t id) {
  std::lock_guard lock(m_mutex);
  return jobLocked(id);
}

std::vector<JobRecord> JobStore::listJobs(const JobFilter& filter, std::int64_t& total) {
  std::lock_guard lock(m_mutex);
  std::string where = " WHERE 1=1";
  if (!filter.statuses.empty()) {
    where += " AND status IN (";
    for (std::size_t i = 0; i < filter.statuses.size(); ++i) where += i ? ",?" : "?";
    where += ")";
  }
  if (!filter.processId.empty()) where += " AND process_id = ?";
  if (!filter.nameContains.empty()) where += " AND instr(lower(name), lower(?)) > 0";
  auto bindFilter = [&](Stmt& q) {
    int i = 1;
    for (Status s : filter.statuses) q.bind(i++, std::string(toString(s)));
    if (!filter.processId.empty()) q.bind(i++, filter.processId);
    if (!filter.nameContains.empty()) q.bind(i++, filter.nameContains);
    return i;
  };
  {
    Stmt count(m_db, ("SELECT COUNT(*) FROM jobs" + where).c_str());
    bindFilter(count);
    total = count.step() ? count.i64(0) : 0;
  }
  Stmt q(m_db, (std::string("SELECT ") + kJobColumns + " FROM jobs" + where +
                " ORDER BY id DESC LIMIT ? OFFSET ?").c_str());
  int i = bindFilter(q);
  q.bind(i, filter.limit);
  q.bind(i + 1, filter.offset);
  std::vector<JobRecord> out;
  while (q.step()) out.push_back(readJob(q));
  for (JobRecord& j : out) addCounts(m_db, j);
  return out;
}

std::vector<RunRecord> JobStore::runs(std::int64_t jobId) {
  std::lock_guard lock(m_mutex);
  return runsLocked(jobId);
}

std::optional<JobWithRuns> JobStore::jobWithRuns(std::int64_t id) {
  // Every write goes through this connection under m_mutex (rupture.lock keeps one server to a
  // data directory), so holding it over both reads makes them one snapshot.
  std::lock_guard lock(m_mutex);
  auto job = jobLocked(id);
  if (!job) return std::nullopt;
  return JobWithRuns{std::move(*job), runsLocked(id)};
}

std::vector<RunRecord> JobStore::runsLocked(std::int64_t jobId) {
  Stmt q(m_db, (std::string("SELECT ") + kRunColumns + " FROM runs WHERE job_id = ? ORDER BY idx").c_str());
  q.bind(1, jobId);
  std::vector<RunRecord> out;
  while (q.step()) out.push_back(readRun(q));
  return out;
}

std::optional<RunRecord> JobStore::run(RunKey key) {
  std::lock_guard lock(m_mutex);
  Stmt q(m_db, (std::string("SELECT ") + kRunColumns + " FROM runs WHERE job_id = ? AND idx = ?").c_str());
  q.bind(1, key.job).bind(2, key.index);
  if (!q.step()) return std::nullopt;
  RunRecord r = readRun(q);
  if (r.spec.is_null() && !r.specPatch.is_null()) {
    Stmt j(m_db, "SELECT process_id, inputs FROM jobs WHERE id = ?");
    j.bind(1, key.job);
    if (!j.step()) throw std::runtime_error("job store: run " + std::to_string(key.index) + " has no job");
    r.spec = jobBaseSpec(j.text(0), j.json(1)).patch(r.specPatch);
  }
  return r;
}

std::vector<RunKey> JobStore::queuedRuns() {
  std::lock_guard lock(m_mutex);
  Stmt q(m_db,
         "SELECT r.job_id, r.idx FROM runs r JOIN jobs j ON j.id = r.job_id "
         "WHERE r.status = 'accepted' AND j.status != 'dismissed' ORDER BY r.job_id, r.idx");
  std::vector<RunKey> out;
  while (q.step()) out.push_back({q.i64(0), static_cast<int>(q.i64(1))});
  return out;
}

std::vector<RunKey> JobStore::unfinishedRuns() {
  std::lock_guard lock(m_mutex);
  Stmt q(m_db, "SELECT job_id, idx FROM runs WHERE status IN ('accepted', 'running') ORDER BY job_id, idx");
  std::vector<RunKey> out;
  while (q.step()) out.push_back({q.i64(0), static_cast<int>(q.i64(1))});
  return out;
}

std::vector<RunKey> JobStore::failedRuns() {
  std::lock_guard lock(m_mutex);
  Stmt q(m_db, "SELECT job_id, idx FROM runs WHERE status = 'failed' ORDER BY job_id, idx");
  std::vector<RunKey> out;
  while (q.step()) out.push_back({q.i64(0), static_cast<int>(q.i64(1))});
  return out;
}

std::vector<std::int64_t> JobStore::jobsAwaitingRefinement() {
  std::lock_guard lock(m_mutex);
  Stmt q(m_db,
         "SELECT j.id FROM jobs j WHERE j.study IS NOT NULL "
         "AND json_extract(j.study, '$.refinement.state') = 'pending' "
         "AND NOT EXISTS (SELECT 1 FROM runs r WHERE r.job_id = j.id AND r.status IN ('accepted', 'running')) "
         "ORDER BY j.id");
  std::vector<std::int64_t> out;
  while (q.step()) out.push_back(q.i64(0));
  return out;
}

std::vector<int> JobStore::appendRuns(std::int64_t jobId, const std::vector<std::pair<Json, Json>>& runs,
                                      const std::vector<int>& replicates, const Json& study) {
  const std::optional<JobRecord> job = this->job(jobId);
  if (!job) throw std::runtime_error("job store: no job " + std::to_string(jobId) + " to append runs to");
  const std::vector<std::string> patches = specPatches(job->processId, job->inputs, runs);
  std::lock_guard lock(m_mutex);
  const std::string now = utcNow();
  Transaction tx(m_db);
  int next = 0;
  {
    Stmt q(m_db, "SELECT COALESCE(MAX(idx), -1) + 1 FROM runs WHERE job_id = ?");
    q.bind(1, jobId);
    if (q.step()) next = static_cast<int>(q.i64(0));
  }
  Stmt insertRun(m_db,
                 "INSERT INTO runs(job_id, idx, swept, spec, status, updated, replicate, spec_is_patch) "
                 "VALUES(?, ?, ?, ?, 'accepted', ?, ?, 1)");
  std::vector<int> indices;
  for (std::size_t k = 0; k < runs.size(); ++k) {
    insertRun.reset();
    insertRun.bind(1, jobId).bind(2, next).bind(3, runs[k].first.dump()).bind(4, patches[k])
        .bind(5, now).bind(6, k < replicates.size() ? replicates[k] : 0);
    insertRun.run();
    indices.push_back(next++);
  }
  Stmt u(m_db, "UPDATE jobs SET study = ? WHERE id = ?");
  u.bind(1, study.dump()).bind(2, jobId).run();
  updateJobStatus(jobId, now);
  tx.commit();
  return indices;
}

void JobStore::setStudy(std::int64_t jobId, const Json& study) {
  std::lock_guard lock(m_mutex);
  const std::string now = utcNow();
  Transaction tx(m_db);
  Stmt u(m_db, "UPDATE jobs SET study = ? WHERE id = ?");
  u.bind(1, study.dump()).bind(2, jobId).run();
  updateJobStatus(jobId, now);
  tx.commit();
}

int JobStore::queueDepth() {
  std::lock_guard lock(m_mutex);
  Stmt q(m_db,
         "SELECT COUNT(*) FROM runs r JOIN jobs j ON j.id = r.job_id "
         "WHERE r.status = 'accepted' AND j.status != 'dismissed'");
  return q.step() ? static_cast<int>(q.i64(0)) : 0;
}

long long JobStore::queuedInputBytes() {
  std::lock_guard lock(m_mutex);
  Stmt q(m_db, "SELECT COALESCE(SUM(LENGTH(CAST(inputs AS BLOB))), 0) FROM jobs WHERE status IN ('accepted', 'running')");
  return q.step() ? q.i64(0) : 0;
}

int JobStore::runningCount() {
  std::lock_guard lock(m_mutex);
  Stmt q(m_db, "SELECT COUNT(*) FROM runs WHERE status = 'running'");
  return q.step() ? static_cast<int>(q.i64(0)) : 0;
}

int JobStore::requeueInterrupted() {
  std::lock_guard lock(m_mutex);
  const std::string now = utcNow();
  Transaction tx(m_db);
  std::vector<std::int64_t> jobs;
  {
    Stmt q(m_db, "SELECT DISTINCT job_id FROM runs WHERE status = 'running'");
    while (q.step()) jobs.push_back(q.i64(0));
  }
  Stmt u(m_db,
         "UPDATE runs SET progress = 0, rate_from = NULL, started = NULL, updated = ?, status = CASE WHEN "
         "(SELECT status FROM jobs WHERE id = runs.job_id) = 'dismissed' THEN 'dismissed' ELSE 'accepted' END "
         "WHERE status = 'running'");
  u.bind(1, now).run();
  const int changed = sqlite3_changes(m_db);
  for (std::int64_t id : jobs) updateJobStatus(id, now);
  tx.commit();
  return changed;
}

bool JobStore::startRun(RunKey key) {
  std::lock_guard lock(m_mutex);
  const std::string now = utcNow();
  Transaction tx(m_db);
  Stmt u(m_db,
         "UPDATE runs SET status = 'running', progress = 0, rate_from = NULL, started = ?, updated = ?, attempts = attempts + 1 "
         "WHERE job_id = ? AND idx = ? AND status = 'accepted' "
         "AND (SELECT status FROM jobs WHERE id = ?) != 'dismissed'");
  u.bind(1, now).bind(2, now).bind(3, key.job).bind(4, key.index).bind(5, key.job).run();
  if (sqlite3_changes(m_db) == 0) return false;
  Stmt j(m_db, "UPDATE jobs SET started = COALESCE(started, ?) WHERE id = ?");
  j.bind(1, now).bind(2, key.job).run();
  updateJobStatus(key.job, now);
  tx.commit();
  return true;
}

void JobStore::setProgress(const std::vector<RunProgress>& progress) {
  if (progress.empty()) return;
  std::lock_guard lock(m_mutex);
  const std::string now = utcNow();
  Transaction tx(m_db);
  for (const RunProgress& p : progress) {
    // `updated` moves only when something did, so a client can tell a stalled run from a live one.
    // The first progress above 0 anchors the run's rate (SET reads the row as it was before).
    Stmt u(m_db,
           "UPDATE runs SET progress = ?, stage = CASE WHEN ? = '' THEN stage ELSE ? END, updated = ?, "
           "rate_from = CASE WHEN rate_from IS NULL AND ? > 0 THEN ? ELSE rate_from END, "
           "rate_from_progress = CASE WHEN rate_from IS NULL AND ? > 0 THEN ? ELSE rate_from_progress END "
           "WHERE job_id = ? AND idx = ? AND status = 'running' AND (progress != ? OR (? != '' AND stage != ?))");
    const double value = std::clamp(p.fraction, 0.0, 1.0);
    u.bind(1, value).bind(2, p.stage).bind(3, p.stage).bind(4, now).bind(5, value).bind(6, now).bind(7, value);
    u.bind(8, value).bind(9, p.key.job).bind(10, p.key.index).bind(11, value).bind(12, p.stage).bind(13, p.stage).run();
  }
  tx.commit();
}

void JobStore::recordResume(RunKey key, std::int64_t step) {
  std::lock_guard lock(m_mutex);
  Stmt u(m_db, "UPDATE runs SET resumes = resumes + 1, resumed_from_step = ?, updated = ? WHERE job_id = ? AND idx = ?");
  u.bind(1, step).bind(2, utcNow()).bind(3, key.job).bind(4, key.index).run();
}

void JobStore::finishRun(RunKey key, Status status, const Json* summary, const std::string* error,
                         const std::string* resultPath) {
  std::lock_guard lock(m_mutex);
  const std::string now = utcNow();
  Transaction tx(m_db);
  Stmt u(m_db,
         "UPDATE runs SET status = ?, progress = CASE WHEN ? THEN 1 ELSE progress END, summary = ?, "
         "error = ?, result_path = ?, finished = ?, updated = ? WHERE job_id = ? AND idx = ?");
  u.bind(1, std::string(toString(status))).bind(2, status == Status::Successful ? 1 : 0);
  if (summary) u.bind(3, summary->dump()); else u.bindNull(3);
  if (error) u.bind(4, *error); else u.bindNull(4);
  if (resultPath) u.bind(5, *resultPath); else u.bindNull(5);
  u.bind(6, now).bind(7, now).bind(8, key.job).bind(9, key.index).run();
  updateJobStatus(key.job, now);
  tx.commit();
}

void JobStore::finishSuccessful(RunKey key, const Json& summary, const std::string& resultPath) {
  finishRun(key, Status::Successful, &summary, nullptr, &resultPath);
}

void JobStore::finishFailed(RunKey key, const std::string& message) {
  finishRun(key, Status::Failed, nullptr, &message, nullptr);
}

void JobStore::finishDismissed(RunKey key) {
  const std::string message = "cancelled while running";
  finishRun(key, Status::Dismissed, nullptr, &message, nullptr);
}

std::vector<int> JobStore::retryFailedRuns(std::int64_t jobId) {
  std::lock_guard lock(m_mutex);
  const std::string now = utcNow();
  Transaction tx(m_db);
  std::vector<int> indices;
  {
    Stmt q(m_db,
           "SELECT r.idx FROM runs r JOIN jobs j ON j.id = r.job_id "
           "WHERE r.job_id = ? AND r.status = 'failed' AND j.status != 'dismissed' ORDER BY r.idx");
    q.bind(1, jobId);
    while (q.step()) indices.push_back(static_cast<int>(q.i64(0)));
  }
  if (indices.empty()) return indices;
  Stmt u(m_db,
         "UPDATE runs SET status = 'accepted', progress = 0, rate_from = NULL, error = NULL, started = NULL, finished = NULL, "
         "updated = ? WHERE job_id = ? AND status = 'failed'");
  u.bind(1, now).bind(2, jobId).run();
  updateJobStatus(jobId, now);
  tx.commit();
  return indices;
}

std::vector<int> JobStore::resumeUnfinishedRuns(std::int64_t jobId) {
  std::lock_guard lock(m_mutex);
  const std::string now = utcNow();
  Transaction tx(m_db);
  auto job = jobLocked(jobId);
  // Only an ended job, and only once its cancelled runs have stopped (a run still running would
  // end dismissed after the resume and leave the job unfinished).
  if (!job || !(job->status == Status::Failed || job->status == Status::Dismissed) || job->runsRunning > 0) return {};
  std::vector<int> indices;
  {
    Stmt q(m_db, "SELECT idx FROM runs WHERE job_id = ? AND status IN ('failed', 'dismissed', 'accepted') ORDER BY idx");
    q.bind(1, jobId);
    while (q.step()) indices.push_back(static_cast<int>(q.i64(0)));
  }
  if (indices.empty()) return indices;
  Stmt u(m_db,
         "UPDATE runs SET status = 'accepted', progress = 0, rate_from = NULL, error = NULL, started = NULL, finished = NULL, "
         "updated = ? WHERE job_id = ? AND status IN ('failed', 'dismissed', 'accepted')");
  u.bind(1, now).bind(2, jobId).run();
  // The job is no longer dismissed: updateJobStatus derives its status from the runs again.
  Stmt j(m_db, "UPDATE jobs SET status = 'accepted', finished = NULL WHERE id = ?");
  j.bind(1, jobId).run();
  updateJobStatus(jobId, now);
  tx.commit();
  return indices;
}

void JobStore::requeueRun(RunKey key) {
  std::lock_guard lock(m_mutex);
  const std::string now = utcNow();
  Transaction tx(m_db);
  Stmt u(m_db,
         "UPDATE runs SET progress = 0, rate_from = NULL, started = NULL, updated = ?, status = CASE WHEN "
         "(SELECT status FROM jobs WHERE id = runs.job_id) = 'dismissed' THEN 'dismissed' ELSE 'accepted' END "
         "WHERE job_id = ? AND idx = ? AND status = 'running'");
  u.bind(1, now).bind(2, key.job).bind(3, key.index).run();
  updateJobStatus(key.job, now);
  tx.commit();
}

std::optional<JobRecord> JobStore::dismissJob(std::int64_t id) {
  std::lock_guard lock(m_mutex);
  const std::string now = utcNow();
  Transaction tx(m_db);
  auto job = jobLocked(id);
  if (!job) return std::nullopt;
  if (job->status == Status::Accepted || job->status == Status::Running) {
    Stmt runs(m_db,
              "UPDATE runs SET status = 'dismissed', error = 'dismissed before it started', finished = ?, "
              "updated = ? WHERE job_id = ? AND status = 'accepted'");
    runs.bind(1, now).bind(2, now).bind(3, id).run();
    Stmt j(m_db,
           "UPDATE jobs SET status = 'dismissed', finished = ?, updated = ?, message = ? WHERE id = ?");
    j.bind(1, now).bind(2, now)
        .bind(3, "dismissed by request after " + std::to_string(job->runsSuccessful + job->runsFailed) +
                     " of " + std::to_string(job->runsTotal) + " runs finished")
        .bind(4, id).run();
  }
  job = jobLocked(id);
  tx.commit();
  return job;
}

void JobStore::updateJobStatus(std::int64_t jobId, const std::string& now) {
  auto job = jobLocked(jobId);
  if (!job) return;
  if (job->status == Status::Dismissed) {
    Stmt u(m_db, "UPDATE jobs SET updated = ? WHERE id = ?");
    u.bind(1, now).bind(2, jobId).run();
    return;
  }
  const int finished = job->runsSuccessful + job->runsFailed + job->runsDismissed;
  // A job whose refinement is pending is not finished when its runs are: the next round follows.
  const bool refining = job->study.is_object() && job->study.contains("refinement") &&
                        job->study["refinement"].value("state", "") == "pending";
  Status status = Status::Running;
  std::string message;
  if (finished == job->runsTotal && refining) {
    message = "all " + std::to_string(job->runsTotal) + " runs finished; choosing refinement points";
  } else if (finished == job->runsTotal) {
    status = job->runsFailed > 0 ? Status::Failed : Status::Successful;
    message = status == Status::Successful
                  ? "all " + std::to_string(job->runsTotal) + " runs successful"
                  : std::to_string(job->runsFailed) + " of " + std::to_string(job->runsTotal) + " runs failed";
  } else if (job->runsRunning == 0 && finished == 0) {
    status = Status::Accepted;
    message = std::to_string(job->runsAccepted) + " runs queued";
  } else {
    message = std::to_string(finished) + " of " + std::to_string(job->runsTotal) + " runs finished";
    if (job->runsFailed) message += " (" + std::to_string(job->runsFailed) + " failed)";
  }
  Stmt u(m_db,
         "UPDATE jobs SET status = ?, message = ?, updated = ?, "
         "finished = CASE WHEN ? THEN COALESCE(finished, ?) ELSE NULL END WHERE id = ?");
  u.bind(1, std::string(toString(status))).bind(2, message).bind(3, now)
      .bind(4, isTerminal(status) ? 1 : 0).bind(5, now).bind(6, jobId).run();
}

}  // namespace rupture::server
