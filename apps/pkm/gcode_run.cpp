// `pkm gcode run --machine M PROGRAM`: interpolate a G-code program, convert it to strut
// readings of a hexapod, time it and check every limit (docs/gcode.md "gcode run").
#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli_common.hpp"
#include "pkm/cnc/cycle_time.hpp"
#include "pkm/cnc/interpreter.hpp"
#include "pkm/cnc/joint_checks.hpp"
#include "pkm/cnc/joint_path.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/io/number_format.hpp"

namespace pkm::cli {
namespace {

struct RunArgs {
  std::string program;
  std::string machine = "default";
  double tolerance = 0.01;
  std::string out;
  std::string report;
  bool force = false;
  cnc::MotionLimits limits{200.0, 2000.0, 10000.0};
};

/// Exit code when a check is violated.
constexpr int kExitViolation = 1;

/// Rejects Exechon machines (not supported yet) with a clear message.
void rejectExechon(const std::string& spec) {
  std::string type = "hexapod";
  if (std::filesystem::is_regular_file(spec)) {
    type = io::machineType(io::readTextFile(spec));
  } else {
    for (const auto& n : io::builtinMachineNames("exechon"))
      if (n == spec) type = "exechon";
  }
  if (type != "hexapod")
    throw InvalidArgument(fmt::format(
        "{}: gcode run supports hexapod machines only ({} machines are not supported yet)",
        spec,
        type));
}

void refuseOverwrite(const std::string& path, bool force) {
  if (!path.empty() && !force && std::filesystem::exists(path))
    throw IoError(fmt::format("{} exists; pass --force to overwrite it", path));
}

/// Angles (joint_angle) are reported in degrees, everything else in its own unit.
double shown(cnc::PathCheck c, double v) {
  return c == cnc::PathCheck::kJointAngle ? radToDeg(v) : v;
}

nlohmann::ordered_json eventJson(cnc::PathCheck c, const cnc::CheckEvent& e) {
  nlohmann::ordered_json j;
  j["line"] = e.line;
  j["position"] = std::vector<double>(e.pos.begin(), e.pos.end());
  j["item"] = e.item;
  j["value"] = shown(c, e.value);
  j["limit"] = shown(c, e.limit);
  j["margin"] = shown(c, e.margin);
  return j;
}

std::string unitOf(cnc::PathCheck c, const std::string& len) {
  switch (c) {
    case cnc::PathCheck::kJointAngle:
      return "deg";
    case cnc::PathCheck::kSingular:
      return "";
    case cnc::PathCheck::kJointVelocity:
      return len + "/s";
    case cnc::PathCheck::kJointAcceleration:
      return len + "/s^2";
    default:
      return len;
  }
}

void runGcode(const RunArgs& a) {
  a.limits.validate();
  PKM_CHECK(a.tolerance > 0.0 && std::isfinite(a.tolerance), "--tolerance must be > 0");
  refuseOverwrite(a.out, a.force);
  refuseOverwrite(a.report, a.force);
  rejectExechon(a.machine);
  const io::HexapodMachine machine = io::loadHexapodMachine(a.machine);
  printNotices(machine.notices);
  const auto& model = machine.model;
  const cnc::Program program = cnc::Program::load(a.program);
  cnc::MoveCollector moves;
  cnc::Interpreter interpreter;
  (void)interpreter.run(program, moves);
  if (moves.moves.empty()) throw InvalidArgument(fmt::format("{}: no motion", a.program));
  // The first motion positions the machine at its end point (the interpreter's start-up
  // position 0 is not a machine position).
  const cnc::InterpolationOptions io = cnc::jointSpaceInterpolation(model, a.tolerance);
  cnc::PathInterpolator interp(io, moves.moves.front().end);
  std::vector<cnc::PathPoint> points;
  for (std::size_t m = 0; m < moves.moves.size(); ++m)
    interp.append(moves.moves[m], static_cast<std::uint32_t>(m), points);
  cnc::HexapodJointConverter conv(model);
  std::vector<kinematics::StrutVector> q;
  conv.solveAll(points, q);
  const cnc::CycleTime time = cnc::estimateCycleTime(points, q, a.limits);
  const cnc::PathCheckReport report = cnc::checkPath(model, points, q, a.limits);

  if (!a.out.empty()) {
    const std::string tmp = a.out + ".tmp";
    std::FILE* f = std::fopen(tmp.c_str(), "wb");
    if (f == nullptr) throw IoError(fmt::format("{}: cannot write", a.out));
    std::string buf = std::string(cnc::kJointCsvHeader) + "\n";
    for (std::size_t i = 0; i < points.size(); ++i) {
      cnc::appendJointCsv(buf, points[i], time.t[i], q[i]);
      if (buf.size() > (1u << 20)) {
        std::fwrite(buf.data(), 1, buf.size(), f);
        buf.clear();
      }
    }
    std::fwrite(buf.data(), 1, buf.size(), f);
    if (std::fclose(f) != 0) throw IoError(fmt::format("{}: write failed", a.out));
    std::filesystem::rename(tmp, a.out);
  }

  const std::string len(toString(model.unit));
  Output out;
  std::string& s = out.text();
  s += fmt::format("gcode run: {} on {} ({} lines, {} motions, {} points)\n",
                   a.program,
                   model.name,
                   program.lineCount(),
                   moves.moves.size(),
                   points.size());
  s += fmt::format(
      "interpolation: tolerance {} mm, max step {:.4g} mm, max rotary step {:.4g} deg\n",
      a.tolerance,
      io.max_step,
      io.max_angle_step);
  s +=
      fmt::format("limits: joint velocity {} {}/s, joint acceleration {} {}/s^2, rapid {} mm/min\n",
                  a.limits.max_joint_velocity,
                  len,
                  a.limits.max_joint_acceleration,
                  len,
                  a.limits.rapid_rate);
  s += fmt::format("cycle time: {:.3f} s\n", time.total);
  s += fmt::format("{:<19} {:<9} {:>10} {:>14} {:>7}  {}\n",
                   "check",
                   "status",
                   "violations",
                   "worst margin",
                   "line",
                   "item");
  nlohmann::ordered_json checks;
  for (std::size_t k = 0; k < cnc::kPathChecks; ++k) {
    const auto c = static_cast<cnc::PathCheck>(k);
    const cnc::CheckStat& st = report.stats[k];
    const std::string name(cnc::toString(c));
    const char* status = !st.enabled ? "n/a" : st.violations > 0 ? "VIOLATED" : "ok";
    if (st.enabled)
      s += fmt::format("{:<19} {:<9} {:>10} {:>14} {:>7}  {}\n",
                       name,
                       status,
                       st.violations,
                       fmt::format("{:.4g} {}", shown(c, st.worst.margin), unitOf(c, len)),
                       st.worst.line,
                       st.worst.item);
    else
      s += fmt::format("{:<19} {:<9}\n", name, status);
    nlohmann::ordered_json j;
    j["enabled"] = st.enabled;
    j["violations"] = st.violations;
    j["unit"] = unitOf(c, len);
    if (st.enabled) j["worst"] = eventJson(c, st.worst);
    if (st.violations > 0) j["first_violation"] = eventJson(c, st.first);
    checks[name] = j;
  }
  for (std::size_t k = 0; k < cnc::kPathChecks; ++k) {
    const auto c = static_cast<cnc::PathCheck>(k);
    const cnc::CheckStat& st = report.stats[k];
    if (st.violations == 0) continue;
    const auto& e = st.first;
    s += fmt::format(
        "{}:{}: {} violated first at X{} Y{} Z{} A{} B{} C{}: {} value {:.6g}, "
        "limit {:.6g}, margin {:.4g} {}\n",
        a.program,
        e.line,
        cnc::toString(c),
        io::formatNumber(e.pos[0]),
        io::formatNumber(e.pos[1]),
        io::formatNumber(e.pos[2]),
        io::formatNumber(e.pos[3]),
        io::formatNumber(e.pos[4]),
        io::formatNumber(e.pos[5]),
        e.item,
        shown(c, e.value),
        shown(c, e.limit),
        shown(c, e.margin),
        unitOf(c, len));
  }
  s += report.ok() ? "result: all checks pass\n" : "result: VIOLATIONS (exit code 1)\n";
  if (!a.report.empty()) {
    nlohmann::ordered_json j;
    j["program"] = a.program;
    j["machine"] = model.name;
    j["units"] = len;
    j["tolerance_mm"] = a.tolerance;
    j["max_step_mm"] = io.max_step;
    j["max_angle_step_deg"] = io.max_angle_step;
    j["max_joint_velocity"] = a.limits.max_joint_velocity;
    j["max_joint_acceleration"] = a.limits.max_joint_acceleration;
    j["rapid_rate_mm_per_min"] = a.limits.rapid_rate;
    j["motions"] = moves.moves.size();
    j["points"] = points.size();
    j["cycle_time_s"] = time.total;
    j["ok"] = report.ok();
    j["checks"] = checks;
    std::FILE* f = std::fopen(a.report.c_str(), "wb");
    if (f == nullptr) throw IoError(fmt::format("{}: cannot write", a.report));
    const std::string text = j.dump(2) + "\n";
    std::fwrite(text.data(), 1, text.size(), f);
    if (std::fclose(f) != 0) throw IoError(fmt::format("{}: write failed", a.report));
  }
  out.flush();
  if (!report.ok()) std::exit(kExitViolation);
}

}  // namespace

void addGcodeRunCommand(CLI::App& gcode) {
  auto a = std::make_shared<RunArgs>();
  CLI::App* r = gcode.add_subcommand(
      "run",
      "interpolate PROGRAM, convert it to strut readings of a hexapod, estimate the cycle time "
      "and check every limit (exit 1 on a violation)");
  r->add_option("program", a->program, "G-code file (.ngc)")->required();
  r->add_option("--machine", a->machine, "hexapod machine: JSON file or built-in name");
  r->add_option("--tolerance", a->tolerance, "chordal tolerance in mm (default 0.01)");
  r->add_option("--out", a->out, "write the joint CSV (line,t,x,y,z,a,b,c,q0..q5) to FILE");
  r->add_option("--report", a->report, "write the check report as JSON to FILE");
  r->add_flag("--force", a->force, "overwrite existing --out/--report files");
  r->add_option("--max-joint-velocity",
                a->limits.max_joint_velocity,
                "strut speed limit, machine length unit/s (default 200)");
  r->add_option("--max-joint-acceleration",
                a->limits.max_joint_acceleration,
                "strut acceleration limit, machine length unit/s^2 (default 2000)");
  r->add_option("--rapid-rate", a->limits.rapid_rate, "G0 path speed, mm/min (default 10000)");
  r->callback([a] { runGcode(*a); });
}

}  // namespace pkm::cli
