// `pkm calibrate hexapod --live`: the options of the automated calibration by constrained motion
// on a running LinuxCNC, the confirmation asked on a terminal, and its report
// (live::calibrateLive, live::liveCalibrationText; docs/linuxcnc.md).
#include "calibrate_live.hpp"

#include <unistd.h>

#include <cstdio>
#include <iostream>

#include "cli_common.hpp"
#include "pkm/core/error.hpp"
#include "pkm/live/live_calibration.hpp"

namespace pkm::cli {

void addCalibrateLiveOptions(CLI::App& hex, LiveCalibrateArgs& args) {
  hex.add_flag("--live",
               args.live,
               "measure on the running LinuxCNC of --ini by constrained motion: plan stations, "
               "drive it there by MDI, servo until the --gauges read zero, calibrate "
               "(--out is then a folder; docs/linuxcnc.md)");
  hex.add_option("--gauges", args.gauges, "--live: the three gauges' HAL pins (mm)")
      ->delimiter(',')
      ->expected(3);
  hex.add_option("--gauge-points",
                 args.gauge_points,
                 "--live: the gauge tips in the tool frame, x,y,z three times, mm (default: "
                 "pkm-truth's)")
      ->delimiter(',')
      ->expected(9);
  hex.add_option("--laser", args.request.laser, "--live: a laser's HAL pin along x, mm");
  hex.add_option("--laser-length", args.request.laser_length, "--live: the x move measured, mm");
  hex.add_option("--stations", args.request.stations.count, "--live: stations to fit with");
  hex.add_option(
      "--holdout-stations", args.request.stations.holdout, "--live: stations kept out of the fit");
  hex.add_option("--reach", args.request.stations.reach, "--live: largest |dx|, |dy| of a station");
  hex.add_option("--reference",
                 args.reference,
                 "--live: where the gauges are zeroed, x,y,z,a,b,c (default [TRAJ] HOME)")
      ->delimiter(',')
      ->expected(6);
  hex.add_option(
      "--approach", args.request.approach, "--live: every move comes from this far below, mm");
  hex.add_option("--tolerance", args.request.tolerance, "--live: gauges within this read zero, mm");
  hex.add_option("--settle",
                 args.request.settle_s,
                 "--live: seconds to wait after a move before reading the gauges (default 0.1)");
  hex.add_option("--gauge-samples",
                 args.request.gauge_samples,
                 "--live: reads of the gauges, 2 ms apart, averaged per reading (default 20)");
  hex.add_flag("--install",
               args.request.install,
               "--live: install the result, apply it to the running LinuxCNC and re-measure, "
               "without asking");
}

void runCalibrateLive(LiveCalibrateArgs& args, const workflow::HexapodCalibrationRequest& fit) {
  live::LiveCalibrationRequest& r = args.request;
  if (args.gauges.size() == 3) r.gauges = {args.gauges[0], args.gauges[1], args.gauges[2]};
  if (args.gauge_points.size() == 9)
    for (std::size_t k = 0; k < 3; ++k)
      r.gauge_points[k] = Eigen::Vector3d(
          args.gauge_points[3 * k], args.gauge_points[3 * k + 1], args.gauge_points[3 * k + 2]);
  if (args.reference.size() == 6)
    r.reference = std::array<double, 6>{args.reference[0],
                                        args.reference[1],
                                        args.reference[2],
                                        args.reference[3],
                                        args.reference[4],
                                        args.reference[5]};
  r.ini = fit.ini;
  r.out = fit.out;
  r.force = fit.force;
  if (fit.prior_sigma > 0.0) r.prior_sigma = fit.prior_sigma;
  if (fit.measurement_sigma > 0.0) r.measurement_sigma = fit.measurement_sigma;
  if (fit.prior_uncertainty > 0.0) r.prior_uncertainty = fit.prior_uncertainty;
  r.validate();
  live::CommanderOptions options;
  live::LinuxcncCommander cnc(options);
  live::ConfirmInstall ask;
  if (!r.install && ::isatty(0) && ::isatty(2))
    ask = [&r](const live::LiveCalibrationResult& so_far) {
      std::fprintf(stderr,
                   "Held-out gauge residuals %.4f mm -> %.4f mm. Install into %s, apply it to the "
                   "running LinuxCNC (machine off and on; nothing moves) and re-measure? [y/N] ",
                   so_far.holdout_rms_before,
                   so_far.holdout_rms_after,
                   r.ini.c_str());
      std::string answer;
      std::getline(std::cin, answer);
      return answer == "y" || answer == "Y" || answer == "yes";
    };
  CliRunControl run;
  const live::LiveCalibrationResult result = live::calibrateLive(r, cnc, run.control(), ask);
  run.finish();
  Output out;
  out.text() += live::liveCalibrationText(r, result);
}

}  // namespace pkm::cli
