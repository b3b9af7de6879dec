// `gcode run` on a hexapod or an Exechon: the program interpolated, converted to joints, timed
// and checked (workflow/gcode_run.hpp).
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <memory>
#include <optional>

#include "gcode_run_detail.hpp"
#include "pkm/cnc/exechon_path.hpp"
#include "pkm/cnc/exechon_path_checks.hpp"
#include "pkm/cnc/joint_path.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/atomic_file.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/io/number_format.hpp"
#include "pkm/kinematics/exechon_wrist.hpp"
#include "pose_rows.hpp"

namespace pkm::workflow::detail {

namespace {

/// The option's value when given, else the machine file's when it has one (noted in `from`),
/// else `fallback`.
double pick(const std::optional<double>& option,
            double fallback,
            const std::optional<io::JointRateSpec>& file,
            double io::JointRateSpec::*field,
            const char* name,
            std::vector<std::string>& from) {
  if (option) return *option;
  if (!file || std::isnan((*file).*field)) return fallback;
  from.emplace_back(name);
  return (*file).*field;
}

/// The rate limits in effect for a machine file's joint_rates.
void effectiveLimits(const GcodeRunRequest& r,
                     const std::optional<io::JointRateSpec>& file,
                     bool wrist,
                     JointRun& run) {
  using S = io::JointRateSpec;
  std::vector<std::string>& from = run.from_file;
  run.limits.rapid_rate = r.rapid_rate.value_or(kDefaultRapidRate);
  run.limits.max_joint_velocity =
      pick(r.max_joint_velocity, 200.0, file, &S::velocity, "velocity", from);
  run.limits.max_joint_acceleration =
      pick(r.max_joint_acceleration, 2000.0, file, &S::acceleration, "acceleration", from);
  run.wrist_velocity = r.max_wrist_velocity.value_or(180.0);
  run.wrist_acceleration = r.max_wrist_acceleration.value_or(1800.0);
  if (!wrist) return;
  run.wrist_velocity =
      pick(r.max_wrist_velocity, 180.0, file, &S::wrist_velocity_deg, "wrist velocity", from);
  run.wrist_acceleration = pick(r.max_wrist_acceleration,
                                1800.0,
                                file,
                                &S::wrist_acceleration_deg,
                                "wrist acceleration",
                                from);
}

/// A limit of the INI in mm (or deg) per second, +inf when not given.
double orNoLimit(double v, double scale) {
  return std::isnan(v) ? cnc::RapidAxisLimits::kNoLimit : v * scale;
}

/// An INI's velocity limits on rapids (LinuxCNC: a G0 runs at [TRAJ] MAX_LINEAR_VELOCITY, lowered
/// so that no axis exceeds its [AXIS_L] MAX_VELOCITY along the move): the rapid rate unless the
/// request gives one, and the axis limits.
void iniRapidLimits(const GcodeRunRequest& r,
                    const io::IniVelocityLimits& ini,
                    LengthUnit unit,
                    JointRun& run) {
  const double mm = millimetresPer(unit);
  if (!r.rapid_rate && !std::isnan(ini.linear)) {
    run.limits.rapid_rate = ini.linear * 60.0 * mm;
    run.from_file.emplace_back("rapid rate");
  }
  cnc::RapidAxisLimits& axes = run.limits.rapid_axes;
  std::vector<std::string> words;
  for (std::size_t i = 0; i < 6; ++i) {
    axes.axis_velocity[i] = orNoLimit(ini.axis[i], i < 3 ? mm : 1.0);
    if (!std::isnan(ini.axis[i]))
      words.push_back(
          fmt::format("{} {:.6g} {}/s", "XYZABC"[i], ini.axis[i], i < 3 ? toString(unit) : "deg"));
  }
  axes.angular_rate = orNoLimit(ini.angular, 60.0);
  if (!std::isnan(ini.angular))
    words.push_back(fmt::format("rotary-only {:.6g} deg/s", ini.angular));
  if (!words.empty())
    run.rapid_limits =
        fmt::format("each G0 at most {} along the move ({})", fmt::join(words, ", "), ini.source);
}

/// The interpreted program's motions cut into points for joint-space conversion.
std::vector<cnc::PathPoint> interpolate(const GcodeRunRequest& request,
                                        const std::vector<cnc::Move>& moves,
                                        const cnc::InterpolationOptions& options,
                                        const GcodeProgress& progress) {
  // The first motion positions the machine at its end point (the interpreter's start-up
  // position 0 is not a machine position).
  cnc::InterpolationOptions o = options;
  o.skip_still_moves = true;  // no zero-length segment in the joint path
  o.max_points = request.max_points;
  cnc::PathInterpolator interp(o, moves.front().end);
  std::vector<cnc::PathPoint> points;
  progress.report("interpolating", "motions", 2, kRunStages, 0, moves.size());
  for (std::size_t m = 0; m < moves.size(); ++m) {
    try {
      interp.append(moves[m], static_cast<std::uint32_t>(m), points);
    } catch (const cnc::PathTooLong& e) {
      throw IoError(locate(request.program.name,
                           moves[m].line,
                           fmt::format("{}: raise it with --max-points N (each point takes about "
                                       "150 bytes)",
                                       e.what())));
    }
    progress.every("interpolating", "motions", 2, kRunStages, m + 1, moves.size());
  }
  return points;
}

/// converter.solve of every point, in order.
template <class Converter, class Joints>
void convert(Converter& converter,
             const std::vector<cnc::PathPoint>& points,
             const GcodeProgress& progress,
             std::vector<Joints>& out) {
  progress.report("converting", "points", 3, kRunStages, 0, points.size());
  out.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    out[i] = converter.solve(points[i].pos);
    progress.every("converting", "points", 3, kRunStages, i + 1, points.size());
  }
}

/// Why a hexapod's interference and joint-angle checks are off, and how to turn them on.
void hexapodOffReasons(const kinematics::HexapodModel& model, JointRun& run) {
  const auto at = [&run](cnc::PathCheck c) -> std::string& {
    return run.off_reason[static_cast<std::size_t>(c)];
  };
  if (!(model.strut_diameter > 0.0))
    at(cnc::PathCheck::kInterference) =
        "(the machine has no strut diameter; a LinuxCNC configuration states none: give "
        "--strut-diameter D, or \"strut_diameter\" in a machine file)";
  at(cnc::PathCheck::kJointAngle) =
      "(the machine has no joint cone limits; a LinuxCNC configuration states none: give each "
      "strut's base_joint and platform_joint \"max_angle_deg\" in a machine file)";
}

}  // namespace

double toleranceMm(const GcodeRunRequest& request, LengthUnit unit) {
  return request.tolerance ? *request.tolerance * millimetresPer(unit) : kDefaultToleranceMm;
}

void runHexapod(const GcodeRunRequest& request,
                const io::HexapodMachine& machine,
                const cnc::MoveCollector& program,
                const GcodeProgress& progress,
                JointRun& run) {
  auto model = std::make_shared<kinematics::HexapodModel>(machine.model);
  if (request.strut_diameter) model->strut_diameter = *request.strut_diameter;
  hexapodOffReasons(*model, run);
  run.machine_name = model->name;
  run.len = std::string(toString(model->unit));
  effectiveLimits(request, machine.joint_rates, false, run);
  if (machine.ini_velocity) iniRapidLimits(request, *machine.ini_velocity, model->unit, run);
  run.tolerance_mm = toleranceMm(request, model->unit);
  run.interpolation = cnc::jointSpaceInterpolation(*model, run.tolerance_mm);
  run.points = interpolate(request, program.moves, run.interpolation, progress);
  cnc::HexapodJointConverter conv(*model);
  auto q = std::make_shared<std::vector<kinematics::StrutVector>>();
  convert(conv, run.points, progress, *q);
  run.time = cnc::estimateCycleTime(
      run.points, *q, run.limits, cnc::dwellsOnPath(run.points, program.dwells));
  run.report = cnc::checkPath(*model, run.points, *q, run.limits, request.max_violations);
  for (int i = 0; i < kinematics::kStruts; ++i) {
    run.joint_names.push_back(fmt::format("strut {}", i));
    run.joint_units.push_back(run.len);
  }
  run.joints_at = [q](std::size_t i) { return (*q)[i]; };
  run.frame_at = [&run, model](std::size_t i) {
    kinematics::HexapodData data(*model);
    return hexapodPoseRow(*model, data, cnc::poseFromAxes(run.points[i].pos, model->unit));
  };
  run.csv_header = cnc::kJointCsvHeader;
  run.csv_row = [&run, q](std::string& out, std::size_t i) {
    cnc::appendJointCsv(out, run.points[i], run.time.t[i], (*q)[i]);
  };
}

void runExechon(const GcodeRunRequest& request,
                const cnc::MoveCollector& program,
                const RunControl& control,
                const GcodeProgress& progress,
                JointRun& run) {
  const auto orientation = cnc::parseExechonOrientation(request.orientation);
  for (const cnc::Move& m : program.moves)
    if (m.end[4] != 0.0)
      throw InvalidArgument(fmt::format("{}:{}: B{} programmed, but an Exechon has no B axis",
                                        request.program.name,
                                        m.line,
                                        io::formatNumber(m.end[4])));
  const io::ExechonMachine machine =
      request.exechon ? *request.exechon : io::loadExechonMachine(request.machine);
  if (!request.exechon) control.note(machine.notices);
  auto model = std::make_shared<kinematics::ExechonModel>(machine.model);
  run.exechon = true;
  run.machine_name = model->name;
  run.len = std::string(toString(model->unit));
  effectiveLimits(request, machine.joint_rates, true, run);
  const cnc::JointRateLimits limits =
      cnc::exechonRateLimits(run.limits, run.wrist_velocity, run.wrist_acceleration);
  run.tolerance_mm = toleranceMm(request, model->unit);
  run.interpolation = cnc::exechonInterpolation(*model, run.tolerance_mm);
  run.points = interpolate(request, program.moves, run.interpolation, progress);
  cnc::ExechonJointConverter conv(*model, orientation);
  auto samples = std::make_shared<std::vector<cnc::ExechonPathSample>>();
  convert(conv, run.points, progress, *samples);
  std::vector<kinematics::StrutVector> q(samples->size());
  for (std::size_t i = 0; i < q.size(); ++i) q[i] = (*samples)[i].joints;
  run.time =
      cnc::estimateCycleTime(run.points, q, limits, cnc::dwellsOnPath(run.points, program.dwells));
  run.report = cnc::checkExechonPath(*model, run.points, *samples, limits, request.max_violations);
  for (int i = 0; i < 5; ++i) {
    run.joint_names.push_back(cnc::exechonJointName(i));
    run.joint_units.push_back(i < 3 ? run.len : "deg");
  }
  run.joints_at = [samples](std::size_t i) { return (*samples)[i].joints; };
  run.frame_at = [model, samples](std::size_t i) {
    const cnc::ExechonPathSample& sample = (*samples)[i];
    if (!sample.ok()) {
      PoseCheckRow row;
      row.status = std::string(kinematics::toString(sample.status));
      return row;
    }
    kinematics::ExechonData data(*model);
    kinematics::evaluateConfiguration(*model, data, sample.config);
    return exechonDataRow(*model, data, kinematics::checkConfiguration(*model, data));
  };
  run.csv_header = cnc::kExechonJointCsvHeader;
  run.csv_row = [&run, samples](std::string& out, std::size_t i) {
    cnc::appendExechonJointCsv(out, run.points[i], run.time.t[i], (*samples)[i]);
  };
}

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

}  // namespace pkm::workflow::detail
