#include "pkm/metrology/plane_prediction.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "pkm/core/error.hpp"
#include "pkm/metrology/checks.hpp"

namespace pkm::metrology {

double ErrorFunction::operator()(double q) const {
  const std::size_t n = positions.size();
  if (n == 0) return 0.0;
  if (n == 1) return values[0];
  // The interval containing q (the end intervals extrapolate).
  const auto it = std::upper_bound(positions.begin() + 1, positions.end() - 1, q);
  const auto j = static_cast<std::size_t>(it - positions.begin());
  const double t = (q - positions[j - 1]) / (positions[j] - positions[j - 1]);
  return values[j - 1] + t * (values[j] - values[j - 1]);
}

Eigen::Vector2d PlaneErrorModel::error(double x, double y) const {
  return {exx(x) + exy(y), eyx(x) + eyy(y)};
}

PlaneErrorModel planeModel(const StepDiagonalResult& step) {
  PlaneErrorModel m;
  const StepDiagonalAxis& ax = step.axes[0];
  const StepDiagonalAxis& ay = step.axes[1];
  m.exx = {ax.positions, ax.components[0]};
  m.eyx = {ax.positions, ax.components[1]};
  m.exy = {ay.positions, ay.components[0]};
  m.eyy = {ay.positions, ay.components[1]};
  return m;
}

PlaneErrorModel planeModel(const ShiftedDiagonalResult& shifted) {
  PlaneErrorModel m;
  m.exx = {{0.0, 1.0}, {0.0, shifted.scale[0]}};
  m.eyy = {{0.0, 1.0}, {0.0, shifted.scale[1]}};
  m.exy = {{0.0, 1.0}, {0.0, -shifted.squareness[0]}};
  return m;
}

double predictReading(const PlaneErrorModel& model,
                      const Eigen::Vector2d& start,
                      const Eigen::Vector2d& direction,
                      const Eigen::Vector2d& sensitive,
                      double s) {
  const Eigen::Vector2d p = start + s * direction;
  return sensitive.dot(model.error(p.x(), p.y()) - model.error(start.x(), start.y()));
}

namespace {

/// Subtracts the mean, or the least-squares line when `line`.
void detrend(const std::vector<double>& x, std::vector<double>& y, bool line) {
  const auto n = static_cast<double>(x.size());
  double mx = 0.0, my = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    mx += x[i] / n;
    my += y[i] / n;
  }
  double slope = 0.0;
  if (line) {
    double sxx = 0.0, sxy = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      sxx += (x[i] - mx) * (x[i] - mx);
      sxy += (x[i] - mx) * (y[i] - my);
    }
    slope = sxx > 0.0 ? sxy / sxx : 0.0;
  }
  for (std::size_t i = 0; i < x.size(); ++i) y[i] -= my + slope * (x[i] - mx);
}

}  // namespace

PlaneComparison comparePlanePrediction(const PlaneErrorModel& model,
                                       const Eigen::Vector2d& start,
                                       const Eigen::Vector2d& direction,
                                       const Eigen::Vector2d& sensitive,
                                       std::span<const double> positions,
                                       std::span<const double> measured,
                                       bool remove_line) {
  PKM_CHECK(positions.size() == measured.size(),
            "plane prediction: {} positions but {} measured values",
            positions.size(),
            measured.size());
  requireCount(positions.size(), 2, "plane prediction");
  requireFinite(positions, "plane prediction positions");
  requireFinite(measured, "plane prediction measured values");
  PlaneComparison c;
  c.positions.assign(positions.begin(), positions.end());
  c.measured.assign(measured.begin(), measured.end());
  for (double s : positions)
    c.predicted.push_back(predictReading(model, start, direction, sensitive, s));
  detrend(c.positions, c.measured, remove_line);
  detrend(c.positions, c.predicted, remove_line);
  double ss = 0.0;
  for (std::size_t i = 0; i < c.positions.size(); ++i) {
    const double d = c.measured[i] - c.predicted[i];
    ss += d * d;
    c.max_abs = std::max(c.max_abs, std::abs(d));
  }
  c.rms = std::sqrt(ss / static_cast<double>(c.positions.size()));
  return c;
}

}  // namespace pkm::metrology
