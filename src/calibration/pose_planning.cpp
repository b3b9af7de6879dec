#include "pkm/calibration/pose_planning.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <random>

#include "pkm/calibration/hexapod_measurements.hpp"
#include "pkm/core/error.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"

namespace pkm::calibration {
namespace {

using Block = Eigen::MatrixXd;  // rows of one pose × free parameters

/// The identification Jacobian rows of every candidate (free columns only).
std::vector<Block> candidateBlocks(const kinematics::HexapodModel& model,
                                   const std::vector<kinematics::PoseRpy>& candidates,
                                   const PosePlanOptions& options,
                                   const std::vector<int>& free) {
  kinematics::HexapodData data(model);
  std::vector<Block> blocks;
  blocks.reserve(candidates.size());
  const auto n = static_cast<Eigen::Index>(free.size());
  for (const kinematics::PoseRpy& pose : candidates) {
    PoseParameterJacobian J;
    PoseObservation o;
    o.pose = pose;
    o.readings = kinematics::inverseKinematics(model, data, pose);
    if (options.measurement == PlannedMeasurement::kFullPose) {
      (void)poseResiduals(model, data, o, &J);
    } else {
      const auto e = forwardPoseError(model, data, o.readings, pose, pose, &J);
      PKM_CHECK(e.has_value(), "pose planning: FK fails at a candidate pose");
    }
    const Eigen::Index rows = options.measurement == PlannedMeasurement::kFullPose ? 6 : 3;
    Block b(rows, n);
    for (Eigen::Index c = 0; c < n; ++c)
      b.col(c) = J.col(free[static_cast<std::size_t>(c)]).head(rows);
    blocks.push_back(std::move(b));
  }
  return blocks;
}

/// Singular values (descending) of the scaled Jacobian whose information matrix is M.
Eigen::VectorXd singularValues(const Eigen::MatrixXd& M) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(M, Eigen::EigenvaluesOnly);
  Eigen::VectorXd s = eig.eigenvalues().cwiseMax(0.0).cwiseSqrt().reverse();
  return s;
}

double indexOf(const Eigen::MatrixXd& M, ObservabilityIndex index, Eigen::Index rows) {
  return observabilityIndex(index, singularValues(M), rows);
}

/// Candidates evaluated exactly per step for the indices other than O1.
constexpr std::size_t kShortlist = 24;

/// The unused candidates ordered by their D-optimal gain log det(I + B·M⁻¹·Bᵀ) (the matrix
/// determinant lemma), best first; all of them for O1, whose index is a monotone function of the
/// gain, else the best kShortlist (the exact index is then evaluated on those only).
std::vector<std::size_t> shortlist(const Eigen::MatrixXd& M,
                                   const std::vector<Block>& blocks,
                                   const std::vector<char>& used,
                                   bool all) {
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(M);
  std::vector<std::pair<double, std::size_t>> gains;
  for (std::size_t c = 0; c < blocks.size(); ++c) {
    if (used[c]) continue;
    const Block& B = blocks[c];
    const Eigen::MatrixXd S =
        Eigen::MatrixXd::Identity(B.rows(), B.rows()) + B * ldlt.solve(B.transpose());
    gains.emplace_back(Eigen::LDLT<Eigen::MatrixXd>(S).vectorD().array().log().sum(), c);
  }
  std::sort(gains.begin(), gains.end(), [](const auto& a, const auto& b) {
    return a.first > b.first || (a.first == b.first && a.second < b.second);
  });
  if (!all && gains.size() > kShortlist) gains.resize(kShortlist);
  std::vector<std::size_t> out;
  for (const auto& g : gains) out.push_back(g.second);
  return out;
}

/// Ridge of the information matrix while poses are chosen: the first poses cannot be full rank.
constexpr double kInformationRidge = 1e-9;

/// Scales the columns of every candidate block (in place) by √(candidates) / the column's norm
/// over all candidates, so that the indices do not depend on units; returns each candidate's
/// scaled information matrix JᵀJ (n × n, n = free parameters).
std::vector<Eigen::MatrixXd> scaleCandidateBlocks(std::vector<Block>& blocks, Eigen::Index n) {
  Eigen::VectorXd norm2 = Eigen::VectorXd::Zero(n);
  for (const Block& b : blocks) norm2 += b.colwise().squaredNorm().transpose();
  const Eigen::VectorXd scale = norm2.cwiseSqrt().cwiseMax(1e-300).cwiseInverse() *
                                std::sqrt(static_cast<double>(blocks.size()));
  std::vector<Eigen::MatrixXd> info;  // per candidate: scaled Jᵀ J
  info.reserve(blocks.size());
  for (Block& b : blocks) {
    b = b * scale.asDiagonal();
    info.push_back(b.transpose() * b);
  }
  return info;
}

/// Greedy phase: chooses `count` candidates one at a time, each the best for `index` (of `rows`
/// equations) given the information M (updated in place, regularised); marks them in `used` and
/// appends them to plan.chosen.
void choosePosesGreedily(const std::vector<Block>& blocks,
                         const std::vector<Eigen::MatrixXd>& info,
                         int count,
                         ObservabilityIndex index,
                         Eigen::Index rows,
                         Eigen::MatrixXd& M,
                         std::vector<char>& used,
                         PosePlan& plan) {
  for (int k = 0; k < count; ++k) {
    int best = -1;
    double best_value = -1.0;
    if (index == ObservabilityIndex::kO1) {
      best = static_cast<int>(shortlist(M, blocks, used, true).front());
    } else {
      for (const std::size_t c : shortlist(M, blocks, used, false)) {
        const double v = indexOf(M + info[c], index, rows);
        if (v > best_value) best_value = v, best = static_cast<int>(c);
      }
    }
    used[static_cast<std::size_t>(best)] = 1;
    plan.chosen.push_back(best);
    M += info[static_cast<std::size_t>(best)];
  }
}

/// Exchange passes (at most exchange_passes): swaps a chosen pose for an unused candidate when the
/// index grows by more than a relative 1e-12, until a pass improves nothing; updates M, `used`,
/// plan.chosen and plan.swaps.
void exchangePoses(const std::vector<Block>& blocks,
                   const std::vector<Eigen::MatrixXd>& info,
                   ObservabilityIndex index,
                   Eigen::Index rows,
                   int exchange_passes,
                   Eigen::MatrixXd& M,
                   std::vector<char>& used,
                   PosePlan& plan) {
  double current = indexOf(M, index, rows);
  for (int pass = 0; pass < exchange_passes; ++pass) {
    bool improved = false;
    for (int& chosen : plan.chosen) {
      const Eigen::MatrixXd without = M - info[static_cast<std::size_t>(chosen)];
      int best = -1;
      double best_value = current;
      for (const std::size_t c : shortlist(without, blocks, used, false)) {
        const double v = indexOf(without + info[c], index, rows);
        if (v > best_value * (1.0 + 1e-12)) best_value = v, best = static_cast<int>(c);
      }
      if (best < 0) continue;
      used[static_cast<std::size_t>(chosen)] = 0;
      used[static_cast<std::size_t>(best)] = 1;
      chosen = best;
      M = without + info[static_cast<std::size_t>(best)];
      current = best_value;
      ++plan.swaps;
      improved = true;
    }
    if (!improved) break;
  }
}

/// Stores the plan's index value, all five indices, rank and condition number, from the
/// information matrix M of the chosen poses (ridge removed; `rows` equations).
void fillPlanIndices(const Eigen::MatrixXd& M,
                     ObservabilityIndex index,
                     Eigen::Index rows,
                     PosePlan& plan) {
  const Eigen::VectorXd s = singularValues(M);
  plan.index_value = observabilityIndex(index, s, rows);
  for (const ObservabilityIndex i : {ObservabilityIndex::kO1,
                                     ObservabilityIndex::kO2,
                                     ObservabilityIndex::kO3,
                                     ObservabilityIndex::kO4,
                                     ObservabilityIndex::kO5})
    plan.indices.push_back(observabilityIndex(i, s, rows));
  const double tol = 1e-8 * s(0);
  plan.rank = static_cast<int>((s.array() > tol).count());
  plan.condition_number = plan.rank > 0 ? s(0) / s(plan.rank - 1) : INFINITY;
}

/// Baseline: the mean `index` of random subsets of `count` of the candidates (information
/// matrices `info`, n × n), drawn from a fixed stream.
double randomSubsetBaseline(const std::vector<Eigen::MatrixXd>& info,
                            int count,
                            ObservabilityIndex index,
                            Eigen::Index rows,
                            Eigen::Index n) {
  std::mt19937_64 rng(0x9E3779B97F4A7C15ULL);
  std::vector<int> order(info.size());
  for (std::size_t c = 0; c < order.size(); ++c) order[c] = static_cast<int>(c);
  double sum = 0.0;
  constexpr int kBaselineDraws = 20;
  for (int d = 0; d < kBaselineDraws; ++d) {
    std::shuffle(order.begin(), order.end(), rng);
    Eigen::MatrixXd R = Eigen::MatrixXd::Zero(n, n);
    for (int k = 0; k < count; ++k)
      R += info[static_cast<std::size_t>(order[static_cast<std::size_t>(k)])];
    sum += indexOf(R, index, rows);
  }
  return sum / kBaselineDraws;
}

}  // namespace

void PosePlanOptions::validate() const {
  PKM_CHECK(count >= 1, "pose planning: count must be >= 1, got {}", count);
  PKM_CHECK(exchange_passes >= 0, "pose planning: exchange_passes must be >= 0");
  PKM_CHECK(std::any_of(free.begin(), free.end(), [](bool f) { return f; }),
            "pose planning: no parameter is free");
}

PosePlan planHexapodPoses(const kinematics::HexapodModel& model,
                          const std::vector<kinematics::PoseRpy>& candidates,
                          const PosePlanOptions& options) {
  options.validate();
  PKM_CHECK(candidates.size() >= static_cast<std::size_t>(options.count),
            "pose planning: {} candidates for {} poses",
            candidates.size(),
            options.count);
  std::vector<int> free;
  for (int k = 0; k < kHexapodParameters; ++k)
    if (options.free[static_cast<std::size_t>(k)]) free.push_back(k);
  return planFromJacobians(candidateBlocks(model, candidates, options, free),
                           options.count,
                           options.index,
                           options.exchange_passes);
}

PosePlan planFromJacobians(std::vector<Eigen::MatrixXd> blocks,
                           int count,
                           ObservabilityIndex index,
                           int exchange_passes) {
  PKM_CHECK(count >= 1 && exchange_passes >= 0,
            "pose planning: count must be >= 1 and exchange passes >= 0 (got {}, {})",
            count,
            exchange_passes);
  PKM_CHECK(blocks.size() >= static_cast<std::size_t>(count),
            "pose planning: {} candidates for {} poses",
            blocks.size(),
            count);
  const Eigen::Index n = blocks.front().cols();
  for (const Block& b : blocks)
    PKM_CHECK(b.cols() == n && b.rows() == blocks.front().rows() && b.allFinite(),
              "pose planning: every candidate needs finite rows of the same shape");
  PKM_CHECK(n >= 1, "pose planning: no parameter is free");

  const std::vector<Eigen::MatrixXd> info = scaleCandidateBlocks(blocks, n);
  const Eigen::Index rows_per = blocks.front().rows();
  const Eigen::Index rows = rows_per * count;
  // Greedy phase on a slightly regularised information matrix (the first poses cannot be full
  // rank).
  Eigen::MatrixXd M = kInformationRidge * Eigen::MatrixXd::Identity(n, n);
  std::vector<char> used(blocks.size(), 0);
  PosePlan plan;
  choosePosesGreedily(blocks, info, count, index, rows, M, used, plan);
  exchangePoses(blocks, info, index, rows, exchange_passes, M, used, plan);
  M -= kInformationRidge * Eigen::MatrixXd::Identity(n, n);
  fillPlanIndices(M, index, rows, plan);
  plan.random_baseline = randomSubsetBaseline(info, count, index, rows, n);
  return plan;
}

}  // namespace pkm::calibration
