// Linear uncertainty budgets of a hexapod calibration and the predicted TCP uncertainty
// (calibration/hexapod_budget.hpp).
#include "pkm/calibration/hexapod_budget.hpp"

#include <fmt/format.h>

#include <Eigen/QR>
#include <Eigen/SVD>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <limits>

#include "detail/hexapod_errors.hpp"
#include "pkm/core/error.hpp"
#include "pkm/core/parallel.hpp"
#include "pkm/geometry/so3.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"

namespace pkm::calibration {
namespace {

using detail::ObservationRef;

/// The fit's unknowns at the estimate: the identification Jacobian's free columns, then frame and
/// backlash columns, with the observation row offsets.
struct Stacked {
  Eigen::MatrixXd J;                     ///< rows: observations (then priors); cols: unknowns
  Eigen::Index observation_rows = 0;     ///< rows of J from observations
  std::vector<Eigen::Index> row_offset;  ///< first row of each observation (observations order)
};

/// Evaluation context: the estimate, its frame and backlash.
struct AtEstimate {
  kinematics::HexapodModel model;
  detail::FrameEstimate frame;
  bool has_frame = false;
  std::optional<kinematics::StrutVector> backlash;
  [[nodiscard]] const detail::FrameEstimate* framePtr() const {
    return has_frame ? &frame : nullptr;
  }
};

Eigen::VectorXd blockResidual(const AtEstimate& at,
                              kinematics::HexapodData& work,
                              const HexapodCalibrationData& data,
                              const ObservationRef& ref) {
  double r[6] = {0, 0, 0, 0, 0, 0};
  const bool ok = detail::evaluate(at.model,
                                   work,
                                   data,
                                   ref,
                                   at.framePtr(),
                                   r,
                                   nullptr,
                                   nullptr,
                                   at.backlash ? &*at.backlash : nullptr);
  Eigen::VectorXd out = Eigen::VectorXd::Zero(ref.rows());
  if (ok)
    for (Eigen::Index k = 0; k < ref.rows(); ++k) out(k) = r[k];
  return out;
}

Stacked stackUnknowns(const AtEstimate& at,
                      const HexapodCalibrationData& data,
                      const HexapodCalibrationSummary& fit,
                      const HexapodCalibrationOptions& calibration) {
  const std::vector<ObservationRef> refs = detail::observations(data);
  const auto n_free = static_cast<Eigen::Index>(fit.free_indices.size());
  const Eigen::Index n_frame = at.has_frame ? 6 : 0, n_back = at.backlash ? 6 : 0;
  Stacked s;
  s.observation_rows = static_cast<Eigen::Index>(data.equations());
  const bool prior = calibration.parameter_prior_sigma > 0.0;
  s.J.setZero(s.observation_rows + (prior ? n_free : 0), n_free + n_frame + n_back);
  kinematics::HexapodData work(at.model);
  Eigen::Index row = 0;
  for (const ObservationRef& ref : refs) {
    s.row_offset.push_back(row);
    double r[6];
    Eigen::MatrixXd Jt, Jf, Jb;
    if (detail::evaluate(at.model,
                         work,
                         data,
                         ref,
                         at.framePtr(),
                         r,
                         &Jt,
                         at.has_frame ? &Jf : nullptr,
                         at.backlash ? &*at.backlash : nullptr,
                         at.backlash ? &Jb : nullptr)) {
      for (Eigen::Index c = 0; c < n_free; ++c)
        s.J.block(row, c, ref.rows(), 1) = Jt.col(fit.free_indices[static_cast<std::size_t>(c)]);
      if (at.has_frame) s.J.block(row, n_free, ref.rows(), 6) = Jf;
      if (at.backlash) s.J.block(row, n_free + n_frame, ref.rows(), 6) = Jb;
    }
    row += ref.rows();
  }
  if (prior)
    s.J.bottomLeftCorner(n_free, n_free)
        .diagonal()
        .setConstant(calibration.measurement_sigma / calibration.parameter_prior_sigma);
  return s;
}

/// The first block (in observations order) of each kind of observation and of each constrained
/// set: the block of a coordinate's own observation without a search.
struct BlockIndex {
  std::size_t points = 0, distances = 0;
  std::vector<std::size_t> gauge_sets;
  explicit BlockIndex(const HexapodCalibrationData& data) : points(data.poses.size()) {
    std::size_t next = points + data.points.size();
    for (const ConstrainedMotionData& c : data.constrained) {
      gauge_sets.push_back(next);
      next += c.stations.size();
    }
    distances = next;
  }
  /// The blocks `c` touches: its own observation's, or every station of its set (a reference
  /// gauge or reading), as [first, last).
  [[nodiscard]] std::pair<std::size_t, std::size_t> touched(
      const HexapodCalibrationData& data, const detail::MeasuredCoordinate& c) const {
    switch (c.ref.kind) {
      case ObservationRef::Kind::kPose:
        return {c.ref.index, c.ref.index + 1};
      case ObservationRef::Kind::kPoint:
        return {points + c.ref.index, points + c.ref.index + 1};
      case ObservationRef::Kind::kGauge: {
        const std::size_t first = gauge_sets[c.ref.set];
        if (detail::actsOnWholeSet(c))
          return {first, first + data.constrained[c.ref.set].stations.size()};
        return {first + c.ref.index, first + c.ref.index + 1};
      }
      case ObservationRef::Kind::kDistance:
        return {distances + c.ref.index, distances + c.ref.index + 1};
    }
    return {0, 0};
  }
};

/// The effect matrix of one source: per coordinate, the central difference of the residual blocks
/// it touches (a reference gauge touches every station of its set), scaled by u/u_ref; the
/// coordinates of one group add into one column. Sparse: a coordinate touches only its own
/// observation's rows (or its constrained set's); exact zeros are not stored.
Eigen::SparseMatrix<double> effectOf(const AtEstimate& at,
                                     const HexapodCalibrationData& data,
                                     const Stacked& s,
                                     const std::vector<ObservationRef>& refs,
                                     const detail::CoordinateSource& source) {
  const double u_ref = source.contributor.standardUncertainty();
  const detail::SourceColumns columns = detail::sourceColumns(source);
  const BlockIndex blocks(data);
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(source.coordinates.size() * 6);
  kinematics::HexapodData work(at.model);
  // One copy of the data: each perturbation is undone by restoring the observation from `data`.
  HexapodCalibrationData d = data;
  for (std::size_t j = 0; j < source.coordinates.size(); ++j) {
    const detail::MeasuredCoordinate& c = source.coordinates[j];
    const bool rotation =
        c.ref.kind == ObservationRef::Kind::kPose && c.coordinate >= 3 && c.coordinate < 6;
    const double h = rotation ? 1e-6 : 1e-6 * at.model.characteristicLength();
    const double scale = u_ref > 0.0 ? c.u / u_ref : 0.0;
    const auto [first, last] = blocks.touched(data, c);
    for (std::size_t b = first; b < last; ++b) {
      const ObservationRef& ref = refs[b];
      detail::perturbMeasurement(d, c, h);
      const Eigen::VectorXd rp = blockResidual(at, work, d, ref);
      detail::restoreMeasurement(d, data, c);
      detail::perturbMeasurement(d, c, -h);
      const Eigen::VectorXd rm = blockResidual(at, work, d, ref);
      detail::restoreMeasurement(d, data, c);
      for (Eigen::Index k = 0; k < ref.rows(); ++k) {
        const double v = (rp(k) - rm(k)) / (2.0 * h) * scale;
        if (v != 0.0) entries.emplace_back(s.row_offset[b] + k, columns.column[j], v);
      }
    }
  }
  Eigen::SparseMatrix<double> E(s.observation_rows, columns.count);
  E.setFromTriplets(entries.begin(), entries.end());  // a group's coordinates add up
  return E;
}

/// The number of singular values of J above its largest times n·ε (Eigen's default threshold).
int numericalRank(const Eigen::MatrixXd& J) {
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(J);
  const Eigen::VectorXd& s = svd.singularValues();
  if (s.size() == 0) return 0;
  const double threshold = s(0) * static_cast<double>(std::max(J.rows(), J.cols())) *
                           Eigen::NumTraits<double>::epsilon();
  return static_cast<int>((s.array() > threshold).count());
}

/// The prior (calibration.parameter_prior_sigma) as an input of the budgets: each of the p prior
/// rows w·(θ_k − θ₀_k), w = σ_r/σ_θ, changes by w per σ_θ of error in the machine file's θ₀_k.
ObservationErrorSource priorSource(const HexapodCalibrationOptions& calibration,
                                   LengthUnit unit,
                                   Eigen::Index p) {
  ObservationErrorSource prior;
  const double sigma = calibration.prior_uncertainty > 0.0 ? calibration.prior_uncertainty
                                                           : calibration.parameter_prior_sigma;
  prior.contributor.name = "prior: the machine file's geometry";
  prior.contributor.value = sigma;
  prior.contributor.unit = std::string(toString(unit));
  prior.contributor.distribution = metrology::Distribution::kNormal;
  prior.contributor.normal_k = 1.0;
  prior.contributor.source = fmt::format(
      "the true geometry within sigma {:g} {} of the machine file, per parameter (the fit's prior "
      "weight: sigma {:g} {}); it fixes the directions the data do not see",
      sigma,
      toString(unit),
      calibration.parameter_prior_sigma,
      toString(unit));
  // Prior row k is w·(θ_k − θ₀_k), w = σ_r/σ_prior: an error e in θ₀_k changes it by −w·e.
  prior.effect.resize(p, p);
  prior.effect.setIdentity();
  prior.effect *= calibration.measurement_sigma / calibration.parameter_prior_sigma;
  return prior;
}

}  // namespace

HexapodParameterUncertainty hexapodParameterUncertainty(
    const kinematics::HexapodModel& initial,
    const HexapodCalibrationData& data,
    const HexapodCalibrationSummary& fit,
    const HexapodCalibrationOptions& calibration,
    const metrology::UncertaintySources& sources) {
  std::string why;
  PKM_CHECK(sources.isValid(&why), "{}", why);
  PKM_CHECK(!fit.free_indices.empty() &&
                data.measurement_frame.has_value() == fit.measurement_frame.has_value(),
            "hexapod budgets: the fit does not belong to the data");
  AtEstimate at{withHexapodParameters(initial, fit.parameters), {}, false, fit.backlash};
  if (fit.measurement_frame) {
    at.frame.initial = *fit.measurement_frame;
    at.has_frame = true;
  }
  const Stacked s = stackUnknowns(at, data, fit, calibration);
  const std::vector<ObservationRef> refs = detail::observations(data);

  ParameterBudgetInput in;
  const std::string unit(toString(initial.unit));
  for (const int k : fit.free_indices) {
    in.names.push_back(hexapodParameterName(k));
    in.units.push_back(unit);
  }
  if (at.has_frame)
    for (std::size_t k = 0; k < 6; ++k) {
      in.names.push_back(measurementFrameNames()[k]);
      in.units.push_back(k < 3 ? unit : "rad");
    }
  if (at.backlash)
    for (const std::string& n : backlashNames()) {
      in.names.push_back(n);
      in.units.push_back(unit);
    }
  in.values.resize(static_cast<Eigen::Index>(in.names.size()));
  Eigen::Index v = 0;
  for (const int k : fit.free_indices) in.values(v++) = fit.parameters(k);
  for (Eigen::Index k = 0; k < (at.has_frame ? 6 : 0); ++k) in.values(v++) = 0.0;
  for (Eigen::Index k = 0; k < (at.backlash ? 6 : 0); ++k) in.values(v++) = (*at.backlash)(k);
  const bool prior = calibration.parameter_prior_sigma > 0.0;
  // The inverse (an SVD) and the sources' effects are independent: the SVD on a spare core.
  auto inverse = alongside([&] {
    // With a prior every direction is determined (by the data or by the prior): the inverse of
    // the whole stacked system, its prior columns carrying the prior's own uncertainty.
    return prior ? identificationInverse(s.J, numericalRank(s.J), s.J.rows())
                 : identificationInverse(s.J, fit.identifiability.rank, s.observation_rows);
  });
  in.residual_sigma = fit.sigma;
  in.residual_unit = unit;
  for (const detail::CoordinateSource& src :
       detail::hexapodCoordinateSources(data, sources, initial, fit.backlash.has_value()))
    in.sources.push_back({src.contributor, effectOf(at, data, s, refs, src)});
  const Eigen::MatrixXd all = inverse.get();
  in.inverse = all.leftCols(s.observation_rows);
  if (prior) {
    in.prior_inverse = all.rightCols(s.J.rows() - s.observation_rows);
    in.prior = priorSource(calibration, initial.unit, in.prior_inverse.cols());
  }
  in.coverage_factor = sources.coverage_factor;

  HexapodParameterUncertainty out;
  out.linear = parameterBudgets(in);
  out.covariance = Eigen::MatrixXd::Zero(kHexapodParameters, kHexapodParameters);
  for (std::size_t a = 0; a < in.names.size(); ++a)
    out.parameter_indices.push_back(a < fit.free_indices.size() ? fit.free_indices[a] : -1);
  for (std::size_t a = 0; a < fit.free_indices.size(); ++a)
    for (std::size_t b = 0; b < fit.free_indices.size(); ++b)
      out.covariance(fit.free_indices[a], fit.free_indices[b]) =
          out.linear.covariance(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b));
  return out;
}

TcpUncertainty hexapodTcpUncertainty(const kinematics::HexapodModel& estimated,
                                     const Eigen::MatrixXd& covariance,
                                     const std::vector<kinematics::PoseRpy>& poses,
                                     double coverage_factor,
                                     bool align_rigid) {
  PKM_CHECK(covariance.rows() == kHexapodParameters && covariance.cols() == kHexapodParameters,
            "TCP uncertainty: the covariance must be 42 x 42, got {} x {}",
            covariance.rows(),
            covariance.cols());
  PKM_CHECK(coverage_factor > 0.0, "TCP uncertainty: the coverage factor must be > 0");
  // The stacked position Jacobian of the poses whose FK converges.
  kinematics::HexapodData work(estimated);
  std::vector<Eigen::Matrix<double, 3, kHexapodParameters>> rows;
  std::vector<Eigen::Vector3d> points;
  std::vector<bool> ok;
  for (const kinematics::PoseRpy& pose : poses) {
    const kinematics::StrutVector q = kinematics::inverseKinematics(estimated, work, pose);
    PoseParameterJacobian J;
    ok.push_back(forwardPoseError(estimated, work, q, pose, pose, &J).has_value());
    if (!ok.back()) continue;
    rows.push_back(J.topRows<3>());
    points.push_back(pose.position);
  }
  const auto n = static_cast<Eigen::Index>(rows.size());
  Eigen::MatrixXd P(3 * n, kHexapodParameters);
  for (Eigen::Index i = 0; i < n; ++i) P.middleRows<3>(3 * i) = rows[static_cast<std::size_t>(i)];
  if (align_rigid && n >= 3) {
    // Remove what a rigid motion δt + δω × p_i explains: P ← (I − R R⁺) P.
    Eigen::MatrixXd R(3 * n, 6);
    for (Eigen::Index i = 0; i < n; ++i) {
      R.block<3, 3>(3 * i, 0).setIdentity();
      R.block<3, 3>(3 * i, 3) = -geometry::hat(points[static_cast<std::size_t>(i)]);
    }
    P -= R * R.completeOrthogonalDecomposition().solve(P);
  }
  TcpUncertainty out;
  double sum = 0.0;
  Eigen::Index k = 0;
  for (const bool converged : ok) {
    if (!converged) {
      out.expanded.push_back(std::numeric_limits<double>::quiet_NaN());
      continue;
    }
    const double U =
        positionExpandedUncertainty(P.middleRows<3>(3 * k++), covariance, coverage_factor);
    out.expanded.push_back(U);
    out.max = std::max(out.max, U);
    sum += U;
    ++out.poses;
  }
  out.mean = out.poses > 0 ? sum / out.poses : 0.0;
  return out;
}

void addTcpRemainder(TcpUncertainty& tcp, double rms, double coverage_factor) {
  PKM_CHECK(std::isfinite(rms) && rms >= 0.0, "TCP remainder: the RMS must be finite and >= 0");
  PKM_CHECK(coverage_factor > 0.0, "TCP remainder: the coverage factor must be > 0");
  const double R = coverage_factor * rms / std::sqrt(3.0);
  double sum = 0.0;
  tcp.max = 0.0;
  for (double& U : tcp.expanded) {
    if (!std::isfinite(U)) continue;
    U = std::hypot(U, R);
    tcp.max = std::max(tcp.max, U);
    sum += U;
  }
  tcp.mean = tcp.poses > 0 ? sum / tcp.poses : 0.0;
  tcp.remainder = std::hypot(tcp.remainder, R);
}

}  // namespace pkm::calibration
