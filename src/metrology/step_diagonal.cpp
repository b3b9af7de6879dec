#include "pkm/metrology/step_diagonal.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>

#include "pkm/core/error.hpp"

namespace pkm::metrology {
namespace {

constexpr double kGridTolerance = 1e-6;  // mm: grid positions that count as the same

/// Forward (ascending-target) increments of one diagonal, averaged over its passes.
struct DiagonalIncrements {
  std::vector<double> grid;                ///< targets, ascending
  std::array<std::vector<double>, 3> inc;  ///< per axis, per interval [grid[j], grid[j+1]]
};

DiagonalIncrements collect(std::span<const StepDiagonalPass> passes, BodyDiagonal diag) {
  DiagonalIncrements out;
  std::array<std::vector<double>, 3> sum;
  int count = 0;
  for (const StepDiagonalPass& pass : passes) {
    if (pass.diagonal != diag) continue;
    const auto& st = pass.steps;
    PKM_CHECK(st.size() >= 2,
              "step diagonal {}: a pass needs at least 2 steps, got {}",
              toString(diag),
              st.size());
    for (const StepDiagonalStep& s : st) {
      PKM_CHECK(std::isfinite(s.target) && std::isfinite(s.deviation[0]) &&
                    std::isfinite(s.deviation[1]) && std::isfinite(s.deviation[2]),
                "step diagonal {}: non-finite target or deviation",
                toString(diag));
    }
    const bool up = st.back().target > st.front().target;
    std::vector<double> grid;
    for (const StepDiagonalStep& s : st) grid.push_back(s.target);
    if (!up) std::reverse(grid.begin(), grid.end());
    for (std::size_t j = 1; j < grid.size(); ++j)
      PKM_CHECK(grid[j] > grid[j - 1] + kGridTolerance,
                "step diagonal {}: the targets of a pass must be strictly monotonic",
                toString(diag));
    if (out.grid.empty()) {
      out.grid = grid;
      for (auto& v : sum) v.assign(grid.size() - 1, 0.0);
    } else {
      PKM_CHECK(grid.size() == out.grid.size(),
                "step diagonal {}: passes on different target grids",
                toString(diag));
      for (std::size_t j = 0; j < grid.size(); ++j)
        PKM_CHECK(std::abs(grid[j] - out.grid[j]) <= kGridTolerance,
                  "step diagonal {}: passes on different target grids",
                  toString(diag));
    }
    // Increments of each sub-move; step i (i ≥ 1, in pass order) spans targets i−1 → i.
    const std::size_t n = st.size();
    for (std::size_t i = 1; i < n; ++i) {
      double previous = st[i - 1].deviation[2];
      const std::size_t interval = up ? i - 1 : n - 1 - i;
      for (std::size_t q = 0; q < 3; ++q) {
        const double increment = st[i].deviation[q] - previous;
        previous = st[i].deviation[q];
        sum[q][interval] += up ? increment : -increment;
      }
    }
    ++count;
  }
  PKM_CHECK(count > 0, "step diagonal: no pass along {}", toString(diag));
  for (std::size_t q = 0; q < 3; ++q) {
    out.inc[q] = sum[q];
    for (double& v : out.inc[q]) v /= count;
  }
  return out;
}

/// Least-squares slope and max − min of the residuals.
std::pair<double, double> slopeAndStraightness(const std::vector<double>& x,
                                               const std::vector<double>& y) {
  const auto n = static_cast<double>(x.size());
  double mx = 0.0, my = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    mx += x[i] / n;
    my += y[i] / n;
  }
  double sxx = 0.0, sxy = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxx += (x[i] - mx) * (x[i] - mx);
    sxy += (x[i] - mx) * (y[i] - my);
  }
  const double slope = sxy / sxx;
  double lo = 0.0, hi = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double r = y[i] - my - slope * (x[i] - mx);
    lo = i == 0 ? r : std::min(lo, r);
    hi = i == 0 ? r : std::max(hi, r);
  }
  return {slope, hi - lo};
}

}  // namespace

StepDiagonalResult extractStepDiagonal(std::span<const StepDiagonalPass> passes,
                                       const Eigen::Vector3d& size) {
  requireBoxSize(size);
  const double d = size.norm();
  const Eigen::Vector3d cosines = size / d;  // a, b, c
  std::array<DiagonalIncrements, 4> diags;
  for (BodyDiagonal diag : kBodyDiagonals)
    diags[static_cast<std::size_t>(diag)] = collect(passes, diag);

  StepDiagonalResult result;
  for (int q = 0; q < 3; ++q) {
    const auto qi = static_cast<std::size_t>(q);
    // R_k(axis position), referred to the first (smallest) position.
    std::array<std::vector<double>, 4> r;
    std::vector<double> positions;
    for (BodyDiagonal diag : kBodyDiagonals) {
      const auto k = static_cast<std::size_t>(diag);
      const DiagonalIncrements& di = diags[k];
      const double sign = travelSigns(diag)[q];
      const double start = diagonalStart(diag, size)[q];
      const std::size_t m = di.grid.size();
      std::vector<std::pair<double, double>> pf(m);  // (axis position, cumulative sum)
      double f = 0.0;
      for (std::size_t j = 0; j < m; ++j) {
        if (j > 0) f += di.inc[qi][j - 1];
        pf[j] = {start + sign * size[q] * di.grid[j] / d, f};
      }
      std::sort(pf.begin(), pf.end());
      std::vector<double> pos(m), val(m);
      for (std::size_t j = 0; j < m; ++j) {
        pos[j] = pf[j].first;
        val[j] = pf[j].second - pf[0].second;
      }
      if (diag == BodyDiagonal::kPPP) {
        positions = pos;
      } else {
        PKM_CHECK(pos.size() == positions.size(),
                  "step diagonal: the {} axis grid of {} differs from that of PPP",
                  "XYZ"[q],
                  toString(diag));
        for (std::size_t j = 0; j < m; ++j)
          PKM_CHECK(std::abs(pos[j] - positions[j]) <= kGridTolerance,
                    "step diagonal: the {} axis grid of {} differs from that of PPP "
                    "(targets must be symmetric, e.g. uniform from 0 to D)",
                    "XYZ"[q],
                    toString(diag));
      }
      r[k] = std::move(val);
    }
    // Wang 2000: the 4×4 sign system solved per position.
    StepDiagonalAxis& axis = result.axes[qi];
    axis.positions = positions;
    for (auto& c : axis.components) c.resize(positions.size());
    axis.residual.resize(positions.size());
    for (std::size_t j = 0; j < positions.size(); ++j) {
      const double r1 = r[0][j], r2 = r[1][j], r3 = r[2][j], r4 = r[3][j];
      axis.components[0][j] = (r1 - r2 + r3 - r4) / (4.0 * cosines.x());
      axis.components[1][j] = (r1 + r2 - r3 - r4) / (4.0 * cosines.y());
      axis.components[2][j] = (r1 + r2 + r3 + r4) / (4.0 * cosines.z());
      axis.residual[j] = r1 - r2 - r3 + r4;
      result.residual_max = std::max(result.residual_max, std::abs(axis.residual[j]));
    }
    for (std::size_t c = 0; c < 3; ++c)
      std::tie(axis.slopes[c], axis.straightness[c]) =
          slopeAndStraightness(positions, axis.components[c]);
  }
  // Wang 2000: squareness from the slope pairs (first-order rigid-body model, ISO 230-1 names),
  // then the project convention.
  const auto& ax = result.axes;
  const double ec0y = -(ax[0].slopes[1] + ax[1].slopes[0]);
  const double eb0z = ax[2].slopes[0] + ax[0].slopes[2];
  const double ea0z = -(ax[2].slopes[1] + ax[1].slopes[2]);
  result.squareness_xy = ec0y;
  result.squareness_xz = -eb0z;
  result.squareness_yz = ea0z;
  return result;
}

}  // namespace pkm::metrology
