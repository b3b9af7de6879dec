// `pkm gcode run --machine M PROGRAM`: interpolate a G-code program, convert it to the joints of a
// hexapod or an Exechon, time it and check every limit (docs/gcode.md "gcode run").
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>

#include "cli_common.hpp"
#include "gcode_options.hpp"
#include "pkm/cnc/cycle_time.hpp"
#include "pkm/cnc/exechon_path.hpp"
#include "pkm/cnc/exechon_path_checks.hpp"
#include "pkm/cnc/interpreter.hpp"
#include "pkm/cnc/joint_checks.hpp"
#include "pkm/cnc/joint_path.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/atomic_file.hpp"
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
  double max_wrist_velocity = 180.0;       ///< deg/s (Exechon)
  double max_wrist_acceleration = 1800.0;  ///< deg/s² (Exechon)
  std::string orientation = "vector";      ///< Exechon: how A/C orient the tool
  InterpreterArgs interpreter;             ///< tool table, block delete, loop guard
  /// Which rate options the user gave (the machine file's joint_rates apply to the others).
  bool velocity_given = false, acceleration_given = false;
  bool wrist_velocity_given = false, wrist_acceleration_given = false;
};

/// Exit code when a check is violated.
constexpr int kExitViolation = 1;

void refuseOverwrite(const std::string& path, bool force) {
  if (!path.empty())
    io::checkOverwrite(path, force ? io::Overwrite::kAllow : io::Overwrite::kRefuse);
}

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

nlohmann::ordered_json eventJson(cnc::PathCheck c,
                                 const cnc::CheckEvent& e,
                                 const std::string& len,
                                 bool exechon) {
  nlohmann::ordered_json j;
  j["line"] = e.line;
  j["position"] = std::vector<double>(e.pos.begin(), e.pos.end());
  j["item"] = e.item;
  j["value"] = shown(c, e.value);
  j["limit"] = shown(c, e.limit);
  j["margin"] = shown(c, e.margin);
  j["unit"] = unitOf(c, len, exechon, e.item);
  return j;
}

/// A program converted to joint space on one machine, whatever its type.
struct JointRun {
  std::string machine_name;
  std::string len;  ///< the machine's length unit
  bool exechon = false;
  cnc::InterpolationOptions interpolation;
  std::vector<cnc::PathPoint> points;
  cnc::CycleTime time;
  cnc::PathCheckReport report;
  std::string csv_header;
  std::function<void(std::string&, std::size_t)> csv_row;  ///< appends point i's row
  cnc::MotionLimits limits;  ///< in effect: options, else the machine file, else defaults
  double wrist_velocity = 0.0, wrist_acceleration = 0.0;  ///< deg/s, deg/s² (Exechon)
  std::vector<std::string> from_file;  ///< the limits taken from the machine file
};

/// The option's value when given, else the machine file's when it has one (noted in `from`).
double pick(double option,
            bool given,
            const std::optional<io::JointRateSpec>& file,
            double io::JointRateSpec::*field,
            const char* name,
            std::vector<std::string>& from) {
  if (given || !file || std::isnan((*file).*field)) return option;
  from.emplace_back(name);
  return (*file).*field;
}

/// The rate limits in effect for a machine file's joint_rates.
void effectiveLimits(const RunArgs& a,
                     const std::optional<io::JointRateSpec>& file,
                     bool wrist,
                     JointRun& run) {
  using S = io::JointRateSpec;
  run.limits = a.limits;
  run.limits.max_joint_velocity = pick(
      a.limits.max_joint_velocity, a.velocity_given, file, &S::velocity, "velocity", run.from_file);
  run.limits.max_joint_acceleration = pick(a.limits.max_joint_acceleration,
                                           a.acceleration_given,
                                           file,
                                           &S::acceleration,
                                           "acceleration",
                                           run.from_file);
  run.wrist_velocity = a.max_wrist_velocity;
  run.wrist_acceleration = a.max_wrist_acceleration;
  if (!wrist) return;
  run.wrist_velocity = pick(a.max_wrist_velocity,
                            a.wrist_velocity_given,
                            file,
                            &S::wrist_velocity_deg,
                            "wrist velocity",
                            run.from_file);
  run.wrist_acceleration = pick(a.max_wrist_acceleration,
                                a.wrist_acceleration_given,
                                file,
                                &S::wrist_acceleration_deg,
                                "wrist acceleration",
                                run.from_file);
}

/// The interpreted program's motions cut into points for joint-space conversion.
std::vector<cnc::PathPoint> interpolate(const std::vector<cnc::Move>& moves,
                                        const cnc::InterpolationOptions& options) {
  // The first motion positions the machine at its end point (the interpreter's start-up
  // position 0 is not a machine position).
  cnc::PathInterpolator interp(options, moves.front().end);
  std::vector<cnc::PathPoint> points;
  for (std::size_t m = 0; m < moves.size(); ++m)
    interp.append(moves[m], static_cast<std::uint32_t>(m), points);
  return points;
}

void runHexapod(const RunArgs& a, const cnc::MoveCollector& program, JointRun& run) {
  const std::vector<cnc::Move>& moves = program.moves;
  const io::HexapodMachine machine = io::loadHexapodMachine(a.machine);
  printNotices(machine.notices);
  auto model = std::make_shared<kinematics::HexapodModel>(machine.model);
  run.machine_name = model->name;
  run.len = std::string(toString(model->unit));
  effectiveLimits(a, machine.joint_rates, false, run);
  run.interpolation = cnc::jointSpaceInterpolation(*model, a.tolerance);
  run.points = interpolate(moves, run.interpolation);
  cnc::HexapodJointConverter conv(*model);
  auto q = std::make_shared<std::vector<kinematics::StrutVector>>();
  conv.solveAll(run.points, *q);
  run.time = cnc::estimateCycleTime(
      run.points, *q, run.limits, cnc::dwellsOnPath(run.points, program.dwells));
  run.report = cnc::checkPath(*model, run.points, *q, run.limits);
  run.csv_header = cnc::kJointCsvHeader;
  run.csv_row = [&run, q](std::string& out, std::size_t i) {
    cnc::appendJointCsv(out, run.points[i], run.time.t[i], (*q)[i]);
  };
}

void runExechon(const RunArgs& a, const cnc::MoveCollector& program, JointRun& run) {
  const std::vector<cnc::Move>& moves = program.moves;
  const auto orientation = cnc::parseExechonOrientation(a.orientation);
  for (const cnc::Move& m : moves)
    if (m.end[4] != 0.0)
      throw InvalidArgument(fmt::format("{}:{}: B{} programmed, but an Exechon has no B axis",
                                        a.program,
                                        m.line,
                                        io::formatNumber(m.end[4])));
  const io::ExechonMachine machine = io::loadExechonMachine(a.machine);
  printNotices(machine.notices);
  auto model = std::make_shared<kinematics::ExechonModel>(machine.model);
  run.exechon = true;
  run.machine_name = model->name;
  run.len = std::string(toString(model->unit));
  effectiveLimits(a, machine.joint_rates, true, run);
  const cnc::JointRateLimits limits =
      cnc::exechonRateLimits(run.limits, run.wrist_velocity, run.wrist_acceleration);
  run.interpolation = cnc::exechonInterpolation(*model, a.tolerance);
  run.points = interpolate(moves, run.interpolation);
  cnc::ExechonJointConverter conv(*model, orientation);
  auto samples = std::make_shared<std::vector<cnc::ExechonPathSample>>();
  conv.solveAll(run.points, *samples);
  std::vector<kinematics::StrutVector> q(samples->size());
  for (std::size_t i = 0; i < q.size(); ++i) q[i] = (*samples)[i].joints;
  run.time =
      cnc::estimateCycleTime(run.points, q, limits, cnc::dwellsOnPath(run.points, program.dwells));
  run.report = cnc::checkExechonPath(*model, run.points, *samples, limits);
  run.csv_header = cnc::kExechonJointCsvHeader;
  run.csv_row = [&run, samples](std::string& out, std::size_t i) {
    cnc::appendExechonJointCsv(out, run.points[i], run.time.t[i], (*samples)[i]);
  };
}

/// Writes the joint CSV through io::AtomicFile, in blocks of about 1 MiB.
void writeJointCsv(const std::string& path, const JointRun& run) {
  io::AtomicFile f(path, io::Overwrite::kAllow);
  std::string buf = run.csv_header + "\n";
  for (std::size_t i = 0; i < run.points.size(); ++i) {
    run.csv_row(buf, i);
    if (buf.size() > (1u << 20)) {
      f.write(buf);
      buf.clear();
    }
  }
  f.write(buf);
  f.commit();
}

/// "-" for a margin that no evaluation set (+infinity), else the margin and its unit.
std::string marginText(cnc::PathCheck c, double margin, const std::string& unit) {
  if (std::isinf(margin)) return "-";
  return fmt::format("{:.4g} {}", shown(c, margin), unit);
}

void runGcode(const RunArgs& a) {
  a.limits.validate();
  PKM_CHECK(a.tolerance > 0.0 && std::isfinite(a.tolerance), "--tolerance must be > 0");
  refuseOverwrite(a.out, a.force);
  refuseOverwrite(a.report, a.force);
  const bool exechon = machineTypeOf(a.machine) == "exechon";
  if (!exechon && a.orientation != "vector")
    throw InvalidArgument("--orientation applies to Exechon machines only");
  cnc::Interpreter interpreter(a.interpreter.options());
  const cnc::Program program = cnc::Program::load(a.program);
  cnc::MoveCollector moves;
  (void)interpreter.run(program, moves);
  if (moves.moves.empty()) throw InvalidArgument(fmt::format("{}: no motion", a.program));
  JointRun run;
  if (exechon)
    runExechon(a, moves, run);
  else
    runHexapod(a, moves, run);
  if (!a.out.empty()) writeJointCsv(a.out, run);

  const std::string& len = run.len;
  const auto& io = run.interpolation;
  const cnc::PathCheckReport& report = run.report;
  Output out;
  std::string& s = out.text();
  s += fmt::format("gcode run: {} on {} ({} lines, {} motions, {} points)\n",
                   a.program,
                   run.machine_name,
                   program.lineCount(),
                   moves.moves.size(),
                   run.points.size());
  if (exechon)
    s += fmt::format("orientation: {} (A/C words are {})\n",
                     a.orientation,
                     a.orientation == "vector" ? "the tool vector's angles in the world frame"
                                               : "the wrist axes' readings");
  s += fmt::format(
      "interpolation: tolerance {} mm, max step {:.4g} mm, max rotary step {:.4g} deg\n",
      a.tolerance,
      io.max_step,
      io.max_angle_step);
  s += fmt::format("limits: joint velocity {} {}/s, joint acceleration {} {}/s^2, ",
                   run.limits.max_joint_velocity,
                   len,
                   run.limits.max_joint_acceleration,
                   len);
  if (exechon)
    s += fmt::format("wrist velocity {} deg/s, wrist acceleration {} deg/s^2, ",
                     run.wrist_velocity,
                     run.wrist_acceleration);
  s += fmt::format("rapid {} mm/min{}\n",
                   a.limits.rapid_rate,
                   run.from_file.empty() ? std::string()
                                         : fmt::format(" ({} from the machine file)",
                                                       fmt::join(run.from_file, ", ")));
  s += fmt::format(
      "cycle time: {:.3f} s{}\n",
      run.time.total,
      run.time.dwell > 0.0 ? fmt::format(" (dwells {:.3f} s)", run.time.dwell) : std::string());
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
    const std::string unit = unitOf(c, len, exechon);
    const char* status = !st.enabled ? "n/a" : st.violations > 0 ? "VIOLATED" : "ok";
    const bool any = std::isfinite(st.worst.margin);
    if (st.enabled)
      s += fmt::format("{:<19} {:<9} {:>10} {:>14} {:>7}  {}\n",
                       name,
                       status,
                       st.violations,
                       marginText(c, st.worst.margin, unitOf(c, len, exechon, st.worst.item)),
                       any ? std::to_string(st.worst.line) : "-",
                       st.worst.item);
    else
      s += fmt::format("{:<19} {:<9}\n", name, status);
    nlohmann::ordered_json j;
    j["enabled"] = st.enabled;
    j["violations"] = st.violations;
    j["unit"] = unit;
    if (st.enabled && any) j["worst"] = eventJson(c, st.worst, len, exechon);
    if (st.violations > 0) j["first_violation"] = eventJson(c, st.first, len, exechon);
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
        unitOf(c, len, exechon, e.item));
  }
  s += report.ok() ? "result: all checks pass\n" : "result: VIOLATIONS (exit code 1)\n";
  if (!a.report.empty()) {
    nlohmann::ordered_json j;
    j["program"] = a.program;
    j["machine"] = run.machine_name;
    j["machine_type"] = exechon ? "exechon" : "hexapod";
    j["units"] = len;
    if (exechon) j["orientation"] = a.orientation;
    j["tolerance_mm"] = a.tolerance;
    j["max_step_mm"] = io.max_step;
    j["max_angle_step_deg"] = io.max_angle_step;
    j["max_joint_velocity"] = run.limits.max_joint_velocity;
    j["max_joint_acceleration"] = run.limits.max_joint_acceleration;
    if (exechon) {
      j["max_wrist_velocity_deg_per_s"] = run.wrist_velocity;
      j["max_wrist_acceleration_deg_per_s2"] = run.wrist_acceleration;
    }
    j["rapid_rate_mm_per_min"] = a.limits.rapid_rate;
    j["limits_from_machine_file"] = run.from_file;
    j["motions"] = moves.moves.size();
    j["points"] = run.points.size();
    j["cycle_time_s"] = run.time.total;
    j["dwell_time_s"] = run.time.dwell;
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
      "interpolate PROGRAM, convert it to the joints of a hexapod or an Exechon, estimate the "
      "cycle time and check every limit (exit 1 on a violation)");
  r->add_option("program", a->program, "G-code file (.ngc)")->required();
  r->add_option("--machine", a->machine, "hexapod or Exechon machine: JSON file or built-in name");
  r->add_option("--orientation",
                a->orientation,
                "Exechon: A/C words are the tool vector's angles in the world frame (vector, "
                "default) or the wrist axes' readings (axes)");
  r->add_option("--tolerance", a->tolerance, "chordal tolerance in mm (default 0.01)");
  a->interpreter.add(*r);
  r->add_option("--out", a->out, "write the joint CSV to FILE (docs/gcode.md)");
  r->add_option("--report", a->report, "write the check report as JSON to FILE");
  r->add_flag("--force", a->force, "overwrite existing --out/--report files");
  CLI::Option* vel = r->add_option("--max-joint-velocity",
                                   a->limits.max_joint_velocity,
                                   "strut speed limit, machine length unit/s (default: the machine "
                                   "file's joint_rates, else 200)");
  CLI::Option* acc = r->add_option(
      "--max-joint-acceleration",
      a->limits.max_joint_acceleration,
      "strut acceleration limit, machine length unit/s^2 (default: the machine file's, else 2000)");
  CLI::Option* wvel =
      r->add_option("--max-wrist-velocity",
                    a->max_wrist_velocity,
                    "Exechon wrist C/A speed limit, deg/s (default: the machine file's, else 180)");
  CLI::Option* wacc = r->add_option(
      "--max-wrist-acceleration",
      a->max_wrist_acceleration,
      "Exechon wrist C/A acceleration limit, deg/s^2 (default: the machine file's, else 1800)");
  r->add_option("--rapid-rate", a->limits.rapid_rate, "G0 path speed, mm/min (default 10000)");
  r->callback([a, vel, acc, wvel, wacc] {
    a->velocity_given = vel->count() > 0;
    a->acceleration_given = acc->count() > 0;
    a->wrist_velocity_given = wvel->count() > 0;
    a->wrist_acceleration_given = wacc->count() > 0;
    runGcode(*a);
  });
}

}  // namespace pkm::cli
