// `pkm calibrate hexapod`: parses the arguments, runs workflow::calibrateHexapod (42 kinematic
// parameters from laser-tracker and dial-gauge files; docs/calibration.md) and prints its
// summary (workflow::hexapodCalibrationText).
#include <cstdio>

#include "analyze_common.hpp"
#include "calibrate_common.hpp"
#include "calibrate_live.hpp"
#include "cli_common.hpp"
#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/workflow/calibrate_hexapod.hpp"
#include "pkm/workflow/calibration_text.hpp"

namespace pkm::cli {
namespace {

/// `pkm calibrate hexapod`'s arguments: the shared ones and the --registration path.
struct HexapodCalibrateArgs : CalibrateArgs<workflow::HexapodCalibrationRequest> {
  std::string registration;  ///< --registration path
  LiveCalibrateArgs live;    ///< --live and its options
};

void runCalibrate(HexapodCalibrateArgs args) {
  if (args.live.live) {
    if (!args.data.empty() || !args.holdout.empty())
      throw InvalidArgument("--live measures its own data: leave out --data and --holdout");
    if (args.request.ini.empty()) throw InvalidArgument("--live needs --ini (the running INI)");
    runCalibrateLive(args.live, args.request);
    return;
  }
  if (args.data.empty()) throw InvalidArgument("--data is required (or --live)");
  fillCalibrateRequest(args);
  if (!args.registration.empty()) args.request.registration = io::readNamedText(args.registration);
  CliRunControl run;
  const workflow::HexapodCalibrationResult result =
      workflow::calibrateHexapod(args.request, run.control());
  run.finish();
  if (args.json) {
    std::fwrite(result.summary_json.data(), 1, result.summary_json.size(), stdout);
    std::fflush(stdout);
    return;
  }
  Output out;
  out.text() += workflow::hexapodCalibrationText(args.request, result);
}

/// Adds to `pkm calibrate hexapod` the machine, the data files, the frame and the fit's options.
void addCalibrateFitOptions(CLI::App& hex, HexapodCalibrateArgs& args) {
  addMachineOptions(hex, args.request.machine, args.request.ini);
  hex.add_option("--data", args.data, "calibration files (tracker pose/point, constrained motion)")
      ->check(CLI::ExistingFile);
  hex.add_option("--holdout", args.holdout, "tracker files kept out of the fit, for validation")
      ->check(CLI::ExistingFile);
  hex.add_option(
         "--out",
         args.request.out,
         "calibrated machine file CAL.json (also CAL.hal, CAL.pkmhexkins.hal, CAL.summary.json)")
      ->required();
  hex.add_option("--frame",
                 args.request.frame,
                 "where tracker readings are: auto (from the files' metadata), world, tracker")
      ->check(CLI::IsMember({"auto", "world", "tracker"}));
  hex.add_option(
         "--registration",
         args.registration,
         "the tracker's readings of the table's fiducial nests (pkm.tracker-registration/1): "
         "puts tracker-frame readings in the machine's world frame")
      ->check(CLI::ExistingFile);
  hex.add_option("--target-offset",
                 args.target_offset,
                 "the tracker target in the tool frame x,y,z (default: the files' smr offset)")
      ->delimiter(',')
      ->expected(3);
  hex.add_option("--fix", args.request.fix, "parameters held at their initial value (e.g. offset0)")
      ->delimiter(',');
  hex.add_option("--loss", args.request.loss, "robust loss: none, huber, cauchy")
      ->check(CLI::IsMember({"none", "huber", "cauchy"}));
  hex.add_option("--loss-scale", args.request.loss_scale, "robust loss scale, machine unit");
  hex.add_flag("--force", args.request.force, "overwrite existing output files");
  hex.add_flag(
      "--allow-large-changes",
      args.request.allow_large_changes,
      "write a result whose parameters moved implausibly far (docs/calibration.md, Guards)");
  hex.add_flag("--json", args.json, "print the summary as JSON");
}

/// Adds to `pkm calibrate hexapod` the Monte Carlo, prior, uncertainty and backlash options.
void addCalibrateNoiseOptions(CLI::App& hex, HexapodCalibrateArgs& args) {
  hex.add_option("--monte-carlo",
                 args.request.monte_carlo,
                 "also run N Monte Carlo trials of the calibration under simulated noise")
      ->check(CLI::Range(2, 100000));
  hex.add_option("--sigma-position",
                 args.request.sigma_position,
                 "Monte Carlo: position noise, machine unit (default: the fitted residual sigma)");
  hex.add_option("--sigma-orientation",
                 args.request.sigma_orientation_urad,
                 "Monte Carlo: 6-DOF orientation noise, urad (default 0)");
  hex.add_option(
      "--sigma-gauge",
      args.request.sigma_gauge,
      "Monte Carlo: dial-gauge noise, machine unit (default: the fitted residual sigma)");
  hex.add_option(
      "--threads",
      args.request.threads,
      "worker threads of the Monte Carlo trials and of the workspace sampling beside the fit "
      "(default: all cores)");
  hex.add_option(
      "--db", args.request.db, "also record the calibration in this result store (pkm.db)");
  hex.add_option("--prior-sigma",
                 args.request.prior_sigma,
                 "regularise toward the machine file: how far the true geometry may plausibly be, "
                 "machine unit (needs --measurement-sigma; for dial-gauge data)");
  hex.add_option(
      "--prior-uncertainty",
      args.request.prior_uncertainty,
      "the machine file's geometry as an input of the uncertainty budgets: one "
      "standard deviation per parameter, machine unit (default --prior-sigma; needs it)");
  hex.add_option("--measurement-sigma",
                 args.request.measurement_sigma,
                 "residual sigma, machine unit, for --prior-sigma and the covariance (default: "
                 "estimated from the residuals)");
  args.uncertainty.add(hex);
  hex.add_option("--uncertainty-trials",
                 args.request.uncertainty_trials,
                 "also propagate the budgets by Monte Carlo (GUM S1): re-fits on perturbed "
                 "observations, adaptive, at most N (>= 20)")
      ->check(CLI::Range(20, 100000));
  hex.add_flag("--backlash",
               args.request.backlash,
               "also estimate a per-strut backlash; approach directions follow from the row order "
               "of each file (one continuous sequence of moves per file)");
}

}  // namespace

void addCalibrateCommand(CLI::App& app) {
  CLI::App* calibrate =
      app.add_subcommand("calibrate", "identify kinematic parameters from measurements");
  calibrate->require_subcommand(1);
  auto args = std::make_shared<HexapodCalibrateArgs>();
  CLI::App* hex = calibrate->add_subcommand(
      "hexapod", "calibrate a hexapod from laser-tracker pose/point files and dial-gauge files");
  addCalibrateFitOptions(*hex, *args);
  addCalibrateNoiseOptions(*hex, *args);
  addCalibrateLiveOptions(*hex, args->live);
  hex->callback([args] { runCalibrate(*args); });
  addCalibrateExechon(*calibrate);
}

}  // namespace pkm::cli
