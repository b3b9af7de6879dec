#include "detail/hexapod_least_squares.hpp"

#include <ceres/ceres.h>

#include "detail/least_squares.hpp"
#include "detail/observations.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"

namespace pkm::calibration {
namespace {

using detail::FrameEstimate;
using detail::HexapodUnknownColumns;
using detail::HexapodUnknownValues;
using detail::ObservationRef;
using kinematics::HexapodData;
using kinematics::HexapodModel;

/// One observation as a Ceres residual block over the parameters (42) and, when the data has a
/// measurement frame, the frame correction (6).
class ObservationCost final : public ceres::CostFunction {
 public:
  ObservationCost(const HexapodModel& model,
                  const HexapodCalibrationData& data,
                  ObservationRef ref,
                  const geometry::RigidTransform* frame,
                  bool backlash)
      : model_(model),
        data_(data),
        ref_(ref),
        has_frame_(frame != nullptr),
        has_backlash_(backlash) {
    if (frame != nullptr) frame_.initial = *frame;
    set_num_residuals(static_cast<int>(ref.rows()));
    mutable_parameter_block_sizes()->push_back(kHexapodParameters);
    if (has_frame_) mutable_parameter_block_sizes()->push_back(6);
    if (has_backlash_) mutable_parameter_block_sizes()->push_back(kinematics::kStruts);
  }
  bool Evaluate(double const* const* parameters,
                double* residuals,
                double** jacobians) const final {
    const HexapodModel m =
        withHexapodParameters(model_, Eigen::Map<const HexapodParameterVector>(parameters[0]));
    FrameEstimate frame = frame_;
    if (has_frame_) frame.delta = Eigen::Map<const Eigen::Matrix<double, 6, 1>>(parameters[1]);
    HexapodData work(m);
    Eigen::MatrixXd Jt, Jf, Jb;
    const bool want = jacobians != nullptr;
    kinematics::StrutVector b = kinematics::StrutVector::Zero();
    const int backlash_block = has_frame_ ? 2 : 1;
    if (has_backlash_) b = Eigen::Map<const kinematics::StrutVector>(parameters[backlash_block]);
    if (!detail::evaluate(m,
                          work,
                          data_,
                          ref_,
                          has_frame_ ? &frame : nullptr,
                          residuals,
                          want ? &Jt : nullptr,
                          want && has_frame_ ? &Jf : nullptr,
                          has_backlash_ ? &b : nullptr,
                          want && has_backlash_ ? &Jb : nullptr))
      return false;
    const Eigen::Index rows = ref_.rows();
    if (want && jacobians[0] != nullptr) {
      Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> out(
          jacobians[0], rows, kHexapodParameters);
      out = Jt;
    }
    if (want && has_frame_ && jacobians[1] != nullptr) {
      Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> out(
          jacobians[1], rows, 6);
      out = Jf;
    }
    if (want && has_backlash_ && jacobians[backlash_block] != nullptr) {
      Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> out(
          jacobians[backlash_block], rows, kinematics::kStruts);
      out = Jb;
    }
    return true;
  }

 private:
  const HexapodModel& model_;
  const HexapodCalibrationData& data_;
  ObservationRef ref_;
  bool has_frame_;
  bool has_backlash_;
  FrameEstimate frame_;
};

/// Holds the estimate at its start along an unidentifiable direction n = (n_θ, n_frame,
/// n_backlash): r = n_θ·(θ − θ₀) + n_frame·δ + n_backlash·(b − b₀), one block per unknown group.
class NullSpacePrior final : public ceres::CostFunction {
 public:
  NullSpacePrior(std::vector<Eigen::VectorXd> n, std::vector<Eigen::VectorXd> start)
      : n_(std::move(n)), start_(std::move(start)) {
    set_num_residuals(1);
    for (const Eigen::VectorXd& v : n_)
      mutable_parameter_block_sizes()->push_back(static_cast<int>(v.size()));
  }
  bool Evaluate(double const* const* parameters,
                double* residuals,
                double** jacobians) const final {
    residuals[0] = 0.0;
    for (std::size_t b = 0; b < n_.size(); ++b) {
      const auto size = n_[b].size();
      const Eigen::Map<const Eigen::VectorXd> x(parameters[b], size);
      residuals[0] += n_[b].dot(x - start_[b]);
      if (jacobians != nullptr && jacobians[b] != nullptr) {
        Eigen::Map<Eigen::VectorXd> out(jacobians[b], size);
        out = n_[b];
      }
    }
    return true;
  }

 private:
  std::vector<Eigen::VectorXd> n_, start_;
};

/// A new robust loss of `options` (nullptr for none), owned by the problem it is added to.
ceres::LossFunction* makeHexapodLoss(const HexapodCalibrationOptions& options) {
  switch (options.loss) {
    case RobustLoss::kNone:
      return nullptr;
    case RobustLoss::kHuber:
      return new ceres::HuberLoss(options.loss_scale);
    case RobustLoss::kCauchy:
      return new ceres::CauchyLoss(options.loss_scale);
  }
  return nullptr;
}

/// Adds to `problem` (parameter blocks `blocks`: θ, then δ and b as laid out in `u`) one
/// NullSpacePrior per null-space vector of out.identifiability, holding the unknowns at their
/// start (out.initial, δ = 0, backlash0) along it.
void addNullSpacePriors(ceres::Problem& problem,
                        const std::vector<double*>& blocks,
                        const HexapodCalibrationSummary& out,
                        const HexapodUnknownColumns& u,
                        const kinematics::StrutVector& backlash0) {
  for (Eigen::Index k = 0; k < out.identifiability.null_space.cols(); ++k) {
    const Eigen::VectorXd col = out.identifiability.null_space.col(k);
    Eigen::VectorXd n = Eigen::VectorXd::Zero(kHexapodParameters);
    for (Eigen::Index c = 0; c < u.n_free; ++c)
      n(out.free_indices[static_cast<std::size_t>(c)]) = col(c);
    std::vector<Eigen::VectorXd> ns{n}, starts{Eigen::VectorXd(out.initial)};
    if (u.has_frame) {
      ns.emplace_back(col.segment(u.n_free, 6));
      starts.emplace_back(Eigen::VectorXd::Zero(6));
    }
    if (u.has_backlash) {
      ns.emplace_back(col.tail(6));
      starts.emplace_back(Eigen::VectorXd(backlash0));
    }
    problem.AddResidualBlock(new NullSpacePrior(ns, starts), nullptr, blocks);
  }
}

/// Adds to `problem` (blocks as for addNullSpacePriors) the Tikhonov prior
/// prior_weight·(θ_k − θ₀_k) per free parameter k (a NullSpacePrior along e_k).
void addParameterPriors(ceres::Problem& problem,
                        const std::vector<double*>& blocks,
                        const HexapodCalibrationSummary& out,
                        const HexapodUnknownColumns& u,
                        const kinematics::StrutVector& backlash0,
                        double prior_weight) {
  for (const int k : out.free_indices) {
    std::vector<Eigen::VectorXd> ns{prior_weight * Eigen::VectorXd::Unit(kHexapodParameters, k)};
    std::vector<Eigen::VectorXd> starts{Eigen::VectorXd(out.initial)};
    if (u.has_frame) {
      ns.emplace_back(Eigen::VectorXd::Zero(6));
      starts.emplace_back(Eigen::VectorXd::Zero(6));
    }
    if (u.has_backlash) {
      ns.emplace_back(Eigen::VectorXd::Zero(6));
      starts.emplace_back(Eigen::VectorXd(backlash0));
    }
    problem.AddResidualBlock(new NullSpacePrior(ns, starts), nullptr, blocks);
  }
}

}  // namespace

void detail::solveHexapodProblem(const HexapodModel& initial,
                                 const HexapodCalibrationData& data,
                                 const HexapodCalibrationOptions& options,
                                 const HexapodUnknownColumns& u,
                                 const kinematics::StrutVector& backlash0,
                                 double prior_weight,
                                 HexapodUnknownValues& x,
                                 HexapodCalibrationSummary& out) {
  std::vector<double*> blocks{x.theta.data()};
  if (u.has_frame) blocks.push_back(x.delta.data());
  if (u.has_backlash) blocks.push_back(x.backlash.data());
  ceres::Problem problem;
  const geometry::RigidTransform* frame_ptr = u.has_frame ? &*data.measurement_frame : nullptr;
  for (const ObservationRef& ref : detail::observations(data))
    problem.AddResidualBlock(new ObservationCost(initial, data, ref, frame_ptr, u.has_backlash),
                             makeHexapodLoss(options),
                             blocks);
  addNullSpacePriors(problem, blocks, out, u, backlash0);
  if (prior_weight > 0.0) addParameterPriors(problem, blocks, out, u, backlash0, prior_weight);
  detail::holdFixedParameters(problem, x.theta.data(), kHexapodParameters, options.free);
  detail::solveLeastSquares(problem,
                            {options.max_iterations,
                             options.function_tolerance,
                             options.gradient_tolerance,
                             options.parameter_tolerance})
      .copyTo(out);
}

}  // namespace pkm::calibration
