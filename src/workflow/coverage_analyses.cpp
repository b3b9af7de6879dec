// The analyses of `pkm validate coverage` (coverage_analyses.hpp).
#include "coverage_analyses.hpp"

#include <fmt/format.h>

#include <map>
#include <memory>
#include <utility>

#include "pkm/core/error.hpp"
#include "pkm/simulation/cartesian_machine.hpp"
#include "pkm/simulation/touch_probe.hpp"
#include "pkm/workflow/analyze_circle.hpp"
#include "pkm/workflow/analyze_diagonals.hpp"
#include "pkm/workflow/analyze_positioning.hpp"

namespace pkm::workflow::detail {
namespace {

namespace sim = pkm::simulation;
namespace met = pkm::metrology;

/// Monte Carlo trials of the diagonal analyses: the coverage compares the linear budget (the U
/// the analyses print), the Monte Carlo beside it is not used here; its minimum keeps it cheap.
constexpr std::size_t kDiagonalTrials = 100;

/// The simulated files by name.
using Files = std::map<std::string, const SimulatedFile*>;

/// The run files of line measurement `name` (NAME_run1.csv, NAME_run2.csv, ...), in run order.
std::vector<io::NamedText> runFiles(const Files& files, const sim::LineSetup& m) {
  std::vector<io::NamedText> out;
  for (int run = 1;; ++run) {
    const auto it = files.find(fmt::format("{}_run{}.csv", m.name, run));
    if (it == files.end()) break;
    out.push_back({it->first, it->second->text});
  }
  return out;
}

void addBudgets(std::vector<CoverageReading>& out,
                const std::string& group,
                const std::vector<met::UncertaintyBudget>& budgets) {
  for (const met::UncertaintyBudget& b : budgets)
    out.push_back({group,
                   b.quantity,
                   b.unit,
                   b.value,
                   b.expandedUncertainty(),
                   b.combinedStandardUncertainty(),
                   b.coverageFactor()});
}

/// The box of the body diagonals: |direction · travel| of "diag-ppp" (zero without it).
Eigen::Vector3d diagonalBox(const io::Scenario& scenario) {
  for (const sim::LineSetup& m : scenario.campaign.measurements)
    if (m.name == "diag-ppp")
      return (m.line.direction * (m.cycle.last - m.cycle.first)).head<3>().cwiseAbs();
  return Eigen::Vector3d::Zero();
}

/// The files of every line measurement whose name starts with `prefix`.
std::vector<io::NamedText> prefixed(const io::Scenario& scenario,
                                    const Files& files,
                                    const std::string& prefix) {
  std::vector<io::NamedText> out;
  for (const sim::LineSetup& m : scenario.campaign.measurements)
    if (m.name.rfind(prefix, 0) == 0)
      for (io::NamedText& f : runFiles(files, m)) out.push_back(std::move(f));
  return out;
}

void diagonals(const io::Scenario& scenario,
               const Files& files,
               const met::UncertaintySources& sources,
               std::vector<CoverageReading>& out) {
  const Eigen::Vector3d box = diagonalBox(scenario);
  if (!(box.minCoeff() > 0.0)) return;
  const std::vector<io::NamedText> body = prefixed(scenario, files, "diag-");
  const std::vector<io::NamedText> step = prefixed(scenario, files, "step-");
  std::vector<io::NamedText> shifted = prefixed(scenario, files, "shift-");
  const std::tuple<const char*, io::DiagonalMethod, std::vector<io::NamedText>> methods[] = {
      {"body diagonals", io::DiagonalMethod::kBody, body},
      {"step diagonals", io::DiagonalMethod::kStep, step},
      {"shifted diagonals", io::DiagonalMethod::kShifted, [&] {
         if (shifted.empty()) return shifted;
         shifted.insert(shifted.end(), body.begin(), body.end());
         return shifted;
       }()}};
  for (const auto& [group, method, data] : methods) {
    if (data.empty()) continue;
    DiagonalsRequest r;
    r.data = data;
    r.method = method;
    r.size = box;
    r.uncertainty = sources;
    r.monte_carlo.trials = kDiagonalTrials;
    addBudgets(out, group, analyzeDiagonals(r).uncertainty);
  }
}

/// The MXT700S parallelism paper's parallelism: the axis PY against the reference Y2 along one beam
/// (their positions run against and along the beam, as the campaign's hybrid step reads them), over
/// 300 mm and over the paper's 50 mm (the "-50" pairs).
void parallelism(const io::Scenario& scenario,
                 const Files& files,
                 const met::UncertaintySources& sources,
                 std::vector<CoverageReading>& out) {
  std::map<std::string, const sim::LineSetup*> by_name;
  for (const sim::LineSetup& m : scenario.campaign.measurements) by_name[m.name] = &m;
  for (const auto& [plane, suffix] : {std::pair{io::ParallelismPlane::kHorizontal, "h"},
                                      std::pair{io::ParallelismPlane::kVertical, "v"},
                                      std::pair{io::ParallelismPlane::kHorizontal, "h-50"},
                                      std::pair{io::ParallelismPlane::kVertical, "v-50"}}) {
    const auto ref = by_name.find(fmt::format("straightness-y2-{}", suffix));
    const auto axis = by_name.find(fmt::format("straightness-py-{}", suffix));
    if (ref == by_name.end() || axis == by_name.end()) continue;
    ParallelismRequest r;
    r.reference = runFiles(files, *ref->second);
    r.axis = runFiles(files, *axis->second);
    r.reference_sign = -1;
    r.axis_sign = 1;
    r.plane = plane;
    r.uncertainty = sources;
    addBudgets(
        out, fmt::format("parallelism Y2-PY ({})", suffix), analyzeParallelism(r).uncertainty);
  }
}

void probes(const io::Scenario& scenario,
            const Files& files,
            const met::UncertaintySources& sources,
            std::vector<CoverageReading>& out) {
  for (const sim::TouchProbeSetup& p : scenario.campaign.probes) {
    for (const char* which : {"circle_uncompensated", "circle_compensated"}) {
      const auto it = files.find(fmt::format("{}_{}.csv", p.name, which));
      if (it == files.end()) continue;
      CircleRequest r;
      r.data = {{it->first, it->second->text}};
      r.uncertainty = sources;
      addBudgets(out, fmt::format("{} {}", p.name, which), analyzeCircle(r).uncertainty);
    }
    const auto it = files.find(p.name + "_offset.csv");
    if (it == files.end()) continue;
    ProbeOffsetRequest r;
    r.data = {{it->first, it->second->text}};
    r.ring_diameter = p.ring_diameter;
    r.tool_plus_z = p.direction.z() > 0.0;
    r.uncertainty = sources;
    addBudgets(out, p.name + " offset", analyzeProbeOffset(r).uncertainty);
  }
}

}  // namespace

std::vector<CoverageReading> coverageReadings(const io::Scenario& scenario,
                                              const SimulateResult& simulation,
                                              const met::UncertaintySources& sources) {
  Files files;
  for (const SimulatedFile& f : simulation.files) files[f.name] = &f;
  std::vector<CoverageReading> out;
  for (const sim::LineSetup& m : scenario.campaign.measurements) {
    const std::vector<io::NamedText> data = runFiles(files, m);
    if (data.empty()) continue;
    if (m.quantity == sim::LineQuantity::kLinear &&
        m.procedure == sim::LineProcedure::kContinuous) {
      Iso230_2Request r;
      r.data = data;
      r.uncertainty = sources;
      addBudgets(out, m.name, analyzeIso230_2(r).uncertainty);
    } else if (m.quantity == sim::LineQuantity::kStraightness) {
      StraightnessRequest r;
      r.data = data;
      r.uncertainty = sources;
      addBudgets(out, m.name, analyzeStraightness(r).uncertainty);
    }
  }
  diagonals(scenario, files, sources, out);
  parallelism(scenario, files, sources, out);
  probes(scenario, files, sources, out);
  return out;
}

std::vector<CoverageReading> injectedSquareness(const io::Scenario& scenario,
                                                const std::string& group) {
  const auto* machine = dynamic_cast<const sim::CartesianMachine*>(scenario.campaign.machine.get());
  if (machine == nullptr) return {};
  const sim::CartesianSquareness& s = machine->errors().squareness;
  return {{group, "squareness_xy", "rad", s.xy},
          {group, "squareness_xz", "rad", s.xz},
          {group, "squareness_yz", "rad", s.yz}};
}

}  // namespace pkm::workflow::detail
