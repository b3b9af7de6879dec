/// @file
/// @brief Uncertainty budgets of straightness, parallelism and circle results (ISO/TR 230-9:2005
/// §6 applied to ISO 230-1 straightness and parallelism and to on-machine circle measurement with
/// a touch probe, Lee et al. 2019): the instrument per its specification (straightness optics,
/// probe repeatability and form, stylus calibration), the test's own statistics (repeated readings,
/// the least-squares slopes' and circle's standard errors) and the artefact's temperature.
/// docs/analysis.md lists each budget's contributors and formulas.
#pragma once

#include <span>
#include <vector>

#include "pkm/metrology/circle_fit.hpp"
#include "pkm/metrology/min_zone_circle.hpp"
#include "pkm/metrology/probe_offset.hpp"
#include "pkm/metrology/uncertainty_budget.hpp"
#include "pkm/metrology/uncertainty_sources.hpp"

namespace pkm::metrology {

/// Budget of a straightness value `straightness` (mm) measured with laser straightness optics
/// over the positions `position` (mm): the optics' accuracy ±(a + b·S + c·L²) at the two extreme
/// readings (rectangular, sensitivity √2) and, when a position was read more than once
/// (`raw_position`/`raw_deviation`, the readings before the per-position mean), the pooled
/// standard deviation s of the readings about their means, s/√n per mean at the two extremes.
/// Throws pkm::InvalidArgument for invalid sources, fewer than 2 positions or raw arrays of
/// different lengths.
[[nodiscard]] UncertaintyBudget straightnessUncertainty(double straightness,
                                                        std::span<const double> position,
                                                        std::span<const double> raw_position,
                                                        std::span<const double> raw_deviation,
                                                        const UncertaintySources& sources);

/// One straightness run of a parallelism measurement: positions along the beam (mm), the
/// least-squares residuals about its representative line (mm) and the optics' readings as
/// displayed (mm; the %-of-reading term of the optics' accuracy acts at their largest magnitude;
/// empty: evaluated at a reading of 0).
struct SlopeRun {
  std::span<const double> position;
  std::span<const double> residual;
  std::span<const double> reading = {};
};

/// Budget of a parallelism value `parallelism` = Δγ · L_axis (mm) from a reference and an axis
/// run along one beam (MXT700S parallelism paper, §3.1): per run the least-squares slope's standard
/// error s_r/√Σ(u − ū)² (s_r the residuals' standard deviation, N − 2 degrees of freedom, carried
/// into ν_eff) and the straightness optics' accuracy a + b·|reading|max + c·L² turned into a slope
/// (√2 a / L_run), each times the axis travel.
/// Throws pkm::InvalidArgument for invalid sources or a run with fewer than 3 points.
[[nodiscard]] UncertaintyBudget parallelismUncertainty(double parallelism,
                                                       const SlopeRun& reference,
                                                       const SlopeRun& axis,
                                                       const UncertaintySources& sources);

/// Budgets of a probed circle (mm): "radius" (LSC; the fit's standard error s/√N with s the
/// residuals' standard deviation on N − 3 degrees of freedom, the stylus radius calibration, the
/// probe's form error, the ring's temperature and expansion coefficient), "roundness_lsc" and
/// "roundness_mzc" (probe repeatability and form at the two extreme points, the master ring's
/// certified form (± ring_form_mm, rectangular), and the noise's
/// upward bias of a range of N residuals, d2(N)·σ with σ the probe's stated repeatability / 2,
/// as a rectangular half-width: expectedNormalRange). Throws
/// pkm::InvalidArgument for invalid sources or fewer than 4 residuals.
[[nodiscard]] std::vector<UncertaintyBudget> circleUncertainty(const CircleFit& lsc,
                                                               const MinZoneCircle& mzc,
                                                               const UncertaintySources& sources);

/// Budgets "offset_x" and "offset_y" (mm) of a least-squares probe offset: the Gauss-Newton
/// covariance s²(JᵀJ)⁻¹ of the fit at its solution (s² = Σe²/(N − 5)), the probe's form error
/// (rectangular, whole: an odd lobe count aliases to a centre shift that the reversal flips into
/// the offset), and nothing for the stylus radius (it moves c and ρ,
/// not d). Throws pkm::InvalidArgument for invalid sources, fewer than 6 touches or touches that
/// do not separate the offset from the centre (singular normal matrix).
[[nodiscard]] std::vector<UncertaintyBudget> probeOffsetUncertainty(
    const ProbeOffsetFit& fit,
    std::span<const ProbeTouch> touches,
    const UncertaintySources& sources);

}  // namespace pkm::metrology
