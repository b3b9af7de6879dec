#include "pkm/cnc/exechon_program_compensation.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/kinematics/exechon_wrist.hpp"

namespace pkm::cnc {
namespace {
namespace kin = kinematics;

/// sin A below which the tool counts as vertical (C undefined): as the wrist pole.
constexpr double kVerticalTool = kin::kExechonWristPoleTolerance;

/// x + 360°·k nearest `near`.
double nearestTurnDeg(double x, double near) {
  if (std::abs(near - x) < 180.0) return x;
  return x + 360.0 * std::round((near - x) / 360.0);
}

}  // namespace

std::array<double, 2> toolAnglesFromDirection(const Eigen::Vector3d& direction,
                                              double a_near,
                                              double c_near) {
  const double norm = direction.norm();
  PKM_CHECK(direction.allFinite() && norm > 0.0, "the tool direction must be finite and non-zero");
  PKM_CHECK(std::isfinite(a_near) && std::isfinite(c_near), "the nearest A, C must be finite");
  const Eigen::Vector3d k = direction / norm;
  // k = (−sin C·sin A, cos C·sin A, −cos A).
  const double rho = std::hypot(k.x(), k.y());
  const double a = radToDeg(std::atan2(rho, -k.z()));  // in [0, 180]
  if (rho <= kVerticalTool) {
    double best = nearestTurnDeg(a, a_near);
    if (k.z() > 0.0) {  // A = ±180°: the nearer
      const double other = nearestTurnDeg(-a, a_near);
      if (std::abs(other - a_near) < std::abs(best - a_near)) best = other;
    }
    return {best, c_near};
  }
  const double c = radToDeg(std::atan2(-k.x(), k.y()));
  std::array<double, 2> out{};
  double best = INFINITY;
  for (int s = 0; s < 2; ++s) {
    const double aa = nearestTurnDeg(s == 0 ? a : -a, a_near);
    const double cc = nearestTurnDeg(s == 0 ? c : c + 180.0, c_near);
    const double d = std::abs(aa - a_near) + std::abs(cc - c_near);
    if (d < best) {
      best = d;
      out = {aa, cc};
    }
  }
  return out;
}

ProgramCompensation compensateExechonProgram(std::string_view text,
                                             const std::string& file,
                                             const kin::ExechonModel& nominal,
                                             const kin::ExechonModel& calibrated,
                                             const ExechonProgramCompensationOptions& options) {
  nominal.validate();
  calibrated.validate();
  PKM_CHECK(nominal.unit == calibrated.unit,
            "the nominal and calibrated Exechon machines use different length units");
  const auto fail = [&](std::size_t line, const std::string& what) {
    throw IoError(fmt::format("{}:{}: {}", file, line, what));
  };
  const PointMap map = [&](const std::vector<PathPoint>& points) {
    ExechonJointConverter real(calibrated, options.orientation);
    kin::ExechonData data(nominal);
    kin::ExechonConfiguration seed = nominal.home;
    const double mm = millimetresPer(nominal.unit);
    std::vector<Axes> commands(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Axes& x = points[i].pos;
      if (x[4] != 0.0)
        fail(points[i].line, fmt::format("B{} programmed, but an Exechon has no B axis", x[4]));
      const ExechonPathSample s = real.solve(x);
      if (!s.ok())
        fail(points[i].line,
             fmt::format("the calibrated machine cannot reach this point ({})",
                         kin::toString(s.status)));
      const kin::ExechonJoints joints{s.readings, s.config.c, s.config.a};
      const kin::FkSummary fk = kin::toolForwardKinematics(nominal, data, joints, seed, options.fk);
      if (!fk.ok())
        fail(points[i].line,
             fmt::format("the nominal forward kinematics failed for this motion ({})",
                         kin::toString(fk.status)));
      seed = kin::configurationOf(data);
      const Eigen::Vector3d p = data.world_p_tool * mm;
      std::array<double, 2> ac{};
      if (options.orientation == ExechonOrientation::kWristAxes)
        ac = {radToDeg(joints.a), radToDeg(joints.c)};
      else
        ac = toolAnglesFromDirection(data.world_u_tool, x[3], x[5]);
      commands[i] = {p.x(), p.y(), p.z(), ac[0], 0.0, ac[1]};
    }
    return commands;
  };
  // An Exechon has no B axis: its motions carry X Y Z A C.
  return rewriteProgram(text,
                        file,
                        map,
                        options.interpolation,
                        AxisMask{true, true, true, true, false, true},
                        options.interpreter);
}

}  // namespace pkm::cnc
