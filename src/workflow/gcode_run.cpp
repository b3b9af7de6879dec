// `pkm gcode run` as a workflow (workflow/gcode_run.hpp).
#include "pkm/workflow/gcode_run.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>

#include "gcode_run_detail.hpp"
#include "pkm/cnc/interpreter.hpp"
#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/io/atomic_file.hpp"
#include "pkm/io/machine_loader.hpp"

namespace pkm::workflow {

namespace {

/// Angles (joint_angle) are reported in degrees, everything else in its own unit.
double shown(cnc::PathCheck c, double v) {
  return c == cnc::PathCheck::kJointAngle ? radToDeg(v) : v;
}

/// The unit of a check's values. An Exechon's rates are in the length unit for legs and in
/// degrees for the wrist: with `item` the unit of that joint, without it both.
std::string unitOf(cnc::PathCheck c,
                   const std::string& len,
                   bool exechon = false,
                   std::string_view item = {}) {
  const bool wrist = item.substr(0, 5) == "wrist";
  const std::string rate = exechon && item.empty() ? fmt::format("{}/s (legs), deg/s (wrist)", len)
                           : wrist                 ? std::string("deg/s")
                                                   : fmt::format("{}/s", len);
  switch (c) {
    case cnc::PathCheck::kJointAngle:
      return "deg";
    case cnc::PathCheck::kSingular:
    case cnc::PathCheck::kReach:
      return "";
    case cnc::PathCheck::kJointVelocity:
      return rate;
    case cnc::PathCheck::kJointAcceleration:
      return exechon && item.empty() ? fmt::format("{}/s^2 (legs), deg/s^2 (wrist)", len)
                                     : rate + "^2";
    default:
      return len;
  }
}

io::GcodeCheckEvent eventOf(cnc::PathCheck c, const cnc::CheckEvent& e, const detail::JointRun& r) {
  io::GcodeCheckEvent out;
  out.line = e.line;
  out.position = e.pos;
  out.item = e.item;
  out.value = shown(c, e.value);
  out.limit = shown(c, e.limit);
  out.margin = shown(c, e.margin);
  out.unit = unitOf(c, r.len, r.exechon, e.item);
  return out;
}

void refuseOverwrite(const std::string& path, bool force) {
  if (!path.empty())
    io::checkOverwrite(path, force ? io::Overwrite::kAllow : io::Overwrite::kRefuse);
}

/// The interpreter stopped at a tool its table lacks (cnc::Interpreter::missingTool).
class MissingTool : public IoError {
 public:
  using IoError::IoError;
};

/// The program's motions and dwells. Throws pkm::IoError "NAME:LINE: message" for a program the
/// interpreter rejects, pkm::InvalidArgument for one without motion.
cnc::MoveCollector interpret(const GcodeRunRequest& request,
                             const io::HexapodMachine* machine,
                             const detail::GcodeProgress& progress,
                             std::size_t& lines,
                             cnc::ToolTable& tools) {
  GcodeInterpreterSettings settings = request.interpreter;
  if (machine != nullptr) takeStartupCode(*machine, settings);
  if (settings.ini.empty()) settings.ini = request.ini;  // the machine's INI sets up rs274 too
  cnc::InterpreterOptions options = settings.options();
  // Each motion makes at least one interpolated point: more motions than the point budget are
  // refused while interpreting, before their memory is spent.
  options.max_moves = request.max_points;
  tools = options.tools;
  cnc::Interpreter interpreter(std::move(options));
  const cnc::Program program = cnc::Program::parse(request.program.text, request.program.name);
  lines = program.lineCount();
  cnc::MoveCollector moves;
  progress.report("interpreting", "motions", 1, detail::kRunStages, 0, 0);
  detail::ProgressMoveSink watched(moves, progress, 1, detail::kRunStages, request.program.name);
  try {
    (void)interpreter.run(program, watched);
  } catch (const IoError& e) {
    if (interpreter.missingTool()) throw MissingTool(e.what());
    throw;
  }
  if (moves.moves.empty())
    throw InvalidArgument(fmt::format("{}: no motion", request.program.name));
  return moves;
}

/// interpret(), and for a program that names a tool no table was given for: again with the
/// `tools.tbl` beside the program file, when there is one (examples run as shipped), with a note.
cnc::MoveCollector interpretWithTools(const GcodeRunRequest& request,
                                      const io::HexapodMachine* machine,
                                      const detail::GcodeProgress& progress,
                                      std::size_t& lines,
                                      cnc::ToolTable& tools,
                                      const RunControl& control) {
  const GcodeInterpreterSettings& given = request.interpreter;
  const std::filesystem::path beside =
      std::filesystem::path(request.program.name).parent_path() / "tools.tbl";
  const bool may_look =
      given.tool_table.empty() && given.tool_table_text.empty() && given.search_working_folder;
  try {
    return interpret(request, machine, progress, lines, tools);
  } catch (const MissingTool&) {
    std::error_code ec;
    if (!may_look || !std::filesystem::is_regular_file(beside, ec)) throw;
  }
  GcodeRunRequest with_tools = request;
  with_tools.interpreter.tool_table = beside.string();
  control.note({fmt::format("{}: the program names a tool and no --tool-table was given: using {}",
                            request.program.name,
                            beside.string())});
  return interpret(with_tools, machine, progress, lines, tools);
}

}  // namespace

namespace detail {

io::GcodeRunReport runReport(const GcodeRunRequest& request,
                             std::size_t lines,
                             std::size_t motions,
                             const JointRun& run) {
  io::GcodeRunReport r;
  r.program = request.program.name;
  r.machine = run.machine_name;
  r.machine_type = run.exechon ? "exechon" : "hexapod";
  r.units = run.len;
  r.orientation = request.orientation;
  r.lines = lines;
  r.motions = motions;
  r.points = run.points.size();
  r.tolerance_mm = run.tolerance_mm;
  r.max_step_mm = run.interpolation.max_step;
  r.max_angle_step_deg = run.interpolation.max_angle_step;
  r.max_joint_velocity = run.limits.max_joint_velocity;
  r.max_joint_acceleration = run.limits.max_joint_acceleration;
  r.max_wrist_velocity_deg_per_s = run.wrist_velocity;
  r.max_wrist_acceleration_deg_per_s2 = run.wrist_acceleration;
  r.rapid_rate_mm_per_min = run.limits.rapid_rate;
  r.limits_from_machine_file = run.from_file;
  r.rapid_limits = run.rapid_limits;
  r.cycle_time_s = run.time.total;
  r.dwell_time_s = run.time.dwell;
  r.ok = run.report.ok();
  for (std::size_t k = 0; k < cnc::kPathChecks; ++k) {
    const auto c = static_cast<cnc::PathCheck>(k);
    const cnc::CheckStat& st = run.report.stats[k];
    r.checks.push_back({std::string(cnc::toString(c)),
                        st.enabled,
                        st.violations,
                        unitOf(c, run.len, run.exechon),
                        eventOf(c, st.worst, run),
                        eventOf(c, st.first, run),
                        st.enabled ? std::string() : run.off_reason[k]});
  }
  return r;
}

}  // namespace detail

void GcodeRunRequest::validate() const {
  cnc::MotionLimits limits;
  limits.max_joint_velocity = max_joint_velocity.value_or(200.0);
  limits.max_joint_acceleration = max_joint_acceleration.value_or(2000.0);
  limits.rapid_rate = rapid_rate.value_or(detail::kDefaultRapidRate);
  limits.validate();
  PKM_CHECK(!tolerance || (*tolerance > 0.0 && std::isfinite(*tolerance)),
            "--tolerance must be > 0");
  PKM_CHECK(max_points > 0, "--max-points must be > 0");
  refuseOverwrite(out, force);
  refuseOverwrite(report, force);
  if (hexapod && exechon)
    throw InvalidArgument("give one loaded machine, not a hexapod and an Exechon");
  const bool on_exechon = onExechon();
  if (!on_exechon && orientation != "vector")
    throw InvalidArgument("--orientation applies to Exechon machines only");
  if (on_exechon && (strut_diameter || !ini.empty()))
    throw InvalidArgument("--strut-diameter and --ini apply to hexapods only");
  PKM_CHECK(!strut_diameter || (*strut_diameter > 0.0 && std::isfinite(*strut_diameter)),
            "--strut-diameter must be > 0");
  interpreter.validate();
  if (machining) machining->validate();
}

bool GcodeRunRequest::onExechon() const {
  if (hexapod || exechon) return exechon != nullptr;
  return io::machineTypeOf(machine) == "exechon";
}

GcodeRunResult runGcode(const GcodeRunRequest& request, const RunControl& control) {
  request.validate();
  const bool exechon = request.onExechon();
  const detail::GcodeProgress progress(control);
  std::optional<io::HexapodMachine> hexapod;
  if (!exechon && request.hexapod) {
    hexapod = *request.hexapod;
  } else if (!exechon) {
    io::HalReadOptions hal;
    if (!request.ini.empty()) hal.ini_path = request.ini;
    hexapod = io::loadHexapodMachine(request.machine, hal);
    control.note(hexapod->notices);
  }
  if (hexapod) {
    if (!hexapod->startup_code.empty())
      control.note({fmt::format("{}: RS274NGC_STARTUP_CODE \"{}\" runs before the program",
                                hexapod->startup_code_source,
                                hexapod->startup_code)});
  }
  std::size_t lines = 0;
  cnc::ToolTable tools;
  const cnc::MoveCollector moves =
      interpretWithTools(request, hexapod ? &*hexapod : nullptr, progress, lines, tools, control);
  detail::JointRun run;
  if (exechon)
    detail::runExechon(request, moves, control, progress, run);
  else
    detail::runHexapod(request, *hexapod, moves, progress, run);
  GcodeRunResult result;
  result.report = detail::runReport(request, lines, moves.moves.size(), run);
  result.path = detail::runPath(run, request.path_points);
  detail::runFrames(run, request.frames, result);
  if (request.machining) {
    control.checkCancelled();
    result.machining =
        detail::runMachining(*request.machining, run, moves, tools, result.path.index, control);
  }
  for (std::size_t k = 0; k < cnc::kPathChecks; ++k) {
    const auto c = static_cast<cnc::PathCheck>(k);
    for (const cnc::CheckEvent& e : run.report.stats[k].events)
      result.violations.push_back({std::string(cnc::toString(c)), eventOf(c, e, run)});
  }
  if (!request.out.empty()) detail::writeJointCsv(request.out, run);
  if (!request.report.empty())
    io::writeFileAtomic(request.report, io::gcodeRunJson(result.report), io::Overwrite::kAllow);
  return result;
}

}  // namespace pkm::workflow
