/// @file
/// @brief `pkm history` as a workflow: how a machine's results evolve across campaigns, read from
/// the result store (store/result_store.hpp; docs/formats.md, "Result store").
#pragma once

#include <string>
#include <vector>

#include "pkm/store/result_store.hpp"

namespace pkm::workflow {

/// A history query.
struct HistoryRequest {
  std::string machine;        ///< the machine's name (a name the store lacks has no rows)
  std::string db = "pkm.db";  ///< the result store; it must exist (reading never creates one)
  std::string quantity;       ///< only this quantity, e.g. "holdout.rms" ("": every quantity)
  /// Throw when the machine has no results (a table of nothing says nothing), naming the
  /// machines the store has.
  bool require_rows = false;
  /// Throws pkm::IoError "DB: no result store (campaigns and `--db` write one)" when the store
  /// does not exist.
  void validate() const;
};

/// A machine's history.
struct HistoryResult {
  std::string machine, db;
  std::vector<store::HistoryRow>
      rows;  ///< in campaign order (store::historyText, store::historyJson)
};

/// Reads the history. Throws as validate(), pkm::IoError for a store that cannot be read,
/// pkm::InvalidArgument "DB: no results for machine 'NAME'
/// (machines in the store: ...)" when `require_rows` and there is none.
[[nodiscard]] HistoryResult queryHistory(const HistoryRequest& request);

}  // namespace pkm::workflow
