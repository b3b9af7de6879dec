// Compensation must not make a machine worse: the built-in "realistic" campaign, every
// unmodelled error source on at its documented magnitude (docs/simulation-errors.md), run over
// 20 seeds; every summary row's after-value is at most its before-value within the combined
// expanded uncertainty √(U_before² + U_after²) (0 where a row has no U).
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>

#include "pkm/workflow/campaign.hpp"

namespace pkm::workflow {
namespace PKM_TEST_NS {

namespace fs = std::filesystem;

/// Seeds of the runs: the campaign's own (the scenarios' seeds) and a few more.
constexpr unsigned kFirstSeed = 1;
constexpr unsigned kSeeds = 20;

/// The built-in realistic campaign with every step's seed set to `seed`.
std::string realisticCampaign(unsigned seed) {
  std::ifstream in(fs::path(PKM_SOURCE_DIR) / "data" / "campaigns" / "realistic.json");
  nlohmann::json c = nlohmann::json::parse(std::string(std::istreambuf_iterator<char>(in), {}));
  c["name"] = fmt::format("realistic-seed-{}", seed);
  for (nlohmann::json& step : c["steps"]) step["seed"] = seed;
  return c.dump();
}

TEST(CampaignNoWorse, CompensationDoesNotMakeTheRealisticMachinesWorse) {
  const fs::path dir = fs::temp_directory_path() / fmt::format("pkm_no_worse_{}", ::getpid());
  int rows = 0;
  double closest = -1e300;  // the largest (after − before − U), in the row's unit
  for (unsigned seed = kFirstSeed; seed < kFirstSeed + kSeeds; ++seed) {
    CampaignOptions options;
    options.campaign = fmt::format("realistic-seed-{}", seed);
    options.campaign_text = realisticCampaign(seed);
    options.out = dir / std::to_string(seed);
    options.force = true;
    const CampaignResult result = runCampaign(options);
    for (const CampaignStepResult& step : result.steps)
      for (const CampaignRow& row : step.rows) {
        if (!std::isfinite(row.before) || !std::isfinite(row.after)) continue;
        const double u = std::isfinite(row.combinedU()) ? row.combinedU() : 0.0;
        EXPECT_LE(std::abs(row.after), std::abs(row.before) + u)
            << "seed " << seed << ", " << step.id << " " << row.quantity << ": before "
            << row.before << ", after " << row.after << " " << row.unit << ", U " << u;
        closest = std::max(closest, std::abs(row.after) - std::abs(row.before) - u);
        ++rows;
      }
  }
  EXPECT_GE(rows, static_cast<int>(kSeeds) * 4);  // every step reported its rows
  RecordProperty("closest_margin", std::to_string(closest));
  std::error_code ec;
  fs::remove_all(dir, ec);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::workflow
