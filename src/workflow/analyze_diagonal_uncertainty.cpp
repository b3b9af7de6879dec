// The squareness budgets of the diagonal methods (analyze_diagonal_uncertainty.hpp).
#include "analyze_diagonal_uncertainty.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <string>
#include <utility>

namespace pkm::workflow::detail {
namespace {

constexpr std::array<const char*, 3> kNames = {"squareness_xy", "squareness_xz", "squareness_yz"};

/// The three squareness values (xy, xz, yz) of one evaluation of a method on perturbed lines.
using ThreeModel = std::function<std::array<double, 3>(std::span<const double> x)>;

SquarenessBudgets propagateThree(const ThreeModel& model,
                                 const std::array<double, 3>& values,
                                 const metrology::UncertaintyBudget& inputs,
                                 const metrology::MonteCarloOptions& options) {
  SquarenessBudgets out;
  for (std::size_t q = 0; q < 3; ++q) {
    const auto one = [&model, q](std::span<const double> x) { return model(x)[q]; };
    metrology::NonlinearBudget b =
        metrology::propagateBothWays(kNames[q], "rad", values[q], one, inputs, options);
    out.linear.push_back(std::move(b.linear));
    out.monte_carlo.push_back(b.monte_carlo);
  }
  return out;
}

/// Name prefix of the per-reading inputs of the step-diagonal model (collapsed after propagation).
constexpr const char* kReadingNoise = "laser reading noise";

/// `inputs` with one normal input of standard uncertainty `sigma_mm` per reading of `passes`.
metrology::UncertaintyBudget withReadingInputs(metrology::UncertaintyBudget inputs,
                                               std::span<const metrology::StepDiagonalPass> passes,
                                               double sigma_mm) {
  for (const metrology::StepDiagonalPass& p : passes)
    for (std::size_t s = 0; s < p.steps.size(); ++s)
      for (int m = 0; m < 3; ++m) {
        metrology::UncertaintyContributor c;
        c.name =
            fmt::format("{} {} step {} sub-move {}", kReadingNoise, toString(p.diagonal), s, m);
        c.value = sigma_mm;
        c.unit = "mm";
        c.distribution = metrology::Distribution::kNormal;
        c.normal_k = 1.0;
        c.source = "instrument reading noise and resolution";
        metrology::addContributor(inputs, c);
      }
  return inputs;
}

/// `inputs` with two beam-alignment angles per diagonal (rad): the tilt of the beam in the two
/// directions across it, set up once per diagonal. A tilt θ in an unknown direction φ around the
/// diagonal has the components θ·cos φ and θ·sin φ: each the arcsine (U-shaped) law of amplitude
/// θ (variance θ²/2), the largest for a tilt bounded by θ; a rectangular law (θ²/3) understated
/// it (`pkm validate coverage`: step yz 89.5 % in the realistic workshop).
metrology::UncertaintyBudget withAlignmentInputs(metrology::UncertaintyBudget inputs,
                                                 double misalignment_rad) {
  for (metrology::BodyDiagonal d : metrology::kBodyDiagonals)
    for (int k = 1; k <= 2; ++k) {
      metrology::UncertaintyContributor c;
      c.name = fmt::format("beam alignment {} (across the beam, {})", toString(d), k);
      c.value = misalignment_rad;
      c.unit = "rad";
      c.distribution = metrology::Distribution::kUShaped;
      c.source = "set-up: beam-to-diagonal misalignment";
      metrology::addContributor(inputs, c);
    }
  return inputs;
}

/// A tilt θ of the beam across a diagonal reads θ·w, w the reflector's offset from the diagonal:
/// zero on it, but not after the X and Y sub-moves of a step (Chapman, Precision Engineering
/// 27(4), 2003). Adds that error to the X and Y sub-move readings of `pass` for the angles
/// (t1, t2) along two unit vectors across the beam.
void addAlignmentError(metrology::StepDiagonalPass& pass,
                       const Eigen::Vector3d& size,
                       double t1,
                       double t2) {
  const Eigen::Vector3d u = metrology::diagonalTravel(pass.diagonal, size).normalized();
  const Eigen::Vector3d e1 = u.cross(Eigen::Vector3d::UnitZ()).normalized();
  const Eigen::Vector3d theta = t1 * e1 + t2 * u.cross(e1);
  double previous = pass.steps.front().target;
  for (metrology::StepDiagonalStep& s : pass.steps) {
    const double step = s.target - previous;
    const Eigen::Vector3d after_x = step * Eigen::Vector3d(u.x(), 0.0, 0.0);
    const Eigen::Vector3d after_y = step * Eigen::Vector3d(u.x(), u.y(), 0.0);
    s.deviation[0] += theta.dot(after_x - u.dot(after_x) * u);
    s.deviation[1] += theta.dot(after_y - u.dot(after_y) * u);
    previous = s.target;
  }
}

/// The per-reading rows of a linear budget (of `readings` inputs) replaced by one row: their
/// quadrature sum (they are independent), as a standard uncertainty in the budget's unit.
void collapseReadingRows(metrology::UncertaintyBudget& b, double sigma_mm, std::size_t readings) {
  double sum2 = 0.0;
  std::size_t n = 0;
  std::vector<metrology::UncertaintyContributor> kept;
  for (const metrology::UncertaintyContributor& c : b.contributors) {
    if (c.name.rfind(kReadingNoise, 0) == 0) {
      sum2 += c.contribution() * c.contribution();
      ++n;
    } else {
      kept.push_back(c);
    }
  }
  if (n == 0) return;
  metrology::UncertaintyContributor all;
  all.name =
      fmt::format("{} ({} readings, {:.3g} um each)", kReadingNoise, readings, sigma_mm * 1e3);
  all.value = std::sqrt(sum2);
  all.unit = b.unit;
  all.distribution = metrology::Distribution::kNormal;
  all.normal_k = 1.0;
  all.source = "instrument reading noise and resolution, through the step extraction";
  kept.push_back(all);
  b.contributors = std::move(kept);
}

}  // namespace

SquarenessBudgets bodySquarenessBudgets(std::span<const metrology::BodyDiagonalSample> samples,
                                        const metrology::BodyDiagonalResult& result,
                                        const Eigen::Vector3d& size,
                                        const metrology::UncertaintySources& sources,
                                        const metrology::MonteCarloOptions& options) {
  std::vector<metrology::DiagonalLineInput> lines;
  std::array<double, 4> errors{};
  for (std::size_t k = 0; k < 4; ++k) {
    const metrology::BodyDiagonal d = metrology::kBodyDiagonals[k];
    lines.push_back({metrology::toString(d),
                     result.length,
                     metrology::bodyDiagonalStatistics(samples, result, d)});
    errors[k] = result.diagonals[k].length_error;
  }
  const metrology::UncertaintyBudget inputs = metrology::diagonalLineInputs(lines, sources);
  const double D = result.length;
  const ThreeModel model = [&](std::span<const double> x) {
    std::array<double, 4> perturbed = errors;
    for (std::size_t k = 0; k < 4; ++k) perturbed[k] += metrology::lineLengthError(x, k, D);
    const metrology::BodyDiagonalSolution s = metrology::solveBodyDiagonals(size, perturbed);
    return std::array<double, 3>{s.squareness_xy, s.squareness_xz, s.squareness_yz};
  };
  const metrology::BodyDiagonalSolution& s = result.solution;
  return propagateThree(
      model, {s.squareness_xy, s.squareness_xz, s.squareness_yz}, inputs, options);
}

SquarenessBudgets shiftedSquarenessBudgets(
    std::span<const metrology::ShiftedDiagonalMeasurement> measurements,
    const metrology::ShiftedDiagonalResult& result,
    const Eigen::Vector3d& size,
    const metrology::UncertaintySources& sources,
    const metrology::MonteCarloOptions& options) {
  // Lines in order of first appearance; each measurement's line index.
  std::map<std::pair<int, int>, std::size_t> index;
  std::vector<std::size_t> line_of;
  std::vector<std::vector<double>> values;
  std::vector<metrology::DiagonalLineInput> lines;
  for (const auto& m : measurements) {
    const std::pair<int, int> key{static_cast<int>(m.diagonal), m.axis};
    if (!index.count(key)) {
      index[key] = lines.size();
      Eigen::Vector3d travel = metrology::diagonalTravel(m.diagonal, size);
      if (m.axis >= 0) travel[m.axis] += m.shift;
      const std::string axis = m.axis < 0 ? "" : fmt::format(" shifted {}", "xyz"[m.axis]);
      lines.push_back({metrology::toString(m.diagonal) + axis, travel.norm(), 0.0});
      values.emplace_back();
    }
    line_of.push_back(index[key]);
    values[index[key]].push_back(m.length_error);
  }
  // Pooled scatter of repeated measurements of a line.
  double squares = 0.0;
  std::size_t dof = 0;
  for (const auto& v : values) {
    double mean = 0.0;
    for (double e : v) mean += e / static_cast<double>(v.size());
    for (double e : v) squares += (e - mean) * (e - mean);
    dof += v.size() - 1;
  }
  const double s = dof ? std::sqrt(squares / static_cast<double>(dof)) : 0.0;
  for (std::size_t k = 0; k < lines.size(); ++k)
    lines[k].statistics_mm = s / std::sqrt(static_cast<double>(values[k].size()));
  const metrology::UncertaintyBudget inputs = metrology::diagonalLineInputs(lines, sources);
  const std::vector<metrology::ShiftedDiagonalMeasurement> base(measurements.begin(),
                                                                measurements.end());
  const ThreeModel model = [&](std::span<const double> x) {
    std::vector<metrology::ShiftedDiagonalMeasurement> perturbed = base;
    for (std::size_t i = 0; i < perturbed.size(); ++i) {
      const std::size_t k = line_of[i];
      perturbed[i].length_error += metrology::lineLengthError(x, k, lines[k].length_mm);
    }
    return metrology::evaluateShiftedDiagonals(perturbed, size).squareness;
  };
  return propagateThree(model, result.squareness, inputs, options);
}

SquarenessBudgets stepSquarenessBudgets(std::span<const metrology::StepDiagonalPass> passes,
                                        const metrology::StepDiagonalResult& result,
                                        const Eigen::Vector3d& size,
                                        const metrology::UncertaintySources& sources,
                                        const metrology::MonteCarloOptions& options) {
  double q2 = 0.0;
  std::size_t nq = 0;
  for (const metrology::StepDiagonalAxis& a : result.axes) {
    for (double q : a.residual) q2 += q * q;
    nq += a.residual.size();
  }
  const double statistics = nq ? std::sqrt(q2 / static_cast<double>(nq)) / 2.0 : 0.0;
  const double D = size.norm();
  std::vector<metrology::DiagonalLineInput> lines;
  for (metrology::BodyDiagonal d : metrology::kBodyDiagonals)
    lines.push_back({metrology::toString(d), D, statistics});
  // Every reading's own noise (and resolution) enters the increments the extraction sums, a
  // random walk along each function, which a per-line length error cannot represent.
  const double sigma =
      std::hypot(sources.laser.reading_noise_mm, sources.laser.resolution_mm / std::sqrt(12.0));
  const std::size_t first_reading = 1 + 3 * lines.size();
  const metrology::UncertaintyBudget with_readings =
      withReadingInputs(metrology::diagonalLineInputs(lines, sources), passes, sigma);
  const std::size_t first_alignment = with_readings.contributors.size();
  const metrology::UncertaintyBudget inputs =
      withAlignmentInputs(with_readings, sources.environment.misalignment_rad);
  // The share of a step's travel along the beam after the X and the Y sub-move: a², a² + b².
  const Eigen::Vector3d c2 = (size / D).cwiseAbs2();
  const std::array<double, 3> share{c2.x(), c2.x() + c2.y(), 1.0};
  const std::vector<metrology::StepDiagonalPass> base(passes.begin(), passes.end());
  const ThreeModel model = [&](std::span<const double> x) {
    std::vector<metrology::StepDiagonalPass> perturbed = base;
    std::size_t reading = first_reading;
    for (metrology::StepDiagonalPass& p : perturbed)
      for (metrology::StepDiagonalStep& s : p.steps)
        for (std::size_t m = 0; m < 3; ++m) s.deviation[m] += x[reading++];
    for (metrology::StepDiagonalPass& p : perturbed) {
      const std::size_t k = first_alignment + 2 * static_cast<std::size_t>(p.diagonal);
      addAlignmentError(p, size, x[k], x[k + 1]);
    }
    for (metrology::StepDiagonalPass& p : perturbed) {
      const double per_mm =
          metrology::lineLengthError(x, static_cast<std::size_t>(p.diagonal), D) / D;
      double previous = p.steps.front().target;
      for (metrology::StepDiagonalStep& s : p.steps) {
        for (std::size_t m = 0; m < 3; ++m)
          s.deviation[m] += per_mm * (previous + share[m] * (s.target - previous));
        previous = s.target;
      }
    }
    const metrology::StepDiagonalResult r = metrology::extractStepDiagonal(perturbed, size);
    return std::array<double, 3>{r.squareness_xy, r.squareness_xz, r.squareness_yz};
  };
  SquarenessBudgets out = propagateThree(
      model, {result.squareness_xy, result.squareness_xz, result.squareness_yz}, inputs, options);
  const std::size_t readings = first_alignment - first_reading;
  for (metrology::UncertaintyBudget& b : out.linear) collapseReadingRows(b, sigma, readings);
  return out;
}

SquarenessBudgets faceSquarenessBudget(std::span<const metrology::FaceDiagonal> diagonals,
                                       std::span<const metrology::PdgeTerm> pdge,
                                       const metrology::FaceDiagonalOptions& fit,
                                       const metrology::FaceDiagonalResult& result,
                                       const metrology::UncertaintySources& sources,
                                       const metrology::MonteCarloOptions& options) {
  std::vector<metrology::DiagonalLineInput> lines;
  for (std::size_t k = 0; k < diagonals.size(); ++k) {
    double length = 0.0, s2 = 0.0, r2 = 0.0;
    std::size_t n = 0;
    for (std::size_t j = 0; j < diagonals[k].points.size(); ++j) {
      const metrology::DiagonalPoint& p = diagonals[k].points[j];
      const double s = std::hypot(p.u, p.v);
      if (s == 0.0) continue;
      length = std::max(length, s);
      s2 += s * s;
      r2 += result.residuals[k][j] * result.residuals[k][j];
      ++n;
    }
    if (n == 0) length = 1.0;  // a diagonal of start points only: no reading moves it
    const double stat = n >= 2 ? std::sqrt(r2 / static_cast<double>(n - 1) / s2) * length : 0.0;
    lines.push_back({fmt::format("diagonal {}", k + 1), length, stat});
  }
  const metrology::UncertaintyBudget inputs = metrology::diagonalLineInputs(lines, sources);
  const std::vector<metrology::FaceDiagonal> base(diagonals.begin(), diagonals.end());
  const metrology::MeasurementModel model = [&](std::span<const double> x) {
    std::vector<metrology::FaceDiagonal> perturbed = base;
    for (std::size_t k = 0; k < perturbed.size(); ++k) {
      const double per_mm =
          metrology::lineLengthError(x, k, lines[k].length_mm) / lines[k].length_mm;
      for (metrology::DiagonalPoint& p : perturbed[k].points)
        p.deviation += per_mm * std::hypot(p.u, p.v);
    }
    return metrology::fitFaceDiagonalSquareness(perturbed, pdge, fit).squareness;
  };
  metrology::NonlinearBudget b =
      metrology::propagateBothWays("squareness", "rad", result.squareness, model, inputs, options);
  return {{std::move(b.linear)}, {b.monte_carlo}};
}

}  // namespace pkm::workflow::detail
