// A program on pkm's workflow library alone (it links pkm::workflow and nothing else): the jobs
// the `pkm` command runs, called as functions. It runs the built-in default campaign, then
// simulates the hexapod tracker measurement of seed004-hexapod-calibration and calibrates the
// hexapod from it, printing both summaries.
//
// Usage: workflow_example OUT_DIR     (OUT_DIR is created; nothing outside it is written)
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

#include "pkm/workflow/calibrate_hexapod.hpp"
#include "pkm/workflow/campaign.hpp"
#include "pkm/workflow/simulate.hpp"

namespace {

namespace fs = std::filesystem;
namespace wf = pkm::workflow;

/// The default campaign, its progress on standard error and its summary table on standard output.
bool runDefaultCampaign(const fs::path& out) {
  wf::CampaignOptions options;
  options.out = out / "campaign";
  options.force = true;
  wf::RunControl control;
  control.progress = [](const wf::ProgressEvent& e) {
    if (e.index > 0) std::fprintf(stderr, "  [%s] %s\n", e.stage.c_str(), e.message.c_str());
  };
  const wf::CampaignResult r = wf::runCampaign(options, control);
  std::printf("campaign '%s': %zu steps in %.1f s\n", r.name.c_str(), r.steps.size(), r.seconds);
  for (const wf::CampaignStepResult& step : r.steps)
    for (const wf::CampaignRow& row : step.rows)
      std::printf("  %-8s %-56s %10.4g -> %-10.4g %s %s\n",
                  step.id.c_str(),
                  row.quantity.c_str(),
                  row.before,
                  row.after,
                  row.unit.c_str(),
                  row.target ? (row.pass() ? "PASS" : "FAIL") : "");
  std::printf("  report: %s\n", r.report.string().c_str());
  return r.all_pass;
}

/// Simulated tracker files, then the hexapod calibration from them.
bool calibrateHexapod(const fs::path& out) {
  wf::SimulateOptions sim;
  sim.scenario = "seed004-hexapod-calibration";
  sim.out = out / "tracker";
  sim.force = true;
  const wf::SimulateResult files = wf::runSimulate(sim);
  std::printf("simulated %zu files of %s (seed %llu)\n",
              files.files.size(),
              files.scenario.c_str(),
              static_cast<unsigned long long>(files.seed));

  wf::HexapodCalibrationRequest request;
  request.machine = "hexapod-default";
  request.data = {pkm::io::readNamedText((sim.out / "tracker-pose.csv").string())};
  request.holdout = {pkm::io::readNamedText((sim.out / "tracker-holdout.csv").string())};
  // The tracker's readings of the table's nests: the calibrated machine in the table's frame.
  request.registration =
      pkm::io::readNamedText((sim.out / "tracker-pose-registration.csv").string());
  request.out = (out / "cal.json").string();
  request.force = true;
  const wf::HexapodCalibrationResult r = wf::calibrateHexapod(request);
  const pkm::io::HexapodCalibrationReport& rep = r.report;
  std::printf("calibrated %s: %d equations, %d of %d unknowns identifiable, %d iterations\n",
              rep.machine.c_str(),
              rep.equations,
              rep.fit.identifiability.rank,
              rep.fit.identifiability.parameters,
              rep.fit.iterations);
  std::printf("  fitted residual RMS %.4g -> %.4g %s\n",
              rep.fit.before.rms,
              rep.fit.after.rms,
              std::string(pkm::toString(rep.unit)).c_str());
  if (rep.holdout)
    std::printf("  held-out TCP error RMS %.4g -> %.4g (max %.4g -> %.4g)\n",
                rep.holdout->before.rms,
                rep.holdout->after.rms,
                rep.holdout->before.max,
                rep.holdout->after.max);
  std::printf("  wrote %s, %s, %s\n",
              rep.out_machine.c_str(),
              rep.out_hal.c_str(),
              rep.out_summary.c_str());
  return rep.holdout && rep.holdout->after.rms < rep.holdout->before.rms;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUT_DIR\n", argv[0]);
    return 2;
  }
  try {
    const fs::path out(argv[1]);
    fs::create_directories(out);
    const bool campaign_ok = runDefaultCampaign(out);
    const bool calibration_ok = calibrateHexapod(out);
    return campaign_ok && calibration_ok ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "workflow_example: error: %s\n", e.what());
    return 2;
  }
}
