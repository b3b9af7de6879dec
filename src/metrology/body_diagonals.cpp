#include "pkm/metrology/body_diagonals.hpp"

#include <fmt/format.h>

#include <cmath>
#include <set>
#include <tuple>
#include <vector>

#include "pkm/core/error.hpp"
#include "pkm/metrology/checks.hpp"

namespace pkm::metrology {

const char* toString(BodyDiagonal diagonal) {
  switch (diagonal) {
    case BodyDiagonal::kPPP:
      return "PPP";
    case BodyDiagonal::kNPP:
      return "NPP";
    case BodyDiagonal::kPNP:
      return "PNP";
    case BodyDiagonal::kNNP:
      return "NNP";
  }
  return "?";
}

std::optional<BodyDiagonal> parseBodyDiagonal(std::string_view name) {
  for (BodyDiagonal d : kBodyDiagonals)
    if (name == toString(d)) return d;
  return std::nullopt;
}

Eigen::Vector3d travelSigns(BodyDiagonal diagonal) {
  switch (diagonal) {
    case BodyDiagonal::kPPP:
      return {1.0, 1.0, 1.0};
    case BodyDiagonal::kNPP:
      return {-1.0, 1.0, 1.0};
    case BodyDiagonal::kPNP:
      return {1.0, -1.0, 1.0};
    case BodyDiagonal::kNNP:
      return {-1.0, -1.0, 1.0};
  }
  return {1.0, 1.0, 1.0};
}

Eigen::Vector3d diagonalStart(BodyDiagonal diagonal, const Eigen::Vector3d& size) {
  const Eigen::Vector3d s = travelSigns(diagonal);
  return {s.x() < 0 ? size.x() : 0.0, s.y() < 0 ? size.y() : 0.0, 0.0};
}

Eigen::Vector3d diagonalTravel(BodyDiagonal diagonal, const Eigen::Vector3d& size) {
  return travelSigns(diagonal).cwiseProduct(size);
}

void requireBoxSize(const Eigen::Vector3d& size) {
  for (int i = 0; i < 3; ++i)
    PKM_CHECK(std::isfinite(size[i]) && size[i] > 0.0,
              "box size: length {} must be finite and > 0, got {}",
              "xyz"[i],
              size[i]);
}

BodyDiagonalSolution solveBodyDiagonals(const Eigen::Vector3d& size,
                                        const std::array<double, 4>& length_errors) {
  requireBoxSize(size);
  requireFinite(length_errors, "body-diagonal length errors");
  const double lx = size.x(), ly = size.y(), lz = size.z();
  const double d = size.norm();
  const double ppp = length_errors[0], npp = length_errors[1], pnp = length_errors[2],
               nnp = length_errors[3];
  // The closed form of the four first-order diagonal equations (docs/analysis.md, "--method body").
  const double ec0y = d * (-ppp + npp + pnp - nnp) / (4.0 * lx * ly);
  const double eb0z = d * (ppp - npp + pnp - nnp) / (4.0 * lx * lz);
  const double ea0z = d * (-ppp - npp + pnp + nnp) / (4.0 * ly * lz);
  BodyDiagonalSolution s;
  s.squareness_xy = ec0y;
  s.squareness_xz = -eb0z;
  s.squareness_yz = ea0z;
  s.K = d * (ppp + npp + pnp + nnp) / 4.0;
  s.scale = s.K / (d * d);
  return s;
}

namespace {

/// Least-squares line through (x, y): slope and RMS residual (ISO 230-1).
std::pair<double, double> lsqLine(const std::vector<double>& x, const std::vector<double>& y) {
  const auto n = static_cast<double>(x.size());
  double mx = 0.0, my = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    mx += x[i];
    my += y[i];
  }
  mx /= n;
  my /= n;
  double sxx = 0.0, sxy = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxx += (x[i] - mx) * (x[i] - mx);
    sxy += (x[i] - mx) * (y[i] - my);
  }
  const double slope = sxy / sxx;
  double ss = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double r = y[i] - my - slope * (x[i] - mx);
    ss += r * r;
  }
  return {slope, std::sqrt(ss / n)};
}

}  // namespace

BodyDiagonalResult evaluateBodyDiagonals(std::span<const BodyDiagonalSample> samples,
                                         const Eigen::Vector3d& size,
                                         const BodyDiagonalOptions& options) {
  requireBoxSize(size);
  BodyDiagonalResult result;
  result.length = size.norm();
  constexpr double kMargin = 1.0;  // mm beyond the ends accepted as overshoot-free positions
  std::array<double, 4> length_errors{};
  for (BodyDiagonal diag : kBodyDiagonals) {
    const auto k = static_cast<std::size_t>(diag);
    std::vector<double> x, y;
    std::vector<PositioningSample> iso;
    for (const BodyDiagonalSample& s : samples) {
      if (s.diagonal != diag) continue;
      PKM_CHECK(std::isfinite(s.position) && std::isfinite(s.deviation),
                "body diagonal {}: position and deviation must be finite",
                toString(diag));
      PKM_CHECK(s.position >= -kMargin && s.position <= result.length + kMargin,
                "body diagonal {}: position {} mm outside the diagonal [0, {}] mm",
                toString(diag),
                s.position,
                result.length);
      x.push_back(s.position);
      y.push_back(s.deviation);
      iso.push_back({s.position, s.direction, s.run, s.position + s.deviation});
    }
    const std::set<double> distinct(x.begin(), x.end());
    PKM_CHECK(distinct.size() >= 2,
              "body diagonal {}: needs at least 2 distinct positions, got {}",
              toString(diag),
              distinct.size());
    DiagonalEvaluation& e = result.diagonals[k];
    e.readings = static_cast<int>(x.size());
    std::tie(e.slope, e.residual_rms) = lsqLine(x, y);
    e.length_error = e.slope * result.length;
    length_errors[k] = e.length_error;
    if (options.iso230_2) e.iso = evaluateIso230_2(iso, options.iso);
  }
  result.solution = solveBodyDiagonals(size, length_errors);
  return result;
}

}  // namespace pkm::metrology
