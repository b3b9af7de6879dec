// The documents of a calibration pose plan (pose_plan_report.hpp).
#include "pkm/io/pose_plan_report.hpp"

#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "pkm/io/number_format.hpp"

namespace pkm::io {
namespace {

namespace cal = pkm::calibration;
using Json = nlohmann::ordered_json;

bool isExechon(const PosePlanReport& r) { return r.kind == "exechon"; }

std::string hexapodMove(const kinematics::PoseRpy& p) {
  return fmt::format("X{:.4f} Y{:.4f} Z{:.4f} A{:.4f} B{:.4f} C{:.4f}",
                     p.position.x(),
                     p.position.y(),
                     p.position.z(),
                     radToDeg(p.rpy.x()),
                     radToDeg(p.rpy.y()),
                     radToDeg(p.rpy.z()));
}

std::string exechonMove(const ExechonPlanMove& m) {
  // Rounded to the 4 decimals written, + 0.0: no "-0.0000".
  const auto w = [](double v) { return std::round(v * 1e4) / 1e4 + 0.0; };
  return fmt::format("X{:.4f} Y{:.4f} Z{:.4f} A{:.4f} C{:.4f}",
                     w(m.tool_point.x()),
                     w(m.tool_point.y()),
                     w(m.tool_point.z()),
                     w(radToDeg(m.a)),
                     w(radToDeg(m.c)));
}

std::string hexapodGcode(const PosePlanReport& r) {
  std::string g =
      fmt::format("(pkm plan-poses: {} calibration poses for {} by {}; measure at every M0)\n",
                  r.poses.size(),
                  r.machine,
                  cal::toString(r.index));
  g += fmt::format("{} G90 (absolute)\n", r.unit == LengthUnit::kInch ? "G20" : "G21");
  g += fmt::format("G1 {} F{:.1f} (home)\n", hexapodMove(r.home), r.feed);
  for (std::size_t k = 0; k < r.poses.size(); ++k) {
    g += fmt::format("N{} G1 {}\n", (k + 1) * 10, hexapodMove(r.poses[k]));
    g += fmt::format("M0 (measure pose {})\n", k);
  }
  g += fmt::format("G1 {}\nM2\n", hexapodMove(r.home));
  return g;
}

std::string exechonGcode(const PosePlanReport& r) {
  // A, C are the wrist readings of the planned configuration (`gcode run --orientation axes`):
  // between two points the readings move linearly, so the wrist never swings through the pole.
  std::string g = fmt::format(
      "(pkm plan-poses: {} tracker points for {} by {}; measure at every M0)\n"
      "(A, C are the wrist readings: run with --orientation axes)\n",
      r.points.size(),
      r.machine,
      cal::toString(r.index));
  g += fmt::format("{} G90 (absolute)\n", r.unit == LengthUnit::kInch ? "G20" : "G21");
  if (r.moves.empty()) return g + "M2\n";
  g += fmt::format("G1 {} F{:.1f} (home)\n", exechonMove(r.moves.front()), r.feed);
  for (std::size_t k = 1; k < r.moves.size(); ++k) {
    g += fmt::format("N{} G1 {}\n", k * 10, exechonMove(r.moves[k]));
    g += fmt::format("M0 (measure point {})\n", k - 1);
  }
  g += fmt::format("G1 {}\nM2\n", exechonMove(r.moves.front()));
  return g;
}

Json vectorJson(const Eigen::Vector3d& v) { return Json::array({v.x(), v.y(), v.z()}); }

}  // namespace

std::string posePlanCsv(const PosePlanReport& r) {
  std::string t = isExechon(r) ? "pose,x,y,z,i,j,k\n" : "pose,x,y,z,a,b,c\n";
  const std::size_t n = isExechon(r) ? r.points.size() : r.poses.size();
  for (std::size_t k = 0; k < n; ++k) {
    t += fmt::format("{}", k);
    Eigen::Vector3d a, b;
    if (isExechon(r)) {
      a = r.points[k].position;
      b = r.points[k].direction;
    } else {
      a = r.poses[k].position;
      const Eigen::Vector3d& rpy = r.poses[k].rpy;
      b = {radToDeg(rpy.x()), radToDeg(rpy.y()), radToDeg(rpy.z())};
    }
    for (const Eigen::Vector3d* v : {&a, &b})
      for (int i = 0; i < 3; ++i) {
        t += ',';
        appendNumber(t, (*v)(i));
      }
    t += '\n';
  }
  return t;
}

std::string posePlanSummary(const PosePlanReport& r) {
  const cal::PosePlan& p = r.plan;
  if (isExechon(r))
    return fmt::format(
        "{} tracker points of {} candidates by {}: {} = {:.6g} (random choice {:.6g}), condition "
        "number {:.4g}, rank {} of {}, {} exchanges",
        p.chosen.size(),
        r.candidates,
        r.index_label,
        cal::toString(r.index),
        p.index_value,
        p.random_baseline,
        p.condition_number,
        p.rank,
        r.parameters,
        p.swaps);
  return fmt::format(
      "{} poses of {} candidates by {}: {} = {:.6g} (random choice {:.6g}), condition number "
      "{:.4g}, rank {}, {} exchanges",
      p.chosen.size(),
      r.candidates,
      r.index_label,
      cal::toString(r.index),
      p.index_value,
      p.random_baseline,
      p.condition_number,
      p.rank,
      p.swaps);
}

std::string posePlanGcode(const PosePlanReport& r) {
  return isExechon(r) ? exechonGcode(r) : hexapodGcode(r);
}

std::string posePlanJson(const PosePlanReport& r) {
  const cal::PosePlan& p = r.plan;
  Json j{{"kind", r.kind},
         {"machine", r.machine},
         {"unit", std::string(toString(r.unit))},
         {"index", cal::toString(r.index)},
         {"index_value", p.index_value},
         {"random_baseline", p.random_baseline},
         {"indices", p.indices},
         {"condition_number", p.condition_number},
         {"rank", p.rank},
         {"parameters", r.parameters},
         {"exchanges", p.swaps},
         {"candidates", r.candidates},
         {"chosen", p.chosen}};
  Json poses = Json::array();
  if (isExechon(r)) {
    for (const kinematics::ExechonToolPose& t : r.points)
      poses.push_back(
          {{"position", vectorJson(t.position)}, {"direction", vectorJson(t.direction)}});
  } else {
    for (const kinematics::PoseRpy& t : r.poses)
      poses.push_back(
          {{"position", vectorJson(t.position)},
           {"rpy_deg",
            vectorJson({radToDeg(t.rpy.x()), radToDeg(t.rpy.y()), radToDeg(t.rpy.z())})}});
  }
  j["poses"] = std::move(poses);
  return j.dump(2) + "\n";
}

}  // namespace pkm::io
