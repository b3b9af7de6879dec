// Readers of positioning and straightness files (positioning_files.hpp).
#include "pkm/io/positioning_files.hpp"

#include <fmt/format.h>

#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <utility>

#include "pkm/io/renishaw_rtl.hpp"
#include "pkm/metrology/per_target.hpp"

namespace pkm::io {

bool isMeasurementFile(const TextTable& t) {
  return t.findColumn({"target_mm"}).has_value() && t.findColumn({"reading_mm"}).has_value();
}

Profile meanProfile(std::span<const TextTable> tables, bool minus_target) {
  std::vector<metrology::TargetSample> samples;
  for (const TextTable& t : tables) {
    const std::size_t ct = t.column({"target_mm"}), cr = t.column({"reading_mm"});
    // A step-diagonal run's intermediate readings (sub_step > 0) are not readings at the target.
    const std::optional<std::size_t> cs = t.findColumn({"sub_step"});
    for (std::size_t r = 0; r < t.rows(); ++r) {
      if (cs && t.integer(r, *cs) != 0) continue;
      const double target = t.number(r, ct);
      samples.push_back({target, t.number(r, cr) - (minus_target ? target : 0.0)});
    }
  }
  const metrology::TargetMeans m = metrology::perTargetMeans(samples);
  return {m.target, m.mean};
}

Profile readStraightnessPoints(std::span<const NamedText> inputs) {
  static const std::vector<ColumnRole> roles = {
      {"position", {"position", "target", "target position", "nominal", "nominal position"}},
      {"deviation", {"deviation", "error", "straightness", "straightness deviation"}}};
  Profile p;
  for (const NamedText& in : inputs) {
    const TextTable t = TextTable::parseData(in.text, in.name);
    if (isMeasurementFile(t)) {
      const std::size_t ct = t.column({"target_mm"}), cr = t.column({"reading_mm"});
      const std::optional<std::size_t> cs = t.findColumn({"sub_step"});
      for (std::size_t r = 0; r < t.rows(); ++r) {
        if (cs && t.integer(r, *cs) != 0) continue;
        p.position.push_back(t.number(r, ct));
        p.value.push_back(t.number(r, cr));
      }
      continue;
    }
    const ExportColumns c(t, roles);
    c.require({{"position"}, {"deviation"}});
    const double sp = columnScale(t, c, "position", "", "--unit", false);
    const double sd = columnScale(t, c, "deviation", "", "--unit", false);
    const std::size_t cp = c.at("position"), cd = c.at("deviation");
    for (std::size_t r = 0; r < t.rows(); ++r) {
      p.position.push_back(t.number(r, cp) * sp);
      p.value.push_back(t.number(r, cd) * sd);
    }
  }
  return p;
}

Profile readStraightness(std::span<const NamedText> inputs) {
  return perTargetMean(readStraightnessPoints(inputs));
}

Profile perTargetMean(const Profile& raw) {
  std::vector<metrology::TargetSample> samples;
  samples.reserve(raw.position.size());
  for (std::size_t k = 0; k < raw.position.size(); ++k)
    samples.push_back({raw.position[k], raw.value[k]});
  const metrology::TargetMeans m = metrology::perTargetMeans(samples);
  return {m.target, m.mean};
}

namespace {

/// The columns of a positioning export (docs/formats.md, "Instrument exports").
const std::vector<ColumnRole>& positioningRoles() {
  static const std::vector<ColumnRole> roles = {
      {"target",
       {"target",
        "target position",
        "nominal",
        "nominal position",
        "position",
        "commanded",
        "command"}},
      {"run", {"run", "run no", "run number", "cycle"}},
      {"direction", {"direction", "dir", "approach"}},
      {"measured", {"measured", "measured position", "actual", "actual position", "reading"}},
      {"error", {"error", "deviation", "dev", "positioning error", "position error"}},
  };
  return roles;
}

/// The samples of one table, in mm; true when its target unit was assumed (mm).
bool readPositioningTable(
    const TextTable& t,
    const PositioningColumns& how,
    std::vector<metrology::PositioningSample>& samples,
    std::map<std::tuple<double, int, long long>, std::pair<std::string, std::size_t>>& seen) {
  const ExportColumns c(t, positioningRoles(), how.columns);
  c.require({{"target"}, {"run"}, {"direction"}, {"measured", "error"}});
  const std::size_t ct = c.at("target"), cd = c.at("direction"), cr = c.at("run");
  const double target_scale = columnScale(t, c, "target", how.unit, "--unit", false);
  const bool assumed = how.unit.empty() && c.unit("target").empty();
  const bool measured = c.find("measured").has_value();
  const std::size_t cm = measured ? c.at("measured") : c.at("error");
  const double value_scale = measured
                                 ? columnScale(t, c, "measured", how.unit, "--unit", false)
                                 : columnScale(t, c, "error", how.error_unit, "--error-unit", true);
  for (std::size_t r = 0; r < t.rows(); ++r) {
    const double target = t.number(r, ct) * target_scale;
    const int direction = t.direction(r, cd);
    const long long run = t.integer(r, cr);
    if (run < 1 || run > 1'000'000'000) t.fail(r, fmt::format("run must be >= 1, got {}", run));
    const auto [it, fresh] = seen.try_emplace({target, direction, run}, t.source(), t.line(r));
    if (!fresh) {
      t.fail(r,
             fmt::format("duplicate reading: target {}, direction {}, run {} (first at {}:{})",
                         t.text(r, ct),
                         direction > 0 ? '+' : '-',
                         run,
                         it->second.first,
                         it->second.second));
    }
    const double value = t.number(r, cm) * value_scale;
    samples.push_back(
        {target, direction, static_cast<int>(run), measured ? value : target + value});
  }
  return assumed;
}

}  // namespace

std::vector<metrology::PositioningSample> readPositioningSamples(
    std::span<const NamedText> inputs,
    const PositioningColumns& how,
    std::vector<std::string>* unstated) {
  std::vector<metrology::PositioningSample> samples;
  std::map<std::tuple<double, int, long long>, std::pair<std::string, std::size_t>> seen;
  for (const NamedText& in : inputs) {
    if (isRenishawRtl(in.text)) {
      for (const metrology::PositioningSample& s : readRenishawRtl(in)) samples.push_back(s);
      continue;
    }
    if (readPositioningTable(TextTable::parseData(in.text, in.name), how, samples, seen) &&
        unstated)
      unstated->push_back(in.name);
  }
  return samples;
}

}  // namespace pkm::io
