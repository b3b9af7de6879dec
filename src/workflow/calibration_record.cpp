// Calibrations in the result store (workflow/calibration_record.hpp).
#include "pkm/workflow/calibration_record.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "pkm/core/error.hpp"
#include "pkm/io/atomic_file.hpp"
#include "pkm/store/result_store.hpp"

namespace pkm::workflow {
namespace {

using nlohmann::ordered_json;

/// Adds the numeric leaves under `j` (path `prefix`) as results; a path component "before",
/// "after" becomes the stage.
void addLeaves(const ordered_json& j,
               const std::string& prefix,
               const std::string& stage,
               const std::string& unit,
               std::vector<store::ResultRecord>& out) {
  if (j.is_number()) {
    const double v = j.get<double>();
    if (std::isfinite(v)) out.push_back({prefix, stage.empty() ? "estimate" : stage, v, unit});
    return;
  }
  if (j.is_array()) {
    for (std::size_t k = 0; k < j.size(); ++k)
      addLeaves(j[k], fmt::format("{}.{}", prefix, k), stage, unit, out);
    return;
  }
  if (!j.is_object()) return;
  for (const auto& [key, value] : j.items()) {
    if (key == "before" || key == "after") {
      addLeaves(value, prefix, key, unit, out);
      continue;
    }
    if (key == "equations" || key == "poses" || key == "points" || key == "fk_failures" ||
        key == "failures")
      continue;  // counts, not results
    addLeaves(value, prefix.empty() ? key : fmt::format("{}.{}", prefix, key), stage, unit, out);
  }
}

}  // namespace

void recordCalibration(const std::string& db, const CalibrationRecord& r) {
  ordered_json summary;
  try {
    summary = ordered_json::parse(r.summary_json);
  } catch (const nlohmann::json::parse_error& e) {
    throw IoError(fmt::format("calibration summary: invalid JSON ({})", e.what()));
  }
  store::CampaignRecord c;
  c.machine = r.machine;
  c.machine_type = r.machine_type;
  c.name = r.campaign;
  c.source = fmt::format("{}", fmt::join(r.files, " "));
  for (const std::string& f : r.files) c.measurements.push_back({f, "calibration-data", f, 0});
  for (const char* key : {"residuals", "holdout", "tcp_error_map"})
    if (summary.contains(key)) addLeaves(summary[key], key, "", r.length_unit, c.results);
  if (summary.contains("backlash"))
    addLeaves(summary["backlash"]["values"], "backlash", "estimate", r.length_unit, c.results);
  if (summary.contains("hybrid")) {
    const ordered_json& h = summary["hybrid"];
    addLeaves(h["squareness"], "squareness", "estimate", "rad", c.results);
    addLeaves(h["residuals"], "hybrid.residuals", "", r.length_unit, c.results);
    if (h.contains("holdout"))
      addLeaves(h["holdout"], "hybrid.holdout", "", r.length_unit, c.results);
  }
  for (const auto& [target, path] : r.compensations)
    c.compensations.push_back({target, path, io::readFileText(path)});
  store::ResultStore results(db);
  (void)results.store(c);
}

}  // namespace pkm::workflow
