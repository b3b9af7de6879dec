// `pkm calibrate exechon`: parses the arguments, runs workflow::calibrateExechon (26 kinematic
// parameters of an Exechon and the hybrid machine's squareness from laser-tracker files;
// docs/calibration.md, "Exechon") and prints its summary (workflow::exechonCalibrationText).
#include "pkm/workflow/calibrate_exechon.hpp"

#include <cstdio>

#include "analyze_common.hpp"
#include "calibrate_common.hpp"
#include "cli_common.hpp"
#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/workflow/calibration_text.hpp"

namespace pkm::cli {
namespace {

using ExechonArgs = CalibrateArgs<workflow::ExechonCalibrationRequest>;

void runExechon(ExechonArgs args) {
  fillCalibrateRequest(args);
  CliRunControl run;
  const workflow::ExechonCalibrationResult r =
      workflow::calibrateExechon(args.request, run.control());
  run.finish();
  if (args.json) {
    std::fwrite(r.summary_json.data(), 1, r.summary_json.size(), stdout);
    std::fflush(stdout);
    return;
  }
  Output out;
  out.text() += workflow::exechonCalibrationText(r);
}

}  // namespace

void addCalibrateExechon(CLI::App& calibrate) {
  auto args = std::make_shared<ExechonArgs>();
  CLI::App* ex = calibrate.add_subcommand(
      "exechon", "calibrate an Exechon (tripod and wrist) from laser-tracker files");
  ex->add_option("--machine", args->request.machine, "Exechon machine file or built-in name")
      ->capture_default_str();
  ex->add_option("--data",
                 args->data,
                 "Exechon tracker files (q1,q2,q3,c,a,x,y,z[,i,j,k]) and hybrid tracker files "
                 "(x2,y2,xp,yp,zp,x,y,z)")
      ->required()
      ->check(CLI::ExistingFile);
  ex->add_option("--holdout", args->holdout, "tracker files kept out of the fit, for validation")
      ->check(CLI::ExistingFile);
  ex->add_option(
        "--out", args->request.out, "calibrated machine file CAL.json (also CAL.summary.json)")
      ->required();
  ex->add_option("--frame",
                 args->request.frame,
                 "where tracker readings are: auto (from the files' metadata), world, tracker")
      ->check(CLI::IsMember({"auto", "world", "tracker"}));
  ex->add_option("--target-offset",
                 args->target_offset,
                 "the tracker target in the tool frame x,y,z (default: the files' smr offset)")
      ->delimiter(',')
      ->expected(3);
  ex->add_option(
        "--fix", args->request.fix, "parameters held at their initial value (e.g. tripod.hx)")
      ->delimiter(',');
  ex->add_option("--loss", args->request.loss, "robust loss: none, huber, cauchy")
      ->check(CLI::IsMember({"none", "huber", "cauchy"}));
  ex->add_option("--loss-scale", args->request.loss_scale, "robust loss scale, machine unit");
  ex->add_option("--errors",
                 args->request.errors,
                 "hybrid machines: the known geometric errors (PDGE tables; file or built-in) "
                 "under the squareness fit")
      ->capture_default_str();
  ex->add_option(
      "--db", args->request.db, "also record the calibration in this result store (pkm.db)");
  ex->add_option("--monte-carlo",
                 args->request.monte_carlo,
                 "also run N Monte Carlo trials of the tripod calibration under simulated noise")
      ->check(CLI::Range(2, 100000));
  ex->add_option(
      "--sigma-position",
      args->request.sigma_position,
      "Monte Carlo: tracker point noise, machine unit (default: the fitted residual sigma)");
  ex->add_option("--sigma-orientation",
                 args->request.sigma_orientation_urad,
                 "Monte Carlo: tool-direction noise, urad (default 0)");
  ex->add_option(
      "--threads", args->request.threads, "Monte Carlo worker threads (default: all cores)");
  args->uncertainty.add(*ex);
  ex->add_option("--uncertainty-trials",
                 args->request.uncertainty_trials,
                 "also propagate the budgets by Monte Carlo (GUM S1): re-fits on perturbed "
                 "points, adaptive, at most N (>= 20)")
      ->check(CLI::Range(20, 100000));
  ex->add_flag("--force", args->request.force, "overwrite existing output files");
  ex->add_flag(
      "--allow-large-changes",
      args->request.allow_large_changes,
      "write a result whose parameters moved implausibly far (docs/calibration.md, Guards)");
  ex->add_flag("--json", args->json, "print the summary as JSON");
  ex->callback([args] { runExechon(*args); });
}

}  // namespace pkm::cli
