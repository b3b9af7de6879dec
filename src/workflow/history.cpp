// `pkm history` (history.hpp): a machine's results across campaigns.
#include "pkm/workflow/history.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <filesystem>
#include <optional>

#include "pkm/core/error.hpp"

namespace pkm::workflow {

void HistoryRequest::validate() const {
  // Reading never creates a store.
  if (db.empty() || !std::filesystem::exists(db))
    throw IoError(fmt::format("{}: no result store (campaigns and `--db` write one)", db));
}

HistoryResult queryHistory(const HistoryRequest& request) {
  request.validate();
  store::ResultStore results(request.db);
  std::optional<std::string> quantity;
  if (!request.quantity.empty()) quantity = request.quantity;
  HistoryResult result{request.machine, request.db, results.history(request.machine, quantity)};
  if (result.rows.empty() && request.require_rows) {
    const std::vector<std::string> known = results.machines();
    throw InvalidArgument(
        fmt::format("{}: no results for machine '{}' (machines in the store: {})",
                    request.db,
                    request.machine,
                    known.empty() ? "none" : fmt::format("{}", fmt::join(known, ", "))));
  }
  return result;
}

}  // namespace pkm::workflow
