// Readers of positioning and straightness files (positioning_files.hpp).
#include "pkm/io/positioning_files.hpp"

#include <fmt/format.h>

#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <utility>

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

Profile readStraightness(std::span<const NamedText> inputs) {
  std::vector<TextTable> sim;
  Profile p;
  for (const NamedText& in : inputs) {
    TextTable t = TextTable::parse(in.text, in.name);
    if (isMeasurementFile(t)) {
      sim.push_back(std::move(t));
      continue;
    }
    const std::size_t cp = t.column({"position"}), cd = t.column({"deviation"});
    for (std::size_t r = 0; r < t.rows(); ++r) {
      p.position.push_back(t.number(r, cp));
      p.value.push_back(t.number(r, cd));
    }
  }
  if (!sim.empty()) {
    const Profile m = meanProfile(sim, false);
    p.position.insert(p.position.end(), m.position.begin(), m.position.end());
    p.value.insert(p.value.end(), m.value.begin(), m.value.end());
  }
  return p;
}

std::vector<metrology::PositioningSample> readPositioningSamples(
    std::span<const NamedText> inputs) {
  std::vector<metrology::PositioningSample> samples;
  std::map<std::tuple<double, int, long long>, std::pair<std::string, std::size_t>> seen;
  for (const NamedText& in : inputs) {
    const TextTable t = TextTable::parse(in.text, in.name);
    const std::size_t ct = t.column({"target", "target_mm"});
    const std::size_t cd = t.column({"direction"});
    const std::size_t cr = t.column({"run"});
    const std::size_t cm = t.column({"measured", "reading_mm"});
    for (std::size_t r = 0; r < t.rows(); ++r) {
      const double target = t.number(r, ct);
      const int direction = t.direction(r, cd);
      const long long run = t.integer(r, cr);
      if (run < 1 || run > 1'000'000'000) t.fail(r, fmt::format("run must be >= 1, got {}", run));
      const auto [it, fresh] = seen.try_emplace({target, direction, run}, t.source(), t.line(r));
      if (!fresh) {
        t.fail(r,
               fmt::format("duplicate reading: target {}, direction {}, run {} (first at {}:{})",
                           target,
                           direction > 0 ? '+' : '-',
                           run,
                           it->second.first,
                           it->second.second));
      }
      samples.push_back({target, direction, static_cast<int>(run), t.number(r, cm)});
    }
  }
  return samples;
}

}  // namespace pkm::io
