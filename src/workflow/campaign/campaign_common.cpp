// Helpers shared by the campaign steps (campaign_steps.hpp).
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <utility>
#include <vector>

#include "campaign_compensation.hpp"
#include "campaign_steps.hpp"
#include "pkm/compensation/axis_table.hpp"
#include "pkm/compensation/siemens_comp.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/atomic_file.hpp"
#include "pkm/io/measurement_files.hpp"
#include "pkm/io/simulation_metadata.hpp"
#include "pkm/metrology/per_target.hpp"
#include "pkm/metrology/positioning_uncertainty.hpp"

namespace pkm::workflow::campaign {

namespace fs = std::filesystem;
namespace sim = pkm::simulation;
namespace met = pkm::metrology;

void StepContext::write(StepOutcome& outcome,
                        const std::string& name,
                        const std::string& text) const {
  const fs::path path = dir / name;
  std::error_code ec;
  fs::create_directories(path.parent_path(), ec);
  io::writeFileAtomic(path, text, io::Overwrite::kAllow);
  outcome.files.push_back(fs::relative(path, out).generic_string());
}

void StepContext::writeCompensation(StepOutcome& outcome,
                                    const std::string& kind,
                                    const std::string& name,
                                    const std::string& text) const {
  write(outcome, name, text);
  outcome.record.compensations.push_back({kind, (dir / name).string(), text});
}

Json plot(const std::string& id,
          const std::string& title,
          const std::string& kind,
          const std::string& x_label,
          const std::string& y_label) {
  return Json{{"id", id},
              {"title", title},
              {"kind", kind},
              {"x_label", x_label},
              {"y_label", y_label},
              {"series", Json::array()}};
}

void addSeries(Json& p,
               const std::string& label,
               const std::vector<double>& x,
               const std::vector<double>& y) {
  Json xs = Json::array(), ys = Json::array();
  for (double v : x) xs.push_back(cell(v, 9));
  for (double v : y) ys.push_back(cell(v, 7));
  p["series"].push_back(Json{{"label", label}, {"x", std::move(xs)}, {"y", std::move(ys)}});
}

Json table(const std::string& title, const std::vector<std::string>& columns) {
  return Json{{"title", title}, {"columns", columns}, {"rows", Json::array()}};
}

Json cell(double value, int digits) {
  if (!std::isfinite(value)) return nullptr;
  if (value == 0.0) return 0.0;
  return std::stod(fmt::format("{:.{}g}", value, digits));
}

Json section(const std::string& id, const std::string& title, std::vector<std::string> text) {
  return Json{{"id", id},
              {"title", title},
              {"paragraphs", std::move(text)},
              {"tables", Json::array()},
              {"plots", Json::array()}};
}

const std::vector<sim::LineRun>& LineData::runs(const std::string& name,
                                                const std::string& source) const {
  for (const sim::MeasurementResult& r : results)
    if (r.setup->name == name) return r.runs;
  throw IoError(fmt::format("{}: the scenario has no measurement '{}'", source, name));
}

bool LineData::has(const std::string& name) const {
  return std::any_of(results.begin(), results.end(), [&](const sim::MeasurementResult& r) {
    return r.setup->name == name;
  });
}

const sim::LineSetup& LineData::setup(const std::string& name, const std::string& source) const {
  for (const sim::MeasurementResult& r : results)
    if (r.setup->name == name) return *r.setup;
  throw IoError(fmt::format("{}: the scenario has no measurement '{}'", source, name));
}

void writeLineFiles(const StepContext& context,
                    StepOutcome& outcome,
                    const std::string& folder,
                    const io::Scenario& scenario,
                    std::uint64_t seed,
                    const LineData& data) {
  for (const sim::MeasurementResult& r : data.results)
    for (const sim::LineRun& run : r.runs)
      context.write(outcome,
                    fmt::format("{}/{}_run{}.csv", folder, r.setup->name, run.run),
                    io::lineRunCsv(r.setup->quantity,
                                   io::lineRunMetadata(scenario, seed, *r.setup, run.run, r.runs),
                                   run));
}

metrology::Iso230_2Result iso230_2(const std::vector<sim::LineRun>& runs) {
  std::vector<metrology::PositioningSample> samples;
  for (const sim::LineRun& run : runs)
    for (const sim::LineReading& r : run.readings)
      if (r.sub_step == 0) samples.push_back({r.target, r.direction, run.run, r.reading});
  return metrology::evaluateIso230_2(samples);
}

double expandedU(const std::vector<metrology::UncertaintyBudget>& budgets,
                 const std::string& quantity) {
  for (const metrology::UncertaintyBudget& b : budgets)
    if (b.quantity == quantity) return b.expandedUncertainty();
  return std::nan("");
}

std::string largestContributors(const metrology::UncertaintyBudget& budget) {
  double total = 0.0;
  std::vector<std::pair<double, std::string>> shares;
  for (const metrology::UncertaintyContributor& c : budget.contributors) {
    const double v = c.contribution() * c.contribution();
    total += v;
    shares.emplace_back(v, c.name);
  }
  if (!(total > 0.0)) return {};
  std::sort(
      shares.begin(), shares.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::string out;
  for (std::size_t k = 0; k < std::min<std::size_t>(2, shares.size()); ++k)
    out += fmt::format(
        "{}{} {:.0f} %", k == 0 ? "" : ", ", shares[k].second, 100.0 * shares[k].first / total);
  return out;
}

std::string largestContributors(const std::vector<metrology::UncertaintyBudget>& budgets,
                                const std::string& quantity) {
  for (const metrology::UncertaintyBudget& b : budgets)
    if (b.quantity == quantity) return largestContributors(b);
  return {};
}

void setIso230_2AfterU(SummaryRow& row,
                       const metrology::Iso230_2Result& after,
                       const std::string& quantity,
                       const metrology::UncertaintySources& sources) {
  const std::vector<metrology::UncertaintyBudget> b =
      metrology::iso230_2Uncertainty(after, sources);
  row.after_U = expandedU(b, quantity);
  row.after_limit = largestContributors(b, quantity);
}

double iso230_2U(const metrology::Iso230_2Result& result,
                 const std::string& quantity,
                 const metrology::UncertaintySources& sources) {
  return expandedU(metrology::iso230_2Uncertainty(result, sources), quantity);
}

void meanReadings(const std::vector<sim::LineRun>& runs,
                  std::vector<double>& targets,
                  std::vector<double>& means) {
  std::vector<metrology::TargetSample> samples;
  for (const sim::LineRun& run : runs)
    for (const sim::LineReading& r : run.readings)
      if (r.sub_step == 0) samples.push_back({r.target, r.reading});
  metrology::TargetMeans m = metrology::perTargetMeans(samples);
  targets = std::move(m.target);
  means = std::move(m.mean);
}

io::Scenario stepScenario(const StepContext& context, std::uint64_t& seed) {
  if (!context.spec.contains("scenario") || !context.spec["scenario"].is_string())
    throw IoError(fmt::format("{}: a step needs \"scenario\" (a scenario file or built-in name)",
                              context.source));
  std::string spec = context.spec["scenario"].get<std::string>();
  std::error_code ec;
  if (!fs::path(spec).is_absolute() && fs::is_regular_file(context.base_dir / spec, ec))
    spec = (context.base_dir / spec).string();
  io::Scenario scenario = io::loadScenario(spec);
  seed = scenario.seed;
  std::optional<sim::Environment> environment = context.environment;
  if (context.spec.contains("environment")) {
    const Json& e = context.spec["environment"];
    const auto preset = e.is_string() ? sim::environmentPreset(e.get<std::string>()) : std::nullopt;
    if (!preset)
      throw IoError(fmt::format("{}: \"environment\" must be a preset name: {}",
                                context.source,
                                fmt::join(sim::environmentPresetNames(), ", ")));
    if (!environment) environment = preset;  // the campaign's environment wins
  }
  if (environment) {
    scenario.campaign.environment = *environment;
    sim::applyProbeEnvironment(scenario.campaign);
    sim::applyMachineEnvironment(scenario.campaign);
  }
  if (context.spec.contains("seed")) {
    if (!context.spec["seed"].is_number_unsigned())
      throw IoError(fmt::format("{}: \"seed\" must be a non-negative integer", context.source));
    seed = context.spec["seed"].get<std::uint64_t>();
  }
  if (context.seed) seed = *context.seed;
  // The true machine's unmodelled geometry, drawn from the step's seed for its environment.
  sim::applyGeometryEnvironment(scenario.campaign, seed);
  return scenario;
}

void writeAxisTables(const StepContext& ctx,
                     StepOutcome& out,
                     const LineData& data,
                     const std::vector<std::pair<std::string, int>>& tables,
                     const std::vector<std::string>& axis_names,
                     AxisTableController& controller) {
  namespace comp = pkm::compensation;
  const comp::FormatTraits eec = comp::traits(comp::TableFormat::kSiemensEec);
  for (const auto& [name, axis] : tables) {
    const sim::LineSetup& setup = data.setup(name, ctx.source);
    metrology::Iso230_2Result r = iso230_2(data.runs(name, ctx.source));
    for (metrology::TargetStatistics& t : r.targets)
      t.target = setup.line.start[axis] + t.target * setup.line.direction[axis];
    const std::string& axis_name = axis_names.at(static_cast<std::size_t>(axis));
    const comp::AxisErrorTable table = comp::tableFromIso230_2(r, axis_name);
    const comp::LinuxcncCompFile file = comp::linuxcncCompFromTable(table, 1);
    const std::string text = comp::writeLinuxcncComp(file);
    ctx.writeCompensation(
        out, "linuxcnc-comp", fmt::format("compensation/{}.comp", axis_name), text);
    ctx.write(out,
              fmt::format("compensation/{}.eec.spf", axis_name),
              comp::writeSiemensEec(comp::siemensEecFromTable(
                  comp::fitToTarget(table, eec, eec.default_max_points))));
    controller.set(axis, file);
  }
}

met::RecordedConditions setupRecords(const sim::Environment& environment) {
  met::RecordedConditions out;
  if (environment.air.enabled) out.dead_path_mm = environment.air.dead_path_mm;
  if (environment.setup.enabled) {
    out.misalignment_rad = environment.setup.beam_misalignment_rad;
    // The bound of the reflector's unknown offset, as the simulated files state it
    // (io::lineRunMetadata); recordedConditions adds the lines' own offsets and rotation range.
    out.abbe_offset_mm = 3.0 * environment.setup.reflector_offset_mm;
  }
  return out;
}

met::RecordedConditions recordedConditions(const LineData& data) {
  met::RecordedConditions out = data.records;
  // The Abbe records as the line files state them: the largest of the linear lines.
  double range = 0.0, offset = 0.0;
  for (const sim::MeasurementResult& r : data.results)
    if (r.setup->quantity == sim::LineQuantity::kLinear && sim::rotationRange(r.runs) > range) {
      range = sim::rotationRange(r.runs);
      offset = r.setup->reflector_offset.norm();
    }
  if (out.abbe_offset_mm && range > 0.0) {  // simulated: the set-up's bound (setupRecords)
    out.abbe_offset_mm = *out.abbe_offset_mm + offset;
    out.angular_range_rad = std::max(out.angular_range_rad.value_or(0.0), range);
  }
  met::RecordedSeries t, p, h, m;
  for (const sim::MeasurementResult& r : data.results)
    for (const sim::LineRun& run : r.runs)
      for (const sim::LineReading& x : run.readings) {
        if (!x.sensed.recorded) continue;
        t.add(x.sensed.air_temperature_c);
        p.add(x.sensed.air_pressure_pa);
        h.add(x.sensed.air_humidity_rh);
        m.add(x.sensed.material_temperature_c);
      }
  if (t.count == 0) return out;
  met::RecordedConditions sensed;
  sensed.air_temperature_c = t;
  sensed.air_pressure_pa = p;
  sensed.air_humidity_rh = h;
  sensed.material_temperature_c = m;
  out.merge(sensed);
  return out;
}

met::UncertaintySources sourcesAt(const met::UncertaintySources& sources, const LineData& data) {
  return met::withRecordedConditions(sources, recordedConditions(data));
}

}  // namespace pkm::workflow::campaign
