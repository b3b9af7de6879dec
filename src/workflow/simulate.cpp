// `pkm simulate` as a workflow (workflow/simulate.hpp).
#include "pkm/workflow/simulate.hpp"

#include <fmt/format.h>

#include "pkm/core/error.hpp"
#include "pkm/io/atomic_file.hpp"
#include "pkm/io/exechon_tracker_files.hpp"
#include "pkm/io/measurement_files.hpp"
#include "pkm/io/probe_files.hpp"
#include "pkm/io/registration_files.hpp"
#include "pkm/io/scenario.hpp"
#include "pkm/io/simulation_metadata.hpp"
#include "pkm/io/tracker_files.hpp"

namespace pkm::workflow {

namespace fs = std::filesystem;
namespace sim = pkm::simulation;

namespace {

/// The laser-tracker files of every kind (hexapod, hybrid, Exechon).
void addTrackerFiles(const io::Scenario& scenario,
                     std::uint64_t seed,
                     std::vector<SimulatedFile>& files) {
  const sim::Campaign& c = scenario.campaign;
  for (const sim::TrackerResult& r : sim::runLaserTrackers(c, seed)) {
    files.push_back({fmt::format("{}.csv", r.setup->name),
                     io::trackerCsv(io::trackerMetadata(c.name, seed, *r.setup, r.readings.size()),
                                    r.setup->mode,
                                    r.readings)});
    // A placed tracker also reads the table's fiducial nests (its own stream, so the readings
    // above do not depend on it): the references that register its frame.
    if (!r.setup->placed() || r.setup->registration_nests.empty()) continue;
    sim::RandomStream rng(seed, r.setup->name + "-registration");
    files.push_back({fmt::format("{}-registration.csv", r.setup->name),
                     io::registrationCsv(io::registrationMetadata(c.name, seed, *r.setup),
                                         sim::simulateTrackerRegistration(*r.setup, rng))});
  }
  for (const sim::HybridTrackerResult& r : sim::runHybridTrackers(c, seed))
    files.push_back(
        {fmt::format("{}.csv", r.setup->name),
         io::hybridTrackerCsv(io::hybridTrackerMetadata(c.name, seed, *r.setup, r.readings.size()),
                              r.readings)});
  for (const sim::ExechonTrackerResult& r : sim::runExechonTrackers(c, seed))
    files.push_back(
        {fmt::format("{}.csv", r.setup->name),
         io::exechonTrackerCsv(
             io::exechonTrackerMetadata(c.name, seed, *r.setup, r.readings.size()), r.readings)});
}

}  // namespace

void SimulateOptions::validate() const {
  if (scenario.empty()) throw IoError("give a SCENARIO (a file or a built-in name; see --list)");
  if (out.empty()) throw IoError("give --out DIR");
}

std::vector<ScenarioInfo> listScenarios() {
  std::vector<ScenarioInfo> out;
  for (const std::string& name : io::builtinScenarioNames()) {
    const io::Scenario s = io::loadScenario(name);
    const sim::Campaign& c = s.campaign;
    out.push_back({name,
                   c.measurements.size() + c.constrained.size() + c.trackers.size() +
                       c.probes.size() + c.exechon_trackers.size() + c.hybrid_trackers.size(),
                   c.description});
  }
  return out;
}

namespace {

/// Every measurement of `scenario` simulated with `seed_option` (default: the scenario's seed).
SimulateResult simulate(const io::Scenario& scenario, std::optional<std::uint64_t> seed_option) {
  SimulateResult result;
  result.scenario = scenario.campaign.name;
  const std::uint64_t seed = result.seed = seed_option.value_or(scenario.seed);
  {
    // The machine's unmodelled geometry is drawn from the seed used (the machine is shared).
    sim::Campaign campaign = scenario.campaign;
    sim::applyGeometryEnvironment(campaign, seed);
  }
  std::vector<SimulatedFile>& files = result.files;
  for (const sim::MeasurementResult& r : sim::runCampaign(scenario.campaign, seed))
    for (const sim::LineRun& run : r.runs)
      files.push_back(
          {fmt::format("{}_run{}.csv", r.setup->name, run.run),
           io::lineRunCsv(r.setup->quantity,
                          io::lineRunMetadata(scenario, seed, *r.setup, run.run, r.runs),
                          run)});
  for (const sim::ConstrainedResult& r : sim::runConstrainedMotion(scenario.campaign, seed))
    files.push_back(
        {fmt::format("{}.csv", r.setup->name),
         io::dialGaugeCsv(io::dialGaugeMetadata(scenario, seed, *r.setup), r.stations)});
  addTrackerFiles(scenario, seed, files);
  for (const sim::TouchProbeRun& r : sim::runTouchProbes(scenario.campaign.probes, seed))
    for (auto& [name, text] : io::touchProbeFiles(scenario.campaign.name, seed, *r.setup, r.result))
      files.push_back({std::move(name), std::move(text)});
  files.push_back({"truth.json", io::truthJson(scenario, seed)});
  files.push_back({"scenario.json", io::scenarioJsonWithSeed(scenario, seed)});
  return result;
}

}  // namespace

SimulateResult simulateScenario(const std::string& spec, std::optional<std::uint64_t> seed_option) {
  return simulate(io::loadScenario(spec), seed_option);
}

SimulateResult simulateLoadedScenario(const io::Scenario& scenario, std::uint64_t seed) {
  return simulate(scenario, seed);
}

SimulateResult simulateScenarioText(const io::NamedText& scenario,
                                    std::optional<std::uint64_t> seed,
                                    const std::string& base_dir) {
  return simulate(io::parseScenarioJson(scenario.text, scenario.name, base_dir), seed);
}

void writeSimulation(const SimulateResult& result, const fs::path& dir, bool force) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir))
    throw IoError(fmt::format("{}: cannot create the directory", dir.string()));
  if (!force)
    for (const SimulatedFile& f : result.files)
      if (fs::exists(dir / f.name, ec))
        throw IoError(fmt::format("{}: exists; refusing to overwrite (use --force)",
                                  (dir / f.name).string()));
  for (const SimulatedFile& f : result.files)
    io::writeFileAtomic(dir / f.name, f.text, io::Overwrite::kAllow);
}

SimulateResult runSimulate(const SimulateOptions& options) {
  options.validate();
  // Simulate first, then check and write, so nothing is written for a failing scenario.
  SimulateResult result = simulateScenario(options.scenario, options.seed);
  writeSimulation(result, options.out, options.force);
  return result;
}

}  // namespace pkm::workflow
