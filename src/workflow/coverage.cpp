// `pkm validate coverage` as a workflow (workflow/coverage.hpp): the runs and the statistics.
#include "pkm/workflow/coverage.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <tuple>

#include "coverage_analyses.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/scenario.hpp"
#include "pkm/simulation/campaign.hpp"
#include "pkm/workflow/simulate.hpp"

namespace pkm::workflow {
namespace {

namespace sim = pkm::simulation;

/// The 95 % the budgets claim.
constexpr double kClaimedCoverage = 0.95;
/// A U wider than this multiple of the observed RMS error covers by width (issue's criterion).
constexpr double kWideFactor = 3.0;

double mean(const std::vector<double>& v) {
  double s = 0.0;
  for (const double x : v) s += x;
  return v.empty() ? std::nan("") : s / static_cast<double>(v.size());
}

/// The scenario of the measured runs: its own environment or `environment` applied.
io::Scenario measuredScenario(const std::string& spec,
                              const std::optional<sim::Environment>& environment) {
  io::Scenario s = io::loadScenario(spec);
  if (environment) {
    s.campaign.environment = *environment;
    sim::applyProbeEnvironment(s.campaign);
    sim::applyMachineEnvironment(s.campaign);
  }
  return s;
}

/// The perfect-instrument twin of `measured`: the same machine (shared, with its geometry and
/// compliance) in the same thermal and structural state (every random stream stays aligned:
/// NoiseModel::perfect, TrackerNoise::perfect and Environment::perfect_instrument draw as the
/// measured run does), every instrument perfect (laser, dial gauges, trackers, probes), the probes
/// without lobing and the ring round and at 20 °C.
io::Scenario perfectTwin(const io::Scenario& measured) {
  io::Scenario t = measured;
  for (sim::LineSetup& m : t.campaign.measurements) m.noise.perfect = true;
  for (sim::DialGaugeSetup& g : t.campaign.constrained) g.noise.perfect = true;
  for (sim::TrackerSetup& k : t.campaign.trackers) k.noise.perfect = true;
  for (sim::ExechonTrackerSetup& k : t.campaign.exechon_trackers) k.noise.perfect = true;
  for (sim::HybridTrackerSetup& k : t.campaign.hybrid_trackers) k.noise.perfect = true;
  for (sim::TouchProbeSetup& p : t.campaign.probes) {
    p.noise.perfect = true;
    p.lobing = 0.0;
    p.ring_expansion = 0.0;
    p.ring_form = 0.0;  // the master ring is part of the standard: a perfect one
  }
  t.campaign.environment.perfect_instrument = true;
  return t;
}

using Key = std::tuple<std::string, std::string>;  // group, quantity

/// Adds one seed's readings of one scenario to `quantities` (index `slot` by scenario, group and
/// quantity, in first-seen order).
void addSeed(const std::string& scenario,
             std::uint64_t seed,
             const std::vector<detail::CoverageReading>& measured,
             const std::vector<detail::CoverageReading>& truth,
             const std::vector<detail::CoverageReading>& injected,
             std::map<Key, std::size_t>& slot,
             std::vector<CoverageQuantity>& quantities) {
  std::map<Key, double> truth_of;
  for (const detail::CoverageReading& t : truth) truth_of[{t.group, t.quantity}] = t.value;
  // A quantity measured at several places per seed (the TCP at each held-out pose) adds a trial
  // per place; a reading with its own truth compares with the virtual machine's true value.
  const auto add = [&](const detail::CoverageReading& m, double t, const std::string& kind) {
    const std::string name = kind == "injected" ? m.quantity + " vs injected" : m.quantity;
    const Key key{m.group, name};
    auto [it, fresh] = slot.try_emplace(key, quantities.size());
    if (fresh) quantities.push_back({scenario, m.group, name, m.unit, kind, {}});
    quantities[it->second].trials.push_back({seed, m.value, t, m.U, m.u_c, m.k});
  };
  for (const detail::CoverageReading& m : measured) {
    if (m.truth) {
      add(m, *m.truth, "true geometry");
      continue;
    }
    const auto t = truth_of.find({m.group, m.quantity});
    if (t == truth_of.end())
      throw InvalidArgument(fmt::format("{} seed {}: {} {} has no perfect-instrument value",
                                        scenario,
                                        seed,
                                        m.group,
                                        m.quantity));
    add(m, t->second, "perfect instrument");
    for (const detail::CoverageReading& i : injected)
      if (i.group == m.group && i.quantity == m.quantity) add(m, i.value, "injected");
  }
}

bool selected(const std::vector<std::string>& only, const detail::CoverageReading& r) {
  if (only.empty()) return true;
  const std::string name = r.group + " " + r.quantity;
  return std::any_of(only.begin(), only.end(), [&](const std::string& s) {
    return name.find(s) != std::string::npos;
  });
}

}  // namespace

std::vector<std::string> defaultCoverageScenarios() {
  return {"seed000-parallelism",
          "seed001-diagonals",
          "seed003-probe-offset",
          "seed003-probe-uncalibrated",
          "seed004-hexapod-calibration",
          "exechon-calibration"};
}

void CoverageOptions::validate() const {
  if (seeds < 2) throw InvalidArgument(fmt::format("--seeds must be at least 2, got {}", seeds));
  std::string why;
  if (!uncertainty.isValid(&why)) throw InvalidArgument("uncertainty sources: " + why);
  if (environment && !environment->isValid(&why)) throw InvalidArgument("environment: " + why);
}

bool CoverageTrial::covered() const { return std::abs(value - truth) <= U; }

double CoverageQuantity::coverage() const {
  if (trials.empty()) return std::nan("");
  const auto n = std::count_if(
      trials.begin(), trials.end(), [](const CoverageTrial& t) { return t.covered(); });
  return static_cast<double>(n) / static_cast<double>(trials.size());
}

double CoverageQuantity::bias() const {
  std::vector<double> e;
  for (const CoverageTrial& t : trials) e.push_back(t.value - t.truth);
  return mean(e);
}

double CoverageQuantity::errorRms() const {
  std::vector<double> e;
  for (const CoverageTrial& t : trials) e.push_back((t.value - t.truth) * (t.value - t.truth));
  return std::sqrt(mean(e));
}

double CoverageQuantity::meanU() const {
  std::vector<double> u;
  for (const CoverageTrial& t : trials) u.push_back(t.U);
  return mean(u);
}

double CoverageQuantity::meanZ() const {
  std::vector<double> z;
  for (const CoverageTrial& t : trials)
    if (t.u_c > 0.0) z.push_back((t.value - t.truth) / t.u_c);
  return mean(z);
}

double CoverageQuantity::spreadZ() const {
  std::vector<double> z;
  for (const CoverageTrial& t : trials)
    if (t.u_c > 0.0) z.push_back((t.value - t.truth) / t.u_c);
  if (z.size() < 2) return std::nan("");
  const double m = mean(z);
  double s = 0.0;
  for (const double x : z) s += (x - m) * (x - m);
  return std::sqrt(s / static_cast<double>(z.size() - 1));
}

double CoverageQuantity::acceptableCoverage() const {
  const double n = static_cast<double>(std::max<std::size_t>(trials.size(), 1));
  return kClaimedCoverage - 2.0 * std::sqrt(kClaimedCoverage * (1.0 - kClaimedCoverage) / n);
}

bool CoverageQuantity::holds() const { return coverage() >= acceptableCoverage(); }

bool CoverageQuantity::wide() const {
  const double rms = errorRms();
  return rms > 0.0 && meanU() > kWideFactor * rms;
}

bool CoverageQuantity::claimed() const { return truth_kind != "injected"; }

std::size_t CoverageResult::holding() const {
  return static_cast<std::size_t>(
      std::count_if(quantities.begin(), quantities.end(), [](const CoverageQuantity& q) {
        return q.claimed() && q.holds();
      }));
}

std::size_t CoverageResult::claims() const {
  return static_cast<std::size_t>(std::count_if(
      quantities.begin(), quantities.end(), [](const CoverageQuantity& q) { return q.claimed(); }));
}

CoverageResult validateCoverage(const CoverageOptions& options, const RunControl& control) {
  options.validate();
  const auto start = std::chrono::steady_clock::now();
  CoverageResult result;
  result.seeds = options.seeds;
  result.first_seed = options.first_seed;
  result.scenarios = options.scenarios.empty() ? defaultCoverageScenarios() : options.scenarios;
  result.environment = options.environment_source;
  result.uncertainty = options.uncertainty_source;
  for (const std::string& spec : result.scenarios) {
    const io::Scenario measured = measuredScenario(spec, options.environment);
    const io::Scenario truth = perfectTwin(measured);
    std::map<Key, std::size_t> slot;
    std::vector<CoverageQuantity> quantities;
    for (int k = 0; k < options.seeds; ++k) {
      const std::uint64_t seed = options.first_seed + static_cast<std::uint64_t>(k);
      control.report(
          {measured.campaign.name,
           static_cast<std::size_t>(k + 1),
           static_cast<std::size_t>(options.seeds),
           std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
           fmt::format("seed {}", seed)});
      control.checkCancelled();
      const SimulateResult simulation = simulateLoadedScenario(measured, seed);
      std::vector<detail::CoverageReading> m =
          detail::coverageReadings(measured, simulation, options.uncertainty);
      for (detail::CoverageReading& r :
           detail::calibrationReadings(measured, simulation, options.uncertainty))
        m.push_back(std::move(r));
      std::erase_if(m,
                    [&](const detail::CoverageReading& r) { return !selected(options.only, r); });
      const std::vector<detail::CoverageReading> t =
          detail::coverageReadings(truth, simulateLoadedScenario(truth, seed), options.uncertainty);
      std::vector<detail::CoverageReading> injected;
      for (const char* group : {"body diagonals", "step diagonals", "shifted diagonals"})
        for (const detail::CoverageReading& r : detail::injectedSquareness(measured, group))
          injected.push_back(r);
      addSeed(measured.campaign.name, seed, m, t, injected, slot, quantities);
    }
    result.quantities.insert(result.quantities.end(), quantities.begin(), quantities.end());
  }
  if (result.quantities.empty())
    throw InvalidArgument(fmt::format(
        "--only {}: no 'group quantity' of the scenarios contains it (e.g. 'linear-x E', "
        "'body diagonals squareness_xy'; the table's first columns list them)",
        fmt::join(options.only, ", ")));
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace pkm::workflow
