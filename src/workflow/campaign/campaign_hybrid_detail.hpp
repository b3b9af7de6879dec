/// @file
/// @brief The parts of the "hybrid-squareness" campaign step shared between its two sources
/// (campaign_hybrid_analysis.cpp: analysis and compensation; campaign_hybrid.cpp: the step, its
/// figures and report section).
#pragma once

#include <limits>
#include <memory>
#include <optional>
#include <string>

#include "campaign_steps.hpp"
#include "pkm/kinematics/hybrid_errors.hpp"
#include "pkm/kinematics/hybrid_model.hpp"
#include "pkm/metrology/parallelism.hpp"
#include "pkm/simulation/compensated_machine.hpp"

namespace pkm::workflow::campaign::detail {

/// What the laser lines of the hybrid machine give.
struct HybridAnalysis {
  metrology::ParallelismResult horizontal, vertical;  ///< Y2-PY parallelism (MXT700S
                                                      ///< parallelism paper, §3.1)
  kinematics::HybridSquareness squareness;            ///< the four squareness errors
  metrology::Iso230_2Result diag_xy, diag_xz;         ///< the face diagonals X2-Y2 and X2-PZ
  /// U (k = 2, mm) of |parallelism| (metrology::parallelismUncertainty).
  double horizontal_U = std::numeric_limits<double>::quiet_NaN();
  double vertical_U = std::numeric_limits<double>::quiet_NaN();
  /// The largest contributors of horizontal_U and vertical_U (largestContributors).
  std::string horizontal_limit, vertical_limit;
  /// The same over the paper's 50 mm (the pairs straightness-{y2,py}-{h,v}-50), when measured:
  /// Table 3 of the MXT700S parallelism paper states its parallelism over that range.
  std::optional<metrology::ParallelismResult> horizontal_50, vertical_50;
  double horizontal_50_U = std::numeric_limits<double>::quiet_NaN();
  double vertical_50_U = std::numeric_limits<double>::quiet_NaN();
  /// The budgets' sources at the conditions the data recorded (sourcesAt).
  metrology::UncertaintySources sources;
};

/// Parallelism from the straightness runs (its U with the instruments of `sources` at the
/// conditions `data` recorded, kept in HybridAnalysis::sources), szX2 and syP
/// from the face diagonals with the positioning and straightness PDGEs removed, sxP and szP from
/// the slope differences. Throws pkm::IoError naming `source` when a measurement is missing.
[[nodiscard]] HybridAnalysis analyseHybrid(const LineData& data,
                                           const std::string& source,
                                           const metrology::UncertaintySources& sources);

/// Writes the compensation of `analysis` (base frame + X2 correction, the X2→yp cross table, the
/// axis tables of X2, Y2 and PZ) and returns it as the controller's command compensation.
[[nodiscard]] std::shared_ptr<simulation::CompensationChain> compensateHybrid(
    const StepContext& context,
    StepOutcome& outcome,
    const LineData& before,
    const kinematics::HybridMachineModel& model,
    const HybridAnalysis& analysis);

}  // namespace pkm::workflow::campaign::detail
