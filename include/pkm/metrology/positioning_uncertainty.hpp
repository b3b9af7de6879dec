/// @file
/// @brief Uncertainty budgets of the ISO 230-2 results E, M, A, B and R of a linear axis, built
/// the way ISO/TR 230-9:2005 (§6, Annex C) and ISO 230-2:2014 Annex A build them: the laser's
/// vacuum wavelength, its environmental compensation (the air sensors' errors through the
/// refractive index of air, metrology/air_refractive_index.hpp), the material temperature and
/// expansion coefficient (the scale referred to 20 °C), the dead path, the cosine (misalignment)
/// and Abbe errors, the set-up repeatability, the environmental variation error E_VE and the
/// test's own statistics (the means' and standard deviations' sampling uncertainty). Lengths in
/// mm. docs/analysis.md, "Budget: ISO 230-2 positioning" lists every contributor and formula.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "pkm/metrology/conformance.hpp"
#include "pkm/metrology/iso230_2.hpp"
#include "pkm/metrology/uncertainty_budget.hpp"
#include "pkm/metrology/uncertainty_sources.hpp"

namespace pkm::metrology {

/// The contributors that act on a length `length_mm` measured by a laser interferometer between
/// two readings (ISO/TR 230-9 §6.2-6.6): vacuum wavelength, air temperature, pressure and humidity
/// sensors (sensitivities from the modified Edlén equation at the environment's air), material
/// temperature sensor, expansion coefficient (when the material is not at 20 °C), dead path,
/// cosine error, Abbe error, set-up repeatability and E_VE. Appended to `budget` (those with a
/// zero contribution are left out). Throws pkm::InvalidArgument for invalid sources or a negative
/// or non-finite length.
void addLaserLengthContributors(UncertaintyBudget& budget,
                                double length_mm,
                                const UncertaintySources& sources);

/// Budgets of E, M, A, B and R (in that order; mm) of a bidirectional ISO 230-2 result whose
/// targets and deviations are in mm; of unidirectional data, the budgets of the direction's own
/// E, A and R ("E_up", "A_up", "R_up", or "E_down", "A_down", "R_down"; the bidirectional
/// quantities are NaN).
/// `coverage` is the k of ISO 230-2's own A and R (R_i↑ = 2k s_i↑). Each E, M, A budget uses the
/// distance between the two targets that define the range as the measured length; B and R, taken
/// at one target, have no length term, but a noise floor: the laser's reading noise σ raises the
/// largest |B_i| by up to σ·√(1/n↑ + 1/n↓)·E[max of m |Z|] and the largest R_i by up to
/// 2k·σ·E[max of m s/σ] (m targets; expectedMaxAbsNormal, expectedMaxSampleSigma), a rectangular
/// half-width. Throws pkm::InvalidArgument for invalid sources.
[[nodiscard]] std::vector<UncertaintyBudget> iso230_2Uncertainty(const Iso230_2Result& result,
                                                                 const UncertaintySources& sources,
                                                                 double coverage = 2.0);

/// ISO 14253-1 decisions for the quantities of `tolerances` (name, upper limit T in mm) that
/// have a budget in `budgets`, in the order of `tolerances`. Throws pkm::InvalidArgument for a
/// name without a budget or a non-finite tolerance.
[[nodiscard]] std::vector<ConformanceResult> decideIso230_2Conformance(
    const std::vector<UncertaintyBudget>& budgets,
    const std::vector<std::pair<std::string, double>>& tolerances);

}  // namespace pkm::metrology
