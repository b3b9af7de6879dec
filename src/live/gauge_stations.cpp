// The stations of an automated constrained-motion calibration (pkm/live/gauge_stations.hpp).
#include "pkm/live/gauge_stations.hpp"

#include <fmt/format.h>

#include <Eigen/SVD>
#include <cmath>

#include "pkm/calibration/constrained_motion.hpp"
#include "pkm/calibration/pose_planning.hpp"
#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"
#include "pkm/workflow/pose_checks.hpp"

namespace pkm::live {
namespace {

namespace cal = pkm::calibration;
namespace kin = pkm::kinematics;

/// Singular values below this fraction of the largest are directions the gauges cannot see.
constexpr double kIdentifiableRatio = 1e-6;
/// c takes this many values over [−range, range].
constexpr int kCSteps = 5;

/// (x y z a b c in mm and degrees) of a command (mm, rad).
std::array<double, 6> checkPoseOf(const Eigen::VectorXd& c) {
  return {c[0], c[1], c[2], radToDeg(c[3]), radToDeg(c[4]), radToDeg(c[5])};
}

/// The command of a planar move from the reference.
Eigen::VectorXd commandOf(const simulation::DialGaugeSetup& s, const Eigen::Vector3d& move) {
  Eigen::VectorXd c = s.reference;
  c[0] += move[0];
  c[1] += move[1];
  c[5] += move[2];
  return c;
}

/// The command passes pkm's checks and LinuxCNC's axis limits.
bool reachable(const kin::HexapodModel& model,
               kin::HexapodData& data,
               const GaugeStationOptions& o,
               const Eigen::VectorXd& command) {
  const std::array<double, 6> pose = checkPoseOf(command);
  for (std::size_t k = 0; k < 6; ++k)
    if (pose[k] < o.axis_min[k] || pose[k] > o.axis_max[k]) return false;
  return workflow::checkHexapodPose(model, data, pose).status == "ok";
}

/// The sign of every strut's change over the approach (+1 all lengthen, −1 all shorten, 0 mixed).
int approachSign(const kin::HexapodModel& model,
                 kin::HexapodData& data,
                 const Eigen::VectorXd& below,
                 const Eigen::VectorXd& command) {
  const kin::StrutVector from =
      kin::inverseKinematics(model, data, {below.head<3>(), below.tail<3>()});
  const kin::StrutVector to =
      kin::inverseKinematics(model, data, {command.head<3>(), command.tail<3>()});
  if (((to - from).array() > 0.0).all()) return 1;
  if (((to - from).array() < 0.0).all()) return -1;
  return 0;
}

/// The station's gauge-height Jacobian at the nominal readings (nullopt: FK failed).
std::optional<cal::GaugeParameterJacobian> heightJacobian(const kin::HexapodModel& model,
                                                          kin::HexapodData& data,
                                                          const cal::ConstrainedMotionData& set,
                                                          const Eigen::VectorXd& command) {
  cal::GaugeStation st;
  st.command = {command.head<3>(), command.tail<3>()};
  st.readings = kin::inverseKinematics(model, data, st.command);
  cal::GaugeParameterJacobian J;
  if (!cal::gaugeHeights(model, data, set, st, &J)) return std::nullopt;
  return J;
}

/// Projects every candidate's rows on the parameter directions the candidates together identify
/// (right singular vectors of all rows, columns scaled by their norms, singular values above
/// kIdentifiableRatio of the largest); returns how many there are.
int projectOnIdentifiable(std::vector<Eigen::MatrixXd>& blocks) {
  Eigen::MatrixXd all(3 * static_cast<Eigen::Index>(blocks.size()), cal::kHexapodParameters);
  for (std::size_t b = 0; b < blocks.size(); ++b)
    all.middleRows(3 * static_cast<Eigen::Index>(b), 3) = blocks[b];
  const Eigen::RowVectorXd scale = all.colwise().norm().cwiseMax(1e-300);
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(all * scale.cwiseInverse().asDiagonal(),
                                              Eigen::ComputeThinV);
  const Eigen::VectorXd& s = svd.singularValues();
  int rank = 0;
  while (rank < s.size() && s[rank] > kIdentifiableRatio * s[0]) ++rank;
  const Eigen::MatrixXd project = scale.cwiseInverse().asDiagonal() * svd.matrixV().leftCols(rank);
  for (Eigen::MatrixXd& b : blocks) b = b * project;
  return rank;
}

/// Orders the stations as a nearest-neighbour tour in x, y from the reference, so that the
/// machine travels less between them.
void orderByNearest(std::vector<Eigen::Vector3d>& stations) {
  Eigen::Vector2d at = Eigen::Vector2d::Zero();
  for (std::size_t i = 0; i < stations.size(); ++i) {
    std::size_t best = i;
    for (std::size_t j = i + 1; j < stations.size(); ++j)
      if ((stations[j].head<2>() - at).norm() < (stations[best].head<2>() - at).norm()) best = j;
    std::swap(stations[i], stations[best]);
    at = stations[i].head<2>();
  }
}

}  // namespace

void GaugeStationOptions::validate() const {
  if (count < 1) throw InvalidArgument("stations: the count must be >= 1");
  if (holdout < 0) throw InvalidArgument("stations: the held-out count must be >= 0");
  if (!(reach > 0.0) || !std::isfinite(reach)) throw InvalidArgument("stations: reach must be > 0");
  if (!(c_range_deg >= 0.0) || !std::isfinite(c_range_deg))
    throw InvalidArgument("stations: the c range must be >= 0");
  if (grid < 3 || grid % 2 == 0) throw InvalidArgument("stations: the grid must be odd and >= 3");
}

GaugeStationPlan planGaugeStations(const io::HexapodMachine& machine,
                                   const simulation::DialGaugeSetup& setup,
                                   const GaugeStationOptions& o) {
  o.validate();
  setup.validate();
  const kin::HexapodModel& model = machine.model;
  kin::HexapodData data(model);
  const Eigen::Vector3d lift = setup.approach * Eigen::Vector3d::UnitZ();
  auto below = [&](Eigen::VectorXd c) {
    c.head<3>() -= lift;
    return c;
  };
  if (!reachable(model, data, o, setup.reference) ||
      !reachable(model, data, o, below(setup.reference)))
    throw InvalidArgument("the reference pose fails the machine's checks or axis limits");
  const int sign = approachSign(model, data, below(setup.reference), setup.reference);
  if (setup.approach > 0.0 && sign == 0)
    throw InvalidArgument(
        "at the reference, an approach along z moves the struts in different directions: "
        "backlash could not be taken up the same way at every station");
  cal::ConstrainedMotionData set;
  set.gauge_points = setup.gauge_points;
  set.table_normal = setup.table_normal.normalized();
  const auto J_ref = heightJacobian(model, data, set, setup.reference);
  if (!J_ref) throw InvalidArgument("the reference pose: forward kinematics does not converge");
  GaugeStationPlan plan;
  std::vector<Eigen::Vector3d> moves;
  std::vector<Eigen::MatrixXd> blocks;
  const double c_range = degToRad(o.c_range_deg);
  for (int i = 0; i < o.grid; ++i)
    for (int j = 0; j < o.grid; ++j)
      for (int k = 0; k < kCSteps; ++k) {
        const Eigen::Vector3d move(o.reach * (2.0 * i / (o.grid - 1) - 1.0),
                                   o.reach * (2.0 * j / (o.grid - 1) - 1.0),
                                   c_range * (2.0 * k / (kCSteps - 1) - 1.0));
        if (move.squaredNorm() == 0.0) continue;  // the reference itself
        ++plan.tried;
        const Eigen::VectorXd c = commandOf(setup, move);
        if (!reachable(model, data, o, c) || !reachable(model, data, o, below(c)) ||
            (setup.approach > 0.0 && approachSign(model, data, below(c), c) != sign))
          continue;
        const auto J = heightJacobian(model, data, set, c);
        if (!J) continue;
        moves.push_back(move);
        blocks.emplace_back(*J - *J_ref);
      }
  plan.candidates = static_cast<int>(moves.size());
  if (plan.candidates < o.count + o.holdout)
    throw InvalidArgument(fmt::format(
        "only {} of {} planar moves within {} of the reference pass the machine's checks; "
        "{} stations and {} held out need more (a smaller --reach, fewer stations)",
        plan.candidates,
        plan.tried,
        o.reach,
        o.count,
        o.holdout));
  plan.identifiable = projectOnIdentifiable(blocks);
  const cal::PosePlan chosen = cal::planFromJacobians(blocks, o.count, o.index, 2);
  plan.index_value = chosen.index_value;
  plan.random_baseline = chosen.random_baseline;
  std::vector<bool> used(moves.size(), false);
  for (const int c : chosen.chosen) {
    plan.fit.push_back(moves[static_cast<std::size_t>(c)]);
    used[static_cast<std::size_t>(c)] = true;
  }
  orderByNearest(plan.fit);
  std::vector<Eigen::Vector3d> rest;
  for (std::size_t m = 0; m < moves.size(); ++m)
    if (!used[m]) rest.push_back(moves[m]);
  for (int h = 0; h < o.holdout; ++h)  // spread evenly over the rest, in grid order
    plan.holdout.push_back(
        rest[static_cast<std::size_t>((2 * h + 1) * rest.size() / (2 * o.holdout))]);
  return plan;
}

}  // namespace pkm::live
