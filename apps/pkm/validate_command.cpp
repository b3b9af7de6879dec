// `pkm validate coverage [--seeds N] [--scenario S...] [--out DIR]`: runs
// workflow::validateCoverage (docs/coverage.md) and prints its table; --check exits 1 when a
// quantity's coverage is below the acceptable.
#include <fmt/format.h>

#include <memory>

#include "cli_common.hpp"
#include "pkm/io/environment_file.hpp"
#include "pkm/io/uncertainty_sources.hpp"
#include "pkm/workflow/coverage.hpp"

namespace pkm::cli {
namespace {

struct CoverageArgs {
  workflow::CoverageOptions options;
  std::string environment;
  std::string uncertainty;
  std::string out;
  bool force = false;
  bool json = false;
  bool check = false;
};

void runCoverage(CoverageArgs& a) {
  if (!a.environment.empty()) {
    a.options.environment = io::loadEnvironment(a.environment);
    a.options.environment_source = a.environment;
  }
  if (!a.uncertainty.empty()) {
    a.options.uncertainty = io::readUncertaintySources(io::readNamedText(a.uncertainty));
    a.options.uncertainty_source = a.uncertainty;
  }
  CliRunControl control;
  const workflow::CoverageResult r = workflow::validateCoverage(a.options, control.control());
  control.finish();
  if (!a.out.empty()) workflow::writeCoverage(r, a.out, a.force);
  writeTextOutput("", a.json ? workflow::coverageJson(r) : workflow::coverageText(r));
  if (!a.out.empty() && !a.json)
    fmt::print("wrote coverage.json, report-data.json and report.html to {}\n", a.out);
  if (a.check && r.holding() < r.claims()) {
    std::fflush(stdout);
    fmt::print(stderr,
               "pkm: {} of {} quantities below the acceptable coverage\n",
               r.claims() - r.holding(),
               r.claims());
    throw ExitCode{kExitCheckFailed};
  }
}

void addValidate(CLI::App& app) {
  CLI::App* group = app.add_subcommand(
      "validate", "pkm's simulator proves pkm's own statements (docs/coverage.md)");
  group->require_subcommand(1);
  auto a = std::make_shared<CoverageArgs>();
  CLI::App* cmd = group->add_subcommand(
      "coverage",
      "every reported U against the simulator's truth over many seeds: coverage per quantity");
  cmd->add_option("--seeds", a->options.seeds, "seeds per scenario (>= 2)")->capture_default_str();
  cmd->add_option("--first-seed", a->options.first_seed, "the first seed")->capture_default_str();
  cmd->add_option("--scenario",
                  a->options.scenarios,
                  "scenario files or built-in names (default: seed000-parallelism, "
                  "seed001-diagonals, seed003-probe-offset)");
  cmd->add_option("--only",
                  a->options.only,
                  "only the quantities whose 'group quantity' contains one of these");
  cmd->add_option("--environment",
                  a->environment,
                  "the workshop of the measured runs: a preset (ideal, realistic) or an "
                  "environment file (default: each scenario's own)");
  cmd->add_option("--uncertainty",
                  a->uncertainty,
                  "instruments and environment of the budgets (JSON; default typical values)");
  cmd->add_option("--out,-o", a->out, "write coverage.json, report-data.json and report.html");
  cmd->add_flag("--force", a->force, "overwrite those files");
  cmd->add_flag("--json", a->json, "print coverage.json instead of the table");
  cmd->add_flag("--check", a->check, "exit 1 when a quantity is below the acceptable coverage");
  cmd->callback([a] { runCoverage(*a); });
}

const CommandRegistration kRegisterValidate{115, "validate", &addValidate};

}  // namespace
}  // namespace pkm::cli
