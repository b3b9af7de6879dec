/// @file
/// @brief Internal: the files of a sensitivity study (workflow/campaign_sensitivity.hpp):
/// sensitivity.json, sensitivity.csv and the report data behind report.html.
#pragma once

#include <string>

#include "pkm/workflow/campaign_sensitivity.hpp"

namespace pkm::workflow::detail {

/// sensitivity.json (schema pkm.sensitivity/1, docs/campaign.md): campaign, source, unit, base
/// environment, uncertainty sources, seed, values and one row per value × summary row (value,
/// step, quantity, unit, before, after, before_U, after_U, target, pass; null where not finite),
/// then the coefficients (step, quantity, unit, before, after: slopes per unit of the source).
[[nodiscard]] std::string sensitivityJson(const SensitivityResult& result,
                                          const SensitivityOptions& options);

/// sensitivity.csv: a header line "value,step,quantity,unit,before,after,before_U,after_U", then
/// one line per row; numbers round-trip (io::formatNumber), empty where not finite; text fields
/// quoted when they hold a comma, a quote or a line break (RFC 4180).
[[nodiscard]] std::string sensitivityCsv(const SensitivityResult& result);

/// The report data (pkm.report/1, docs/report.md): a header naming the source and the base, the
/// summary table of every row, a section of the coefficients, and per campaign step one line plot
/// per summary quantity: the
/// after-value against the source's value with its ±U band (the before-value where no after-value
/// exists).
[[nodiscard]] std::string sensitivityReportData(const SensitivityResult& result,
                                                const SensitivityOptions& options);

}  // namespace pkm::workflow::detail
