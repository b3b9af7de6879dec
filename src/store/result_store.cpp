// The SQLite result store (result_store.hpp).
#include "pkm/store/result_store.hpp"

#include <fmt/format.h>
#include <sqlite3.h>

#include <chrono>
#include <cmath>
#include <ctime>

#include "pkm/core/error.hpp"

namespace pkm::store {
namespace {

/// Schema 1: the tables below without results.U; schema 2 adds results.U (the expanded
/// uncertainty, k = 2, NULL when none).
constexpr int kSchemaVersion = 2;

constexpr const char* kSchema = R"sql(
CREATE TABLE IF NOT EXISTS machines (
  id INTEGER PRIMARY KEY,
  name TEXT NOT NULL UNIQUE,
  type TEXT NOT NULL,
  created TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS campaigns (
  id INTEGER PRIMARY KEY,
  machine_id INTEGER NOT NULL REFERENCES machines(id),
  name TEXT NOT NULL,
  source TEXT NOT NULL,
  status TEXT NOT NULL,
  time TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS measurements (
  id INTEGER PRIMARY KEY,
  campaign_id INTEGER NOT NULL REFERENCES campaigns(id),
  name TEXT NOT NULL, kind TEXT NOT NULL, file TEXT NOT NULL, rows INTEGER NOT NULL);
CREATE TABLE IF NOT EXISTS results (
  id INTEGER PRIMARY KEY,
  campaign_id INTEGER NOT NULL REFERENCES campaigns(id),
  quantity TEXT NOT NULL, stage TEXT NOT NULL, value REAL NOT NULL, unit TEXT NOT NULL,
  U REAL);
CREATE TABLE IF NOT EXISTS compensations (
  id INTEGER PRIMARY KEY,
  campaign_id INTEGER NOT NULL REFERENCES campaigns(id),
  target TEXT NOT NULL, file TEXT NOT NULL, content TEXT NOT NULL);
CREATE INDEX IF NOT EXISTS results_by_campaign ON results(campaign_id);
CREATE INDEX IF NOT EXISTS campaigns_by_machine ON campaigns(machine_id);
)sql";

std::string utcNow() {
  const std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

/// A prepared statement, finalised on destruction.
class Statement {
 public:
  Statement(sqlite3* db, const std::string& path, const char* sql) : db_(db), path_(path) {
    if (sqlite3_prepare_v2(db, sql, -1, &stmt_, nullptr) != SQLITE_OK)
      throw IoError(fmt::format("{}: {}", path, sqlite3_errmsg(db)));
  }
  ~Statement() { sqlite3_finalize(stmt_); }
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;
  Statement& text(int i, const std::string& v) {
    check(sqlite3_bind_text(stmt_, i, v.c_str(), static_cast<int>(v.size()), SQLITE_TRANSIENT));
    return *this;
  }
  Statement& integer(int i, std::int64_t v) {
    check(sqlite3_bind_int64(stmt_, i, v));
    return *this;
  }
  Statement& real(int i, double v) {
    check(sqlite3_bind_double(stmt_, i, v));
    return *this;
  }
  /// `v`, or NULL when it is NaN.
  Statement& realOrNull(int i, double v) {
    check(std::isnan(v) ? sqlite3_bind_null(stmt_, i) : sqlite3_bind_double(stmt_, i, v));
    return *this;
  }
  /// Steps once: true when a row is available.
  bool step() {
    const int rc = sqlite3_step(stmt_);
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) return false;
    throw IoError(fmt::format("{}: {}", path_, sqlite3_errmsg(db_)));
  }
  void run() {
    while (step()) {
    }
    sqlite3_reset(stmt_);
  }
  [[nodiscard]] std::string columnText(int i) const {
    const unsigned char* p = sqlite3_column_text(stmt_, i);
    return p != nullptr ? reinterpret_cast<const char*>(p) : "";
  }
  [[nodiscard]] std::int64_t columnInteger(int i) const { return sqlite3_column_int64(stmt_, i); }
  [[nodiscard]] double columnReal(int i) const { return sqlite3_column_double(stmt_, i); }
  /// The column's number, NaN when it is NULL.
  [[nodiscard]] double columnRealOrNan(int i) const {
    return sqlite3_column_type(stmt_, i) == SQLITE_NULL ? std::nan("") : columnReal(i);
  }

 private:
  void check(int rc) const {
    if (rc != SQLITE_OK) throw IoError(fmt::format("{}: {}", path_, sqlite3_errmsg(db_)));
  }
  sqlite3* db_;
  std::string path_;
  sqlite3_stmt* stmt_ = nullptr;
};

}  // namespace

struct ResultStore::Impl {
  sqlite3* db = nullptr;
  std::string path;

  void exec(const char* sql) const {
    char* message = nullptr;
    if (sqlite3_exec(db, sql, nullptr, nullptr, &message) != SQLITE_OK) {
      const std::string what = message != nullptr ? message : sqlite3_errmsg(db);
      sqlite3_free(message);
      throw IoError(fmt::format("{}: {}", path, what));
    }
  }

  [[nodiscard]] std::int64_t userVersion() const {
    Statement version(db, path, "PRAGMA user_version");
    version.step();
    return version.columnInteger(0);
  }

  /// Runs `sql` in one immediate transaction (rolled back on error).
  void transaction(const std::string& sql) const {
    exec("BEGIN IMMEDIATE");
    try {
      exec(sql.c_str());
      exec("COMMIT");
    } catch (...) {
      sqlite3_exec(db, "ROLLBACK", nullptr, nullptr, nullptr);
      throw;
    }
  }

  /// Schema 1 -> 2: results gains the U column (NULL for the rows already stored). The version is
  /// read again inside the transaction, so that two connections migrating at once add it once.
  void migrateFrom1() const {
    exec("BEGIN IMMEDIATE");
    try {
      if (userVersion() == 1) {
        exec("ALTER TABLE results ADD COLUMN U REAL");
        exec(fmt::format("PRAGMA user_version={}", kSchemaVersion).c_str());
      }
      exec("COMMIT");
    } catch (...) {
      sqlite3_exec(db, "ROLLBACK", nullptr, nullptr, nullptr);
      throw;
    }
  }
};

ResultStore::ResultStore(const std::string& path, int busy_timeout_ms)
    : impl_(std::make_unique<Impl>()) {
  impl_->path = path;
  if (sqlite3_open_v2(path.c_str(),
                      &impl_->db,
                      SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE | SQLITE_OPEN_FULLMUTEX,
                      nullptr) != SQLITE_OK) {
    const std::string what = impl_->db != nullptr ? sqlite3_errmsg(impl_->db) : "out of memory";
    sqlite3_close(impl_->db);
    throw IoError(fmt::format("{}: cannot open the result store: {}", path, what));
  }
  try {
    sqlite3_busy_timeout(impl_->db, busy_timeout_ms);
    impl_->exec("PRAGMA foreign_keys=ON;");
    const std::int64_t v = impl_->userVersion();
    if (v != 0 && v != 1 && v != kSchemaVersion)
      throw IoError(
          fmt::format("{}: result store schema {} (this pkm reads {})", path, v, kSchemaVersion));
    if (v == kSchemaVersion) return;  // an existing store: nothing to write
    if (v == 1) {
      impl_->migrateFrom1();
      return;
    }
    // A new store: write-ahead journal (persistent; if another connection is creating the store
    // at the same moment the switch may be refused, and the rollback journal is safe as well)
    // and the schema, idempotently, in one immediate transaction.
    sqlite3_exec(impl_->db, "PRAGMA journal_mode=WAL", nullptr, nullptr, nullptr);
    impl_->transaction(fmt::format("{}\nPRAGMA user_version={};", kSchema, kSchemaVersion));
  } catch (const IoError& e) {
    sqlite3_close(impl_->db);
    const std::string what = e.what();
    if (what.find("file is not a database") != std::string::npos)
      throw IoError(fmt::format("{}: not a pkm result store (SQLite database)", path));
    throw;
  }
}

ResultStore::~ResultStore() {
  if (impl_ && impl_->db != nullptr) sqlite3_close(impl_->db);
}

std::int64_t ResultStore::store(const CampaignRecord& c) {
  PKM_CHECK(!c.machine.empty(), "result store: a campaign needs a machine name");
  PKM_CHECK(!c.name.empty(), "result store: a campaign needs a name");
  for (const ResultRecord& r : c.results) {
    PKM_CHECK(std::isfinite(r.value), "result store: result '{}' is not finite", r.quantity);
    PKM_CHECK(std::isnan(r.U) || (std::isfinite(r.U) && r.U >= 0.0),
              "result store: the U of result '{}' must be >= 0 and finite, or NaN (none)",
              r.quantity);
  }
  sqlite3* db = impl_->db;
  const std::string& path = impl_->path;
  impl_->exec("BEGIN IMMEDIATE");
  try {
    Statement(db, path, "INSERT OR IGNORE INTO machines(name, type, created) VALUES(?, ?, ?)")
        .text(1, c.machine)
        .text(2, c.machine_type)
        .text(3, utcNow())
        .run();
    Statement find(db, path, "SELECT id FROM machines WHERE name = ?");
    find.text(1, c.machine);
    find.step();
    const std::int64_t machine_id = find.columnInteger(0);
    Statement(db,
              path,
              "INSERT INTO campaigns(machine_id, name, source, status, time) VALUES(?, ?, ?, ?, ?)")
        .integer(1, machine_id)
        .text(2, c.name)
        .text(3, c.source)
        .text(4, c.status)
        .text(5, utcNow())
        .run();
    const std::int64_t id = sqlite3_last_insert_rowid(db);
    Statement m(
        db,
        path,
        "INSERT INTO measurements(campaign_id, name, kind, file, rows) VALUES(?, ?, ?, ?, ?)");
    for (const MeasurementRecord& r : c.measurements)
      m.integer(1, id).text(2, r.name).text(3, r.kind).text(4, r.file).integer(5, r.rows).run();
    Statement res(db,
                  path,
                  "INSERT INTO results(campaign_id, quantity, stage, value, unit, U) "
                  "VALUES(?, ?, ?, ?, ?, ?)");
    for (const ResultRecord& r : c.results)
      res.integer(1, id)
          .text(2, r.quantity)
          .text(3, r.stage)
          .real(4, r.value)
          .text(5, r.unit)
          .realOrNull(6, r.U)
          .run();
    Statement comp(
        db,
        path,
        "INSERT INTO compensations(campaign_id, target, file, content) VALUES(?, ?, ?, ?)");
    for (const CompensationRecord& r : c.compensations)
      comp.integer(1, id).text(2, r.target).text(3, r.file).text(4, r.content).run();
    impl_->exec("COMMIT");
    return id;
  } catch (...) {
    sqlite3_exec(db, "ROLLBACK", nullptr, nullptr, nullptr);
    throw;
  }
}

std::vector<HistoryRow> ResultStore::history(const std::string& machine,
                                             const std::optional<std::string>& quantity) {
  Statement q(impl_->db,
              impl_->path,
              "SELECT c.id, c.time, c.name, r.quantity, r.stage, r.value, r.unit, r.U "
              "FROM results r JOIN campaigns c ON r.campaign_id = c.id "
              "JOIN machines m ON c.machine_id = m.id "
              "WHERE m.name = ?1 AND (?2 IS NULL OR r.quantity = ?2) ORDER BY c.id, r.id");
  q.text(1, machine);
  if (quantity) q.text(2, *quantity);
  std::vector<HistoryRow> out;
  while (q.step())
    out.push_back({q.columnInteger(0),
                   q.columnText(1),
                   q.columnText(2),
                   q.columnText(3),
                   q.columnText(4),
                   q.columnText(6),
                   q.columnReal(5),
                   q.columnRealOrNan(7)});
  return out;
}

std::vector<std::string> ResultStore::machines() {
  Statement q(impl_->db, impl_->path, "SELECT name FROM machines ORDER BY name");
  std::vector<std::string> out;
  while (q.step()) out.push_back(q.columnText(0));
  return out;
}

bool ResultStore::integrityOk() {
  Statement q(impl_->db, impl_->path, "PRAGMA integrity_check");
  return q.step() && q.columnText(0) == "ok";
}

}  // namespace pkm::store
