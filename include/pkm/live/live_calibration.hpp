/// @file
/// @brief `pkm calibrate hexapod --live`: Lee et al.'s calibration by constrained motion
/// ("Development of a Parallel-Typed CNC Machine", §3 and §5) done by the controller itself
/// (docs/linuxcnc.md, "Automated calibration by constrained motion"). pkm plans the stations,
/// drives the running LinuxCNC through them by MDI, and at each one servoes the platform until the
/// three gauges (HAL pins) read zero, every move approaching from the same side; it writes the
/// constrained-motion files, calibrates, checks held-out stations, and on confirmation installs
/// the result, applies it to the running machine (pkmhexkins) and re-measures an x move with a
/// laser (a HAL pin).
#pragma once

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "pkm/live/gauge_stations.hpp"
#include "pkm/live/linuxcnc_commander.hpp"
#include "pkm/simulation/dial_gauges.hpp"
#include "pkm/simulation/machine_in_loop.hpp"
#include "pkm/workflow/calibrate_hexapod.hpp"
#include "pkm/workflow/linuxcnc_install.hpp"
#include "pkm/workflow/progress.hpp"

namespace pkm::live {

/// What the routine is asked to do.
struct LiveCalibrationRequest {
  std::string ini;                    ///< the running configuration's INI (required)
  std::array<std::string, 3> gauges;  ///< HAL pins of the three gauges, mm (required)
  /// Gauge tips in the tool frame, mm (default: pkm-truth's, docs/linuxcnc.md).
  std::array<Eigen::Vector3d, 3> gauge_points = simulation::LoopSensors{}.gauge_points;
  std::string laser;  ///< HAL pin of a laser along x, mm ("": no x-move measurement)
  std::string out;    ///< folder of the files written (required; created)
  /// The reference pose x y z a b c (mm, degrees); default [TRAJ] HOME.
  std::optional<std::array<double, 6>> reference;
  GaugeStationOptions stations;  ///< axis limits are read from the INI
  double approach = 1.0;         ///< mm below every command first (> 0)
  double tolerance = 0.003;      ///< gauges within this are zero, mm
  int max_iterations = 10;       ///< readings per station before giving up
  double settle_s = 0.1;         ///< wait after a move before reading the gauges
  int gauge_samples = 5;         ///< readings averaged per gauge reading (a DRO's dither), ≥ 1
  double laser_length = 540.0;   ///< the x move measured, mm, centred on the reference
  double prior_sigma = 5.0;      ///< the calibration's prior (docs/calibration.md), mm
  double measurement_sigma = 0.002;  ///< the readings' σ, mm
  double prior_uncertainty = 20.0;   ///< the machine file's geometry in the budgets, mm
  /// The user's confirmation given beforehand: install, apply and re-measure after the fit.
  bool install = false;
  bool force = false;  ///< replace files of an earlier run in `out`
  /// Throws pkm::InvalidArgument naming the option.
  void validate() const;
};

/// What it did.
struct LiveCalibrationResult {
  GaugeStationPlan plan;
  std::vector<simulation::DialGaugeStation> stations;  ///< reference, fit stations
  std::vector<simulation::DialGaugeStation> held_out;  ///< reference, held-out stations
  std::string data_file, holdout_file;                 ///< the constrained-motion files
  workflow::HexapodCalibrationRequest fit;             ///< the calibration as it was asked for
  workflow::HexapodCalibrationResult calibration;
  /// The held-out stations' gauge residuals (model − readings), RMS, mm: the configuration's
  /// machine and the calibrated one.
  double holdout_rms_before = 0.0, holdout_rms_after = 0.0;
  std::optional<double> laser_error_before, laser_error_after;  ///< x move error, mm
  std::optional<workflow::LinuxcncInstallResult> install;
  bool applied = false;          ///< the running LinuxCNC computes with the calibration
  std::vector<std::string> log;  ///< every line sent to LinuxCNC
  double seconds = 0.0;          ///< wall time of the routine
};

/// Asked after the fit, when request.install is false, with the result so far: true installs.
using ConfirmInstall = std::function<bool(const LiveCalibrationResult&)>;

/// Runs the routine on the LinuxCNC that `cnc` commands. Refuses (pkm::InvalidArgument) unless
/// LinuxCNC runs `request.ini`, is out of E-stop, on, homed and idle, in mm, without a tool
/// length offset. Progress: one event per station and stage; cancellation is checked before every
/// move (the commander aborts the motion when the routine ends early). Throws pkm::IoError for
/// LinuxCNC's refusals and errors (the message says which), workflow::Cancelled when cancelled,
/// and what the calibration throws.
[[nodiscard]] LiveCalibrationResult calibrateLive(const LiveCalibrationRequest& request,
                                                  LinuxcncCommander& cnc,
                                                  const workflow::RunControl& control = {},
                                                  const ConfirmInstall& confirm = {});

/// The routine's report for a terminal: the plan, each station, the calibration's summary
/// (workflow::hexapodCalibrationText), the held-out check, the x move before and after, what was
/// installed and applied, the commands sent and the wall time.
[[nodiscard]] std::string liveCalibrationText(const LiveCalibrationRequest& request,
                                              const LiveCalibrationResult& result);

}  // namespace pkm::live
