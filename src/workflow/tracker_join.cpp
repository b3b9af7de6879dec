// `pkm tracker join` as a workflow (workflow/tracker_join.hpp): a plan and a tracker's point
// export joined into a tracker point file.
#include "pkm/workflow/tracker_join.hpp"

#include <fmt/format.h>

#include <array>
#include <cctype>
#include <map>

#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/io/atomic_file.hpp"
#include "pkm/io/export_columns.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/io/spatial_analyzer.hpp"
#include "pkm/io/text_table.hpp"
#include "pkm/io/tracker_files.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"

namespace pkm::workflow {
namespace {

/// The planned poses by pose number, in plan order.
struct Plan {
  std::vector<long long> number;
  std::vector<kinematics::PoseRpy> pose;
  std::vector<std::size_t> line;
};

Plan readPlan(const io::NamedText& plan) {
  const io::TextTable t = io::TextTable::parseData(plan.text, plan.name);
  const std::size_t cp = t.column({"pose"});
  constexpr std::array<std::string_view, 6> kAxes{"x", "y", "z", "a", "b", "c"};
  std::array<std::size_t, 6> c{};
  for (std::size_t k = 0; k < 6; ++k) c[k] = t.column({kAxes[k]});
  Plan p;
  for (std::size_t r = 0; r < t.rows(); ++r) {
    kinematics::PoseRpy pose;
    for (int k = 0; k < 3; ++k) {
      pose.position[k] = t.number(r, c[static_cast<std::size_t>(k)]);
      pose.rpy[k] = degToRad(t.number(r, c[static_cast<std::size_t>(k) + 3]));
    }
    p.number.push_back(t.integer(r, cp));
    p.pose.push_back(pose);
    p.line.push_back(t.line(r));
  }
  if (p.pose.empty()) throw IoError(fmt::format("{}: no poses", plan.name));
  return p;
}

/// The pose number a target name ends with (P7, pose_007, 7); nullopt when it ends otherwise.
std::optional<long long> poseNumber(const std::string& name) {
  std::size_t start = name.size();
  while (start > 0 && std::isdigit(static_cast<unsigned char>(name[start - 1]))) --start;
  if (start == name.size() || name.size() - start > 9) return std::nullopt;
  return std::stoll(name.substr(start));
}

/// For each plan row, the index of its point in `points` (or none).
std::vector<std::optional<std::size_t>> matchPoints(
    const Plan& plan,
    const std::vector<io::SpatialAnalyzerPoint>& points,
    const std::string& name,
    const std::string& plan_name) {
  std::vector<std::optional<std::size_t>> match(plan.pose.size());
  if (points.front().target.empty()) {  // no names: one point per pose, in order
    if (points.size() != plan.pose.size())
      throw IoError(
          fmt::format("{}: {} unnamed points for {} planned poses: export the target "
                      "names (Target X Y Z) or one point per pose, in plan order",
                      name,
                      points.size(),
                      plan.pose.size()));
    for (std::size_t i = 0; i < match.size(); ++i) match[i] = i;
    return match;
  }
  std::map<long long, std::size_t> row_of;
  for (std::size_t i = 0; i < plan.number.size(); ++i) row_of[plan.number[i]] = i;
  for (std::size_t j = 0; j < points.size(); ++j) {
    const io::SpatialAnalyzerPoint& p = points[j];
    auto fail = [&](const std::string& what) { throw IoError(locate(name, p.line, what)); };
    const std::optional<long long> n = poseNumber(p.target);
    if (!n)
      fail(fmt::format("target '{}' does not end with a pose number (P7, pose_007)", p.target));
    const auto it = row_of.find(*n);
    if (it == row_of.end()) fail(fmt::format("pose {} is not in {}", *n, plan_name));
    if (match[it->second])
      fail(fmt::format(
          "a second point for pose {} (first at line {})", *n, points[*match[it->second]].line));
    match[it->second] = j;
  }
  return match;
}

/// The joined file's metadata lines.
io::Metadata joinedMetadata(const TrackerJoinRequest& request,
                            const io::HexapodMachine& machine,
                            std::size_t rows) {
  const std::string machine_unit(toString(machine.model.unit));
  io::Metadata meta{
      {"format", "pkm.tracker-point/1"},
      {"measurement", "tracker-point"},
      {"instrument", fmt::format("laser tracker (SpatialAnalyzer export {})", request.points.name)},
      {"mode", "point"},
      {"frame",
       request.frame == "tracker" ? "tracker (x, y, z in the export's working frame; its placement "
                                    "on the machine is fitted)"
                                  : "world (the export's working frame is the machine's)"},
      {"machine", machine.model.name},
      {"plan", request.plan.name}};
  if (request.smr_offset)
    meta.emplace_back("smr offset mm",
                      fmt::format("({}, {}, {})",
                                  (*request.smr_offset)[0],
                                  (*request.smr_offset)[1],
                                  (*request.smr_offset)[2]));
  meta.emplace_back("poses", std::to_string(rows));
  meta.emplace_back("columns",
                    fmt::format("l0..l5 commanded strut readings (nominal IK of the planned pose), "
                                "x,y,z measured point; {}",
                                machine_unit));
  return meta;
}

}  // namespace

void TrackerJoinRequest::validate() const {
  PKM_CHECK(
      frame == "tracker" || frame == "world", "--frame '{}': expected tracker or world", frame);
  PKM_CHECK(unit.empty() || io::millimetresPer(unit).has_value(),
            "--unit '{}': expected mm, um, m or in",
            unit);
  if (io::machineTypeOf(machine) == "exechon")
    throw InvalidArgument(fmt::format(
        "{} is an Exechon: join its tracker points with its leg and wrist readings by hand "
        "(docs/formats.md, \"Exechon tracker files\"); tracker join is for hexapods",
        machine));
  if (!out.empty()) io::checkOverwrite(out, force ? io::Overwrite::kAllow : io::Overwrite::kRefuse);
}

TrackerJoinResult joinTrackerPoints(const TrackerJoinRequest& request) {
  request.validate();
  io::HalReadOptions hal;
  if (!request.ini.empty()) hal.ini_path = request.ini;
  const io::HexapodMachine machine = io::loadHexapodMachine(request.machine, hal);
  const Plan plan = readPlan(request.plan);
  const std::vector<io::SpatialAnalyzerPoint> points =
      io::parseSpatialAnalyzerPoints(request.points);
  const std::vector<std::optional<std::size_t>> match =
      matchPoints(plan, points, request.points.name, request.plan.name);
  const std::string machine_unit(toString(machine.model.unit));
  const double scale = request.unit.empty()
                           ? 1.0
                           : *io::millimetresPer(request.unit) / millimetresPer(machine.model.unit);
  TrackerJoinResult result;
  result.notes.push_back(
      fmt::format("{}: points read in {}{}",
                  request.points.name,
                  request.unit.empty() ? machine_unit : request.unit,
                  request.unit.empty() ? " (the machine's unit; --unit to change)" : ""));
  std::vector<simulation::TrackerReading> readings;
  kinematics::HexapodData data(machine.model);
  for (std::size_t i = 0; i < match.size(); ++i) {
    if (!match[i]) {
      result.notes.push_back(fmt::format("pose {} ({}:{}): no point in {}; left out",
                                         plan.number[i],
                                         request.plan.name,
                                         plan.line[i],
                                         request.points.name));
      continue;
    }
    simulation::TrackerReading r;
    r.lengths = kinematics::inverseKinematics(machine.model, data, plan.pose[i]);
    r.measured.setIdentity();
    r.measured.translation() = points[*match[i]].position * scale;
    readings.push_back(r);
  }
  if (readings.empty())
    throw IoError(
        fmt::format("{}: no point matches a pose of {}", request.points.name, request.plan.name));
  const io::Metadata meta = joinedMetadata(request, machine, readings.size());
  result.text = io::trackerCsv(meta, simulation::TrackerMode::kPoint, readings);
  result.rows = readings.size();
  if (!request.out.empty()) io::writeFileAtomic(request.out, result.text, io::Overwrite::kAllow);
  return result;
}

}  // namespace pkm::workflow
