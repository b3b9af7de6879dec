/// @file
/// @brief The result store: an embedded SQLite database (default `pkm.db`) of machines, campaigns,
/// measurements, results and compensations, so that a machine's errors can be followed across
/// campaigns (`pkm history`). Concurrent writers are safe: each campaign is written in one
/// immediate transaction, the journal is write-ahead (WAL) and a busy writer is waited for
/// (docs/formats.md, "Result store").
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace pkm::store {

/// A measurement file a campaign used.
struct MeasurementRecord {
  std::string name;  ///< e.g. "tracker-fit"
  std::string kind;  ///< e.g. "tracker-pose", "iso230-2"
  std::string file;  ///< path as given
  std::int64_t rows = 0;
};

/// One number a campaign produced.
struct ResultRecord {
  std::string quantity;  ///< e.g. "holdout.rms", "squareness.szX2", "parallelism"
  std::string stage;     ///< "before", "after", "estimate", ...
  double value = 0.0;
  std::string unit;  ///< "mm", "rad", ...
  /// Expanded uncertainty of `value` (k = 2, GUM), in `unit`; NaN when it has none (stored as
  /// NULL).
  double U = std::numeric_limits<double>::quiet_NaN();
};

/// A compensation a campaign wrote (the controller file's text).
struct CompensationRecord {
  std::string target;  ///< e.g. "linuxcnc-hal", "errors-json"
  std::string file;    ///< path written
  std::string content;
};

/// Everything one campaign stores, written atomically.
struct CampaignRecord {
  std::string machine;       ///< machine name (the history key)
  std::string machine_type;  ///< "hexapod", "exechon", "hybrid"
  std::string name;          ///< campaign name, e.g. "calibrate hexapod"
  std::string source;        ///< where the data came from (files, scenario)
  std::string status = "ok";
  std::vector<MeasurementRecord> measurements;
  std::vector<ResultRecord> results;
  std::vector<CompensationRecord> compensations;
};

/// One row of a machine's history.
struct HistoryRow {
  std::int64_t campaign = 0;  ///< campaign id, increasing in storage order
  std::string time;           ///< UTC, ISO 8601 ("2026-11-22T08:30:00Z")
  std::string campaign_name;
  std::string quantity, stage, unit;
  double value = 0.0;
  /// Expanded uncertainty (k = 2) of `value`, in `unit`; NaN when none was stored (NULL, and every
  /// row written by a schema-1 store).
  double U = std::numeric_limits<double>::quiet_NaN();
};

/// A connection to a result store. Not copyable; one per thread.
class ResultStore {
 public:
  /// Opens (creating when absent) the database at `path` with the schema (docs/formats.md),
  /// write-ahead journal and a `busy_timeout_ms` wait for other writers. A store of schema 1 (no
  /// uncertainty column) is migrated to schema 2 in place: its results keep their values and get
  /// a NULL U. Throws pkm::IoError "PATH: message" when it cannot be opened, is not a pkm result
  /// store or has a newer schema.
  explicit ResultStore(const std::string& path, int busy_timeout_ms = 30000);
  ~ResultStore();
  ResultStore(const ResultStore&) = delete;
  ResultStore& operator=(const ResultStore&) = delete;

  /// Stores a campaign (the machine is created on first use) in one transaction; returns its id.
  /// Throws pkm::IoError on a database error (nothing of the campaign is stored then) and
  /// pkm::InvalidArgument for an empty machine or campaign name, a non-finite result or a negative
  /// or infinite U (NaN U is stored as NULL).
  std::int64_t store(const CampaignRecord& campaign);

  /// The machine's results in campaign order (then insertion order), optionally of one quantity.
  [[nodiscard]] std::vector<HistoryRow> history(
      const std::string& machine, const std::optional<std::string>& quantity = std::nullopt);

  /// The names of the machines in the store, sorted.
  [[nodiscard]] std::vector<std::string> machines();

  /// True when SQLite's integrity check passes.
  [[nodiscard]] bool integrityOk();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pkm::store
