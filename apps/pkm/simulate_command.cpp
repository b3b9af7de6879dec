// `pkm simulate SCENARIO --out DIR [--seed N] [--force]` and `pkm simulate --list`: a simulated
// measurement campaign with known truth (docs/formats.md, "Measurement files", "Scenario files").
#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>

#include "campaign.hpp"
#include "cli_common.hpp"
#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/io/exechon_tracker_files.hpp"
#include "pkm/io/measurement_files.hpp"
#include "pkm/io/number_format.hpp"
#include "pkm/io/probe_files.hpp"
#include "pkm/io/scenario.hpp"
#include "pkm/io/tracker_files.hpp"

namespace pkm::cli {

namespace fs = std::filesystem;
namespace sim = pkm::simulation;

namespace {

struct SimulateState {
  std::string scenario, out;
  std::optional<std::uint64_t> seed;
  bool list = false;
  bool force = false;
};

std::string vectorText(const Eigen::VectorXd& v) {
  std::string out = "(";
  for (Eigen::Index i = 0; i < v.size(); ++i) out += (i ? ", " : "") + io::formatNumber(v[i]);
  return out + ")";
}

/// A command with its angular axes in degrees.
std::string commandText(const Eigen::VectorXd& v, const std::vector<bool>& angular) {
  Eigen::VectorXd w = v;
  for (Eigen::Index i = 0; i < w.size(); ++i)
    if (angular[static_cast<std::size_t>(i)]) w[i] = radToDeg(w[i]);
  return vectorText(w);
}

const char* instrumentName(sim::LineQuantity q) {
  switch (q) {
    case sim::LineQuantity::kLinear:
      return "laser interferometer, linear optics (simulated)";
    case sim::LineQuantity::kStraightness:
      return "laser interferometer, straightness optics (simulated)";
    case sim::LineQuantity::kAngular:
      return "laser interferometer, angular optics (simulated)";
  }
  return "?";
}

}  // namespace

io::Metadata lineRunMetadata(const io::Scenario& s,
                             std::uint64_t seed,
                             const sim::LineSetup& m,
                             int run) {
  const std::vector<std::string> axes = s.campaign.machine->axisNames();
  const std::vector<bool> angular_axes = s.campaign.machine->angularAxes();
  const bool angular = m.quantity == sim::LineQuantity::kAngular;
  const char* unit = angular ? "urad" : "mm";
  const double scale = angular ? 1e6 : 1.0;
  io::Metadata md = {
      {"format", "pkm.measurement/1"},
      {"scenario", s.campaign.name},
      {"seed", std::to_string(seed)},
      {"measurement", m.name},
      {"quantity", sim::toString(m.quantity)},
      {"instrument", instrumentName(m.quantity)},
      {"procedure", sim::toString(m.procedure)},
      {"run", fmt::format("{} of {}", run, m.cycle.runs)},
      {"axes", fmt::format("{}", fmt::join(axes, ","))},
      {"line start", commandText(m.line.start, angular_axes)},
      {"line direction", commandText(m.line.direction, angular_axes)},
      {"reflector offset mm", vectorText(m.reflector_offset)},
      {"noise",
       fmt::format("sigma {} {}, {} ppm, resolution {} {}",
                   io::formatNumber(m.noise.sigma * scale),
                   unit,
                   io::formatNumber(m.noise.sigma_ppm),
                   io::formatNumber(m.noise.resolution * scale),
                   unit)},
  };
  if (m.quantity != sim::LineQuantity::kLinear) md.emplace_back("lateral", vectorText(m.lateral));
  if (m.quantity == sim::LineQuantity::kStraightness)
    md.emplace_back("misalignment urad", io::formatNumber(m.misalignment * 1e6));
  return md;
}

namespace {

std::string pointsText(const std::array<Eigen::Vector3d, 3>& points) {
  std::string out;
  for (const Eigen::Vector3d& p : points) out += (out.empty() ? "" : ", ") + vectorText(p);
  return out;
}

io::Metadata dialGaugeMetadata(const io::Scenario& s,
                               std::uint64_t seed,
                               const sim::DialGaugeSetup& d) {
  return {
      {"format", "pkm.constrained-motion/1"},
      {"scenario", s.campaign.name},
      {"seed", std::to_string(seed)},
      {"measurement", d.name},
      {"instrument", "three dial gauges on the platform, tips on the table (simulated)"},
      {"gauge points mm", pointsText(d.gauge_points)},
      {"table normal", vectorText(d.table_normal)},
      {"tolerance mm", io::formatNumber(d.tolerance)},
      {"noise",
       fmt::format("sigma {} mm, resolution {} mm",
                   io::formatNumber(d.noise.sigma),
                   io::formatNumber(d.noise.resolution))},
  };
}

void writeFile(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out) throw IoError(fmt::format("{}: cannot write the file", path.string()));
}

void runSimulate(const SimulateState& st) {
  if (st.list) {
    Output out;
    for (const std::string& name : io::builtinScenarioNames()) {
      const io::Scenario s = io::loadScenario(name);
      out.text() +=
          fmt::format("{}\t{} measurements\t{}\n",
                      name,
                      s.campaign.measurements.size() + s.campaign.constrained.size() +
                          s.campaign.trackers.size() + s.campaign.probes.size() +
                          s.campaign.exechon_trackers.size() + s.campaign.hybrid_trackers.size(),
                      s.campaign.description);
    }
    return;
  }
  if (st.scenario.empty()) throw IoError("give a SCENARIO (a file or a built-in name; see --list)");
  if (st.out.empty()) throw IoError("give --out DIR");
  const io::Scenario scenario = io::loadScenario(st.scenario);
  const std::uint64_t seed = st.seed.value_or(scenario.seed);
  // Simulate first, then check and write, so nothing is written for a failing scenario.
  std::vector<std::pair<std::string, std::string>> files;
  for (const sim::MeasurementResult& r : sim::runCampaign(scenario.campaign, seed))
    for (const sim::LineRun& run : r.runs)
      files.emplace_back(
          fmt::format("{}_run{}.csv", r.setup->name, run.run),
          io::lineRunCsv(
              r.setup->quantity, lineRunMetadata(scenario, seed, *r.setup, run.run), run));
  for (const sim::ConstrainedResult& r : sim::runConstrainedMotion(scenario.campaign, seed))
    files.emplace_back(fmt::format("{}.csv", r.setup->name),
                       io::dialGaugeCsv(dialGaugeMetadata(scenario, seed, *r.setup), r.stations));
  for (const sim::TrackerResult& r : sim::runLaserTrackers(scenario.campaign, seed))
    files.emplace_back(
        fmt::format("{}.csv", r.setup->name),
        io::trackerCsv(
            io::trackerMetadata(scenario.campaign.name, seed, *r.setup, r.readings.size()),
            r.setup->mode,
            r.readings));
  for (const sim::HybridTrackerResult& r : sim::runHybridTrackers(scenario.campaign, seed))
    files.emplace_back(
        fmt::format("{}.csv", r.setup->name),
        io::hybridTrackerCsv(
            io::hybridTrackerMetadata(scenario.campaign.name, seed, *r.setup, r.readings.size()),
            r.readings));
  for (const sim::ExechonTrackerResult& r : sim::runExechonTrackers(scenario.campaign, seed))
    files.emplace_back(
        fmt::format("{}.csv", r.setup->name),
        io::exechonTrackerCsv(
            io::exechonTrackerMetadata(scenario.campaign.name, seed, *r.setup, r.readings.size()),
            r.readings));
  for (const sim::TouchProbeRun& r : sim::runTouchProbes(scenario.campaign.probes, seed))
    for (auto& file : io::touchProbeFiles(scenario.campaign.name, seed, *r.setup, r.result))
      files.push_back(std::move(file));
  files.emplace_back("truth.json", io::truthJson(scenario, seed));
  files.emplace_back("scenario.json", io::scenarioJsonWithSeed(scenario, seed));
  const fs::path dir(st.out);
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir))
    throw IoError(fmt::format("{}: cannot create the directory", st.out));
  if (!st.force)
    for (const auto& [name, text] : files)
      if (fs::exists(dir / name, ec))
        throw IoError(
            fmt::format("{}: exists; refusing to overwrite (use --force)", (dir / name).string()));
  for (const auto& [name, text] : files) writeFile(dir / name, text);
  fmt::print("pkm: wrote {} files to {}\n", files.size(), st.out);
}

}  // namespace

void addSimulateCommand(CLI::App& app) {
  auto st = std::make_shared<SimulateState>();
  CLI::App* cmd = app.add_subcommand(
      "simulate",
      "simulated measurement campaign on a virtual machine with known errors (docs/formats.md)");
  cmd->add_option("scenario", st->scenario, "scenario JSON file or built-in name (see --list)");
  cmd->add_option(
      "--out,-o", st->out, "directory for the measurement files, truth.json and scenario.json");
  cmd->add_option("--seed", st->seed, "random seed (default: the scenario's \"seed\")");
  cmd->add_flag("--force", st->force, "overwrite existing files in DIR");
  cmd->add_flag("--list", st->list, "list the built-in scenarios");
  cmd->callback([st] { runSimulate(*st); });
}

}  // namespace pkm::cli
