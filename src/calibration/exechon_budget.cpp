// Linear uncertainty budgets of an Exechon calibration (calibration/exechon_budget.hpp).
#include "pkm/calibration/exechon_budget.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "detail/contributor.hpp"
#include "detail/exechon_reading_errors.hpp"
#include "pkm/core/error.hpp"
#include "pkm/geometry/so3.hpp"

namespace pkm::calibration {
namespace {

/// The instrument sources on the 3·n point rows: per coordinate, u(e) = (a + b·L_i)/√3.
std::vector<ObservationErrorSource> pointSources(const ExechonCalibrationData& data,
                                                 const metrology::UncertaintySources& sources,
                                                 LengthUnit unit) {
  const double per_mm = 1.0 / millimetresPer(unit);
  const metrology::LaserTrackerSpec& t = sources.tracker;
  const auto n = static_cast<Eigen::Index>(data.observations.size());
  std::vector<double> half(data.observations.size());
  double longest = 0.0;
  for (std::size_t i = 0; i < half.size(); ++i) {
    const double L =
        data.measurement_frame ? data.observations[i].point.norm() / per_mm : t.range_mm;
    half[i] = (t.accuracy_mm + t.accuracy_mm_per_m * L * 1e-3) * per_mm;
    longest = std::max(longest, L);
  }
  const double ref = (t.accuracy_mm + t.accuracy_mm_per_m * longest * 1e-3) * per_mm;
  std::vector<ObservationErrorSource> out;
  const std::string u(toString(unit));
  if (ref > 0.0) {
    Eigen::MatrixXd E = Eigen::MatrixXd::Zero(3 * n, 3 * n);
    for (Eigen::Index i = 0; i < n; ++i)
      E.block<3, 3>(3 * i, 3 * i).setIdentity() *= half[static_cast<std::size_t>(i)] / ref;
    out.push_back({detail::makeContributor(
                       fmt::format("{} (±(a + b·L), L = {:.0f} mm)", t.name, longest),
                       ref,
                       u,
                       metrology::Distribution::kRectangular,
                       fmt::format("specification a = {:g} mm, b = {:g} mm/m, per coordinate",
                                   t.accuracy_mm,
                                   t.accuracy_mm_per_m)),
                   E.sparseView()});
  }
  const double setup = sources.environment.setup_repeatability_mm * per_mm;
  if (setup > 0.0)
    out.push_back({detail::makeContributor("set-up repeatability",
                                           setup,
                                           u,
                                           metrology::Distribution::kNormal,
                                           "environment.setup_repeatability_mm, per coordinate"),
                   Eigen::MatrixXd::Identity(3 * n, 3 * n).sparseView()});
  return out;
}

}  // namespace

ExechonParameterUncertainty exechonParameterUncertainty(
    const kinematics::ExechonModel& initial,
    const ExechonCalibrationData& data,
    const ExechonCalibrationSummary& fit,
    const ExechonCalibrationOptions& calibration,
    const metrology::UncertaintySources& sources) {
  std::string why;
  PKM_CHECK(sources.isValid(&why), "{}", why);
  PKM_CHECK(!fit.free_indices.empty() &&
                data.measurement_frame.has_value() == fit.measurement_frame.has_value(),
            "Exechon budgets: the fit does not belong to the data");
  const kinematics::ExechonModel estimated =
      withExechonParameters(initial, fit.parameters, initial.world_T_zoppi);
  const auto n = static_cast<Eigen::Index>(data.observations.size());
  const auto cols = static_cast<Eigen::Index>(fit.free_indices.size());
  const geometry::RigidTransform f =
      fit.measurement_frame.value_or(geometry::RigidTransform::Identity());
  // r = world(y) − p(θ): ∂r/∂θ = −∂p/∂θ; ∂r/∂δt = I, ∂r/∂δω = −[R_f·y]×.
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(3 * n, cols);
  for (Eigen::Index i = 0; i < n; ++i) {
    const ExechonObservation& o = data.observations[static_cast<std::size_t>(i)];
    const auto Jp = exechonTargetJacobian(
        estimated, o.joints, data.target_offset, estimated.home, calibration.fk);
    if (!Jp) continue;
    for (Eigen::Index c = 0; c < cols; ++c) {
      const int k = fit.free_indices[static_cast<std::size_t>(c)];
      if (k < kExechonParameters)
        J.block<3, 1>(3 * i, c) = -Jp->col(k);
      else if (k < kExechonParameters + 3)
        J.block<3, 1>(3 * i, c) = Eigen::Vector3d::Unit(k - kExechonParameters);
      else
        J.block<3, 1>(3 * i, c) =
            -geometry::hat(f.linear() * o.point).col(k - kExechonParameters - 3);
    }
  }
  ParameterBudgetInput in;
  const std::string unit(toString(initial.unit));
  in.values.resize(cols);
  for (Eigen::Index c = 0; c < cols; ++c) {
    const int k = fit.free_indices[static_cast<std::size_t>(c)];
    const bool param = k < kExechonParameters;
    in.names.push_back(
        param ? exechonParameterName(k)
              : measurementFrameNames()[static_cast<std::size_t>(k - kExechonParameters)]);
    in.units.push_back(param ? (exechonParameterIsLength(k) ? unit : "rad")
                             : (k < kExechonParameters + 3 ? unit : "rad"));
    in.values(c) = param ? fit.parameters(k) : 0.0;
  }
  in.inverse = identificationInverse(J, fit.identifiability.rank, J.rows());
  in.residual_sigma = fit.sigma;
  in.residual_unit = unit;
  in.sources = pointSources(data, sources, initial.unit);
  // The leg readings' errors reach the residuals r = world(y) − p(θ, q) through −∂p/∂q.
  const std::vector<Eigen::Matrix3d> J_target_legs =
      detail::exechonTargetLegJacobian(estimated, data, calibration.fk);
  for (const detail::LegReadingSource& s :
       detail::exechonLegReadingSources(estimated, data, sources, calibration.fk))
    in.sources.push_back({s.contributor, detail::legEffect(J_target_legs, s).sparseView()});
  in.coverage_factor = sources.coverage_factor;

  ExechonParameterUncertainty out;
  out.linear = parameterBudgets(in);
  out.covariance = Eigen::MatrixXd::Zero(kExechonParameters, kExechonParameters);
  for (Eigen::Index a = 0; a < cols; ++a) {
    const int ka = fit.free_indices[static_cast<std::size_t>(a)];
    out.parameter_indices.push_back(ka < kExechonParameters ? ka : -1);
    if (ka >= kExechonParameters) continue;
    for (Eigen::Index b = 0; b < cols; ++b) {
      const int kb = fit.free_indices[static_cast<std::size_t>(b)];
      if (kb < kExechonParameters) out.covariance(ka, kb) = out.linear.covariance(a, b);
    }
  }
  return out;
}

TcpUncertainty exechonToolUncertainty(const kinematics::ExechonModel& estimated,
                                      const Eigen::MatrixXd& covariance,
                                      const std::vector<kinematics::ExechonJoints>& configurations,
                                      const Eigen::Vector3d& target_offset,
                                      const kinematics::FkOptions& fk,
                                      double coverage_factor) {
  PKM_CHECK(covariance.rows() == kExechonParameters && covariance.cols() == kExechonParameters,
            "tool uncertainty: the covariance must be 26 x 26, got {} x {}",
            covariance.rows(),
            covariance.cols());
  PKM_CHECK(coverage_factor > 0.0, "tool uncertainty: the coverage factor must be > 0");
  TcpUncertainty out;
  double sum = 0.0;
  for (const kinematics::ExechonJoints& q : configurations) {
    const auto J = exechonTargetJacobian(estimated, q, target_offset, estimated.home, fk);
    if (!J) {
      out.expanded.push_back(std::numeric_limits<double>::quiet_NaN());
      continue;
    }
    const double U = positionExpandedUncertainty(*J, covariance, coverage_factor);
    out.expanded.push_back(U);
    out.max = std::max(out.max, U);
    sum += U;
    ++out.poses;
  }
  out.mean = out.poses > 0 ? sum / out.poses : 0.0;
  return out;
}

}  // namespace pkm::calibration
