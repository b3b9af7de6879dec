// `pkm simulate SCENARIO --out DIR [--seed N] [--force]` and `pkm simulate --list`: runs
// workflow::runSimulate (docs/formats.md, "Measurement files", "Scenario files") and prints what
// it wrote.
#include <fmt/format.h>

#include <memory>
#include <optional>

#include "cli_common.hpp"
#include "pkm/workflow/simulate.hpp"

namespace pkm::cli {

namespace {

struct SimulateState {
  workflow::SimulateOptions options;
  std::string out;
  bool list = false;
};

void runSimulate(SimulateState st) {
  if (st.list) {
    Output out;
    for (const workflow::ScenarioInfo& s : workflow::listScenarios())
      out.text() += fmt::format("{}\t{} measurements\t{}\n", s.name, s.measurements, s.description);
    return;
  }
  st.options.out = st.out;
  const workflow::SimulateResult r = workflow::runSimulate(st.options);
  fmt::print("pkm: wrote {} files to {}\n", r.files.size(), st.out);
}

}  // namespace

void addSimulateCommand(CLI::App& app) {
  auto st = std::make_shared<SimulateState>();
  CLI::App* cmd = app.add_subcommand(
      "simulate",
      "simulated measurement campaign on a virtual machine with known errors (docs/formats.md)");
  cmd->add_option(
      "scenario", st->options.scenario, "scenario JSON file or built-in name (see --list)");
  cmd->add_option(
      "--out,-o", st->out, "directory for the measurement files, truth.json and scenario.json");
  cmd->add_option("--seed", st->options.seed, "random seed (default: the scenario's \"seed\")");
  cmd->add_flag("--force", st->options.force, "overwrite existing files in DIR");
  cmd->add_flag("--list", st->list, "list the built-in scenarios");
  cmd->callback([st] { runSimulate(*st); });
}

}  // namespace pkm::cli
