// `pkm calibrate hexapod --live` (pkm/live/live_calibration.hpp).
#include "pkm/live/live_calibration.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>

#include "linuxcnc_rig.hpp"
#include "pkm/calibration/constrained_motion.hpp"
#include "pkm/calibration/hexapod_parameters.hpp"
#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/io/atomic_file.hpp"
#include "pkm/io/csv.hpp"
#include "pkm/io/linuxcnc_machine.hpp"
#include "pkm/io/linuxcnc_patch.hpp"
#include "pkm/io/measurement_files.hpp"
#include "pkm/io/simulation_metadata.hpp"

namespace pkm::live {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

/// The files a run writes into its folder.
constexpr std::array<const char*, 7> kOutputs{"constrained-motion.csv",
                                              "constrained-motion-holdout.csv",
                                              "calibration.json",
                                              "calibration.hal",
                                              "calibration.pkmhexkins.hal",
                                              "calibration.summary.json",
                                              "commands.log"};

/// [AXIS_L] MIN_LIMIT / MAX_LIMIT of X Y Z A B C (±inf where absent).
void readAxisLimits(const std::string& ini_path, GaugeStationOptions& o) {
  const io::NamedText ini = io::readNamedText(ini_path);
  const char* axes = "XYZABC";
  for (std::size_t k = 0; k < 6; ++k) {
    const std::string section = fmt::format("[AXIS_{}]", axes[k]);
    o.axis_min[k] = -std::numeric_limits<double>::infinity();
    o.axis_max[k] = std::numeric_limits<double>::infinity();
    for (const auto& [key, value] :
         {std::pair{"MIN_LIMIT", &o.axis_min[k]}, std::pair{"MAX_LIMIT", &o.axis_max[k]}}) {
      const auto entry = io::iniValue(ini, section, key);
      if (!entry) continue;
      if (!io::parseFiniteDouble(entry->value, *value))
        throw IoError(
            locate(ini.name, entry->line, fmt::format("{} {}: not a number", section, key)));
    }
  }
}

/// Refuses unless LinuxCNC runs `ini` in mm, may move, and has no tool length offset.
void checkLinuxcnc(const LinuxcncStatus& st, const std::string& ini) {
  std::error_code ec;
  if (!fs::equivalent(st.ini, ini, ec))
    throw InvalidArgument(fmt::format("LinuxCNC runs {}, not {}", st.ini, ini));
  if (const std::string why = motionRefusal(st); !why.empty())
    throw InvalidArgument("LinuxCNC cannot be moved: " + why);
  if (std::abs(st.linear_units - 1.0) > 1e-12)
    throw InvalidArgument("the live calibration needs a configuration in mm");
  for (const double t : st.tool_offset)
    if (t != 0.0)
      throw InvalidArgument("a tool length offset is active (G43): cancel it with G49 first");
}

/// The constrained-motion data of measured stations (reference first).
calibration::ConstrainedMotionData dataOf(const simulation::DialGaugeSetup& setup,
                                          const std::vector<simulation::DialGaugeStation>& st) {
  calibration::ConstrainedMotionData d;
  d.gauge_points = setup.gauge_points;
  d.table_normal = setup.table_normal.normalized();
  auto station = [](const simulation::DialGaugeStation& s) {
    calibration::GaugeStation g;
    g.readings = s.lengths;
    g.command = {s.command.head<3>(), s.command.tail<3>()};
    g.gauges = s.readings;
    return g;
  };
  d.reference = station(st.front());
  for (std::size_t k = 1; k < st.size(); ++k) d.stations.push_back(station(st[k]));
  return d;
}

/// RMS of the gauge residuals of `data` on `model`, mm (NaN when an FK fails).
double residualRms(const kinematics::HexapodModel& model,
                   const calibration::ConstrainedMotionData& data) {
  kinematics::HexapodData work(model);
  double sum = 0.0;
  for (std::size_t k = 0; k < data.stations.size(); ++k) {
    const auto r = calibration::constrainedResiduals(model, work, data, k);
    if (!r) return std::numeric_limits<double>::quiet_NaN();
    sum += r->squaredNorm();
  }
  return std::sqrt(sum / static_cast<double>(3 * std::max<std::size_t>(1, data.stations.size())));
}

}  // namespace

void LiveCalibrationRequest::validate() const {
  if (ini.empty()) throw InvalidArgument("--ini: give the running configuration's INI");
  for (const std::string& g : gauges)
    if (g.empty()) throw InvalidArgument("--gauges: give the three gauges' HAL pins");
  if (out.empty()) throw InvalidArgument("--out: give the folder for the measurement files");
  if (!(approach > 0.0) || !(tolerance > 0.0) || max_iterations < 1 || !(settle_s >= 0.0) ||
      !(laser_length > 0.0) || gauge_samples < 1)
    throw InvalidArgument(
        "approach, tolerance, iterations, samples, settle and laser length must be > 0");
  if (!(prior_sigma > 0.0) || !(measurement_sigma > 0.0) || prior_uncertainty < 0.0)
    throw InvalidArgument("--prior-sigma and --measurement-sigma must be > 0");
  stations.validate();
  // Each station gives three equations (one per gauge); the fit needs one per unknown.
  const int least = (calibration::kHexapodParameters + 2) / 3;
  if (stations.count < least)
    throw InvalidArgument(fmt::format(
        "--stations: at least {}: three gauge readings a station must give the {} unknowns of "
        "the hexapod's calibration (the default, 36, follows Lee et al.: three times as many)",
        least,
        calibration::kHexapodParameters));
}

namespace {

/// One run of the routine: its inputs, what it has found so far, and its steps.
class Routine {
 public:
  Routine(const LiveCalibrationRequest& request,
          LinuxcncCommander& cnc,
          const workflow::RunControl& control)
      : r_(request), cnc_(cnc), control_(control), config_(io::readLinuxcncHexapod(request.ini)) {}

  /// The set-up and the stations (nothing moves).
  void plan() {
    checkLinuxcnc(cnc_.status(), r_.ini);
    if (!r_.force)  // before anything moves, not after an hour of measuring
      for (const char* name : kOutputs)
        if (fs::exists(fs::path(r_.out) / name))
          throw IoError(fmt::format("{}: exists; pass --force to replace the files of that run",
                                    (fs::path(r_.out) / name).string()));
    fs::create_directories(r_.out);
    setup_.name = "live-constrained-motion";
    setup_.gauge_points = r_.gauge_points;
    const kinematics::PoseRpy& home = config_.machine.model.home;
    const std::array<double, 6> ref =
        r_.reference.value_or(std::array<double, 6>{home.position.x(),
                                                    home.position.y(),
                                                    home.position.z(),
                                                    radToDeg(home.rpy.x()),
                                                    radToDeg(home.rpy.y()),
                                                    radToDeg(home.rpy.z())});
    setup_.reference = Eigen::VectorXd(6);
    setup_.reference << ref[0], ref[1], ref[2], degToRad(ref[3]), degToRad(ref[4]),
        degToRad(ref[5]);
    setup_.tolerance = r_.tolerance;
    setup_.max_iterations = r_.max_iterations;
    setup_.approach = r_.approach;
    GaugeStationOptions options = r_.stations;
    readAxisLimits(r_.ini, options);
    result_.plan = planGaugeStations(config_.machine, setup_, options);
    report("plan",
           0,
           0,
           fmt::format("{} stations and {} held out of {} reachable moves; {} of 42 parameter "
                       "directions identifiable",
                       result_.plan.fit.size(),
                       result_.plan.holdout.size(),
                       result_.plan.candidates,
                       result_.plan.identifiable));
  }

  /// The laser before, the stations and the held-out stations, their files.
  void measure() {
    if (!r_.laser.empty()) {
      report("laser", 0, 0, "x move before calibration");
      result_.laser_error_before = detail::laserXError(
          cnc_, r_.laser, setup_.reference, r_.laser_length, r_.settle_s, control_);
    }
    detail::LinuxcncGaugeRig rig(cnc_, r_.gauges, r_.settle_s, r_.gauge_samples, control_);
    const std::size_t total = result_.plan.fit.size() + result_.plan.holdout.size();
    for (const bool held : {false, true}) {
      setup_.stations = held ? result_.plan.holdout : result_.plan.fit;
      const std::size_t offset = held ? result_.plan.fit.size() : 0;
      auto& into = held ? result_.held_out : result_.stations;
      into = simulation::runConstrainedMotion(rig, setup_, [&](const auto& s) {
        if (s.station == 0) return;
        report("station",
               offset + static_cast<std::size_t>(s.station),
               total,
               fmt::format("{} readings, gauges {:.4f} {:.4f} {:.4f} mm{}",
                           s.iterations,
                           s.readings[0],
                           s.readings[1],
                           s.readings[2],
                           s.converged ? "" : " (not converged)"));
      });
      const io::Metadata meta = io::gaugeSetupMetadata(
          setup_,
          fmt::format("three gauges on HAL pins {} (pkm calibrate hexapod --live)",
                      fmt::join(r_.gauges, ", ")));
      (held ? result_.holdout_file : result_.data_file) =
          write(held ? "constrained-motion-holdout.csv" : "constrained-motion.csv",
                io::dialGaugeCsv(meta, into));
    }
    (void)detail::moveAndCheck(cnc_, setup_.reference);
  }

  /// The calibration and the held-out check.
  void fit(const workflow::RunControl& control) {
    report("fit", 0, 0, "calibrating");
    workflow::HexapodCalibrationRequest& fit = result_.fit;
    fit.loaded = config_.machine;
    fit.machine = config_.file;
    fit.data = {io::readNamedText(result_.data_file)};
    fit.out = (fs::path(r_.out) / "calibration.json").string();
    fit.force = r_.force;
    fit.prior_sigma = r_.prior_sigma;
    fit.measurement_sigma = r_.measurement_sigma;
    fit.prior_uncertainty = r_.prior_uncertainty;
    result_.calibration = workflow::calibrateHexapod(fit, control);
    const calibration::ConstrainedMotionData held = dataOf(setup_, result_.held_out);
    result_.holdout_rms_before = residualRms(config_.machine.model, held);
    result_.holdout_rms_after = residualRms(result_.calibration.calibrated.model, held);
  }

  /// Install, apply to a running pkmhexkins and re-measure the x move.
  void install() {
    report("install", 0, 0, "installing into " + r_.ini);
    result_.install = workflow::installIntoLinuxcnc({result_.fit.out, r_.ini, true});
    if (result_.install->kinematics != "pkmhexkins") return;  // genhexkins: restart LinuxCNC
    detail::applyPkmhexkinsGeometry(cnc_, result_.calibration.calibrated);
    result_.applied = true;
    if (!r_.laser.empty()) {
      report("laser", 0, 0, "x move after calibration");
      result_.laser_error_after = detail::laserXError(
          cnc_, r_.laser, setup_.reference, r_.laser_length, r_.settle_s, control_);
    }
    (void)detail::moveAndCheck(cnc_, setup_.reference);
  }

  /// Writes the log of every line sent.
  void writeLog() { (void)write("commands.log", fmt::format("{}\n", fmt::join(cnc_.log(), "\n"))); }

  LiveCalibrationResult& result() { return result_; }

 private:
  void report(const std::string& stage, std::size_t i, std::size_t n, std::string text) const {
    control_.report({stage,
                     i,
                     n,
                     std::chrono::duration<double>(Clock::now() - started_).count(),
                     std::move(text)});
  }
  std::string write(const std::string& name, const std::string& text) const {
    const std::string path = (fs::path(r_.out) / name).string();
    io::writeFileAtomic(path, text, r_.force ? io::Overwrite::kAllow : io::Overwrite::kRefuse);
    return path;
  }

  const LiveCalibrationRequest& r_;
  LinuxcncCommander& cnc_;
  const workflow::RunControl& control_;
  const io::LinuxcncHexapod config_;
  const Clock::time_point started_ = Clock::now();
  simulation::DialGaugeSetup setup_;
  LiveCalibrationResult result_;
};

}  // namespace

LiveCalibrationResult calibrateLive(const LiveCalibrationRequest& request,
                                    LinuxcncCommander& cnc,
                                    const workflow::RunControl& control,
                                    const ConfirmInstall& confirm) {
  request.validate();
  const auto started = Clock::now();
  Routine run(request, cnc, control);
  run.plan();
  try {
    run.measure();
    run.fit(control);
    if (request.install || (confirm && confirm(run.result()))) run.install();
  } catch (...) {
    try {  // the log of what was sent, kept also when the routine stopped early
      run.writeLog();
    } catch (const std::exception&) {
    }
    throw;
  }
  run.writeLog();
  LiveCalibrationResult result = std::move(run.result());
  result.log = cnc.log();
  result.seconds = std::chrono::duration<double>(Clock::now() - started).count();
  return result;
}

}  // namespace pkm::live
