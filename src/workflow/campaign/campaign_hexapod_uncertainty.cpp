// The "hexapod-calibration" campaign step's uncertainty: the calibration budgets, the U of the
// TCP error rows and the report's budget table (campaign_hexapod_detail.hpp).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "campaign_hexapod_detail.hpp"
#include "pkm/kinematics/pose_rpy.hpp"
#include "workflow/calibration_uncertainty.hpp"

namespace pkm::workflow::campaign::detail {

namespace cal = pkm::calibration;
namespace sim = pkm::simulation;

const std::vector<Eigen::Vector3d>& fiducialNests() {
  static const std::vector<Eigen::Vector3d> nests = {
      {-500, -500, 0}, {500, -500, 0}, {500, 500, 0}, {-500, 500, 0}, {0, 0, 0}, {0, -700, 0}};
  return nests;
}

namespace {

/// The standard uncertainty (mm) of one tracker reading at range L (mm), per direction: the
/// rectangular a + b·L.
double readingU(const metrology::LaserTrackerSpec& t, double range_mm) {
  return (t.accuracy_mm + t.accuracy_mm_per_m * range_mm * 1e-3) / std::sqrt(3.0);
}

/// The largest standard uncertainty (mm) of a held-out TCP error reading: the target's reading
/// and the registration's displacement at the target (rigid fit on n nests).
double measurementU(const metrology::LaserTrackerSpec& t,
                    const sim::TrackerResult& holdout,
                    const geometry::RigidTransform& world_T_tracker) {
  const std::vector<Eigen::Vector3d>& nests = fiducialNests();
  const Eigen::Vector3d centroid =
      std::accumulate(nests.begin(), nests.end(), Eigen::Vector3d(Eigen::Vector3d::Zero())) /
      static_cast<double>(nests.size());
  double spread = 0.0, nest_u = 0.0;
  for (const Eigen::Vector3d& n : nests) {
    spread += (n - centroid).squaredNorm();
    nest_u = std::max(nest_u, readingU(t, (world_T_tracker.inverse() * n).norm()));
  }
  double worst = 0.0;
  for (const sim::TrackerReading& r : holdout.readings) {
    const Eigen::Vector3d tracker_p = r.measured.translation();
    const Eigen::Vector3d world_p = world_T_tracker * tracker_p;
    const double d2 = (world_p - centroid).squaredNorm();
    const double registration =
        nest_u * std::sqrt(1.0 / static_cast<double>(nests.size()) + d2 / spread);
    worst = std::max(worst, std::hypot(readingU(t, tracker_p.norm()), registration));
  }
  return worst;
}

}  // namespace

TcpRowUncertainty tcpRowUncertainty(const kinematics::HexapodModel& model,
                                    const cal::HexapodCalibrationData& data,
                                    const cal::HexapodCalibrationSummary& fit,
                                    const cal::HexapodCalibrationOptions& options,
                                    const sim::TrackerResult& holdout,
                                    const geometry::RigidTransform& world_T_tracker,
                                    const metrology::UncertaintySources& sources) {
  workflow::detail::CalibrationUncertaintyRequest request;
  request.sources = sources;
  // The fit's readings are in the machine frame after the registration: the tracker's a + b·L
  // takes the longest range of the held-out readings (the same set-up).
  request.sources.tracker.range_mm = 0.0;
  for (const sim::TrackerReading& r : holdout.readings)
    request.sources.tracker.range_mm =
        std::max(request.sources.tracker.range_mm, r.measured.translation().norm());
  std::vector<kinematics::PoseRpy> check;
  for (const sim::TrackerReading& r : holdout.readings) {
    kinematics::PoseRpy p;
    p.position = r.command.head<3>();
    p.rpy = r.command.tail<3>();
    check.push_back(p);
  }
  TcpRowUncertainty out;
  out.budget = workflow::detail::hexapodCalibrationUncertainty(
      model, data, fit, options, request, check, "held-out");
  const double k = request.sources.coverage_factor;
  out.measurement = k * measurementU(request.sources.tracker, holdout, world_T_tracker);
  out.predicted = out.budget.tcp.max;
  out.before_U = out.measurement;
  out.after_U = std::hypot(out.measurement, out.predicted);
  return out;
}

Json budgetTable(const io::HexapodCalibrationReport::Uncertainty& u) {
  const std::vector<metrology::UncertaintyBudget>& b = u.parameters.linear.budgets;
  Json t = table(
      fmt::format("Calibration uncertainty (k = 2): the least certain parameters and their largest "
                  "contributors; predicted TCP U at the {} {} poses: max {:.2g} mm",
                  u.tcp.poses,
                  u.tcp_poses,
                  u.tcp.max),
      {"parameter",
       "estimate (mm)",
       "U (mm)",
       "largest contributor",
       "share of u_c²",
       "second contributor",
       "share of u_c²"});
  std::vector<std::size_t> order(b.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) {
    return b[x].expandedUncertainty() > b[y].expandedUncertainty();
  });
  for (std::size_t i = 0; i < std::min<std::size_t>(8, order.size()); ++i) {
    const metrology::UncertaintyBudget& p = b[order[i]];
    std::vector<std::size_t> c(p.contributors.size());
    std::iota(c.begin(), c.end(), std::size_t{0});
    std::sort(c.begin(), c.end(), [&](std::size_t x, std::size_t y) {
      return p.contributors[x].contribution() > p.contributors[y].contribution();
    });
    const double var = std::pow(p.combinedStandardUncertainty(), 2);
    const auto name = [&](std::size_t j) { return j < c.size() ? p.contributors[c[j]].name : "-"; };
    const auto share = [&](std::size_t j) {
      return j < c.size() && var > 0.0
                 ? cell(std::pow(p.contributors[c[j]].contribution(), 2) / var, 2)
                 : Json();
    };
    t["rows"].push_back({p.quantity,
                         cell(p.value, 7),
                         cell(p.expandedUncertainty(), 2),
                         name(0),
                         share(0),
                         name(1),
                         share(1)});
  }
  return t;
}

}  // namespace pkm::workflow::campaign::detail
