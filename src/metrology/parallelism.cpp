#include "pkm/metrology/parallelism.hpp"

#include <algorithm>
#include <cmath>

#include "pkm/core/error.hpp"

namespace pkm::metrology {
namespace {

std::vector<double> beamCoordinates(const BeamRun& run, const char* what) {
  PKM_CHECK(run.beam_sign == 1 || run.beam_sign == -1,
            "parallelism: {} beam sign must be ±1, got {}",
            what,
            run.beam_sign);
  std::vector<double> u(run.positions.size());
  for (std::size_t k = 0; k < u.size(); ++k) u[k] = run.beam_sign * run.positions[k];
  return u;
}

}  // namespace

ParallelismResult evaluateParallelism(const BeamRun& reference,
                                      const BeamRun& axis,
                                      const ParallelismOptions& options) {
  const std::vector<double> u_ref = beamCoordinates(reference, "reference");
  const std::vector<double> u_axis = beamCoordinates(axis, "axis");
  ParallelismResult r;
  r.reference_straightness = evaluateStraightness(u_ref, reference.deviations, options.reference);
  r.axis_straightness = evaluateStraightness(u_axis, axis.deviations, options.reference);
  // Representative slopes γ (α) of both runs and their difference Δγ (Δα) (MXT700S parallelism
  // paper, §3.1).
  r.reference_slope = r.reference_straightness.line.slope;
  r.axis_slope = r.axis_straightness.line.slope;
  r.slope_difference = r.axis_slope - r.reference_slope;
  const auto [lo, hi] = std::minmax_element(axis.positions.begin(), axis.positions.end());
  const double u_start = axis.beam_sign * *lo, u_end = axis.beam_sign * *hi;
  r.parallelism = r.slope_difference * (u_end - u_start);
  // e_k = d_k - γ_ref u_k - c, with the axis's representative line at u_start giving e = 0.
  const double c = r.axis_straightness.line.at(u_start) - r.reference_slope * u_start;
  r.deviations.resize(u_axis.size());
  for (std::size_t k = 0; k < u_axis.size(); ++k) {
    r.deviations[k] = axis.deviations[k] - r.reference_slope * u_axis[k] - c;
    if (std::abs(r.deviations[k]) > std::abs(r.max_deviation)) r.max_deviation = r.deviations[k];
  }
  return r;
}

PkmSquareness pkmSquarenessFromSlopes(double dgamma, double dalpha, double szX2) {
  PKM_CHECK(std::isfinite(dgamma) && std::isfinite(dalpha) && std::isfinite(szX2),
            "seed 000 eq. 11: non-finite input (dgamma {}, dalpha {}, szX2 {})",
            dgamma,
            dalpha,
            szX2);
  // The MXT700S parallelism paper, §3.3: sxP = Δα; szP from Δγ and szX2 (eq. 11, sign as its
  // reported values).
  return {dalpha, szX2 - dgamma};
}

PkmSquareness pkmSquarenessFromSlopes(double dgamma, double dalpha, double szX2, double syP) {
  PKM_CHECK(std::isfinite(syP), "seed 000 eq. 11: non-finite syP {}", syP);
  PkmSquareness s = pkmSquarenessFromSlopes(dgamma, dalpha, szX2);
  for (int pass = 0; pass < 2; ++pass) {
    const PkmSquareness first = s;
    s.szP = szX2 - dgamma - 0.5 * first.sxP * syP;
    s.sxP = dalpha + 0.5 * syP * first.szP;
  }
  return s;
}

}  // namespace pkm::metrology
