// Positioning and straightness files read from memory (measurement_input.hpp).
#include "measurement_input.hpp"

#include <fmt/format.h>

#include <map>
#include <optional>
#include <tuple>
#include <utility>

#include "pkm/io/text_table.hpp"
#include "pkm/metrology/per_target.hpp"

namespace pkm::workflow::detail {
namespace {

bool isMeasurementFile(const io::TextTable& t) {
  return t.findColumn({"target_mm"}).has_value() && t.findColumn({"reading_mm"}).has_value();
}

/// Per-target mean of the readings of simulator files (sub_step 0 only).
Profile meanProfile(const std::vector<io::TextTable>& tables) {
  std::vector<metrology::TargetSample> samples;
  for (const io::TextTable& t : tables) {
    const std::size_t ct = t.column({"target_mm"}), cr = t.column({"reading_mm"});
    // A step-diagonal run's intermediate readings (sub_step > 0) are not readings at the target.
    const std::optional<std::size_t> cs = t.findColumn({"sub_step"});
    for (std::size_t r = 0; r < t.rows(); ++r) {
      if (cs && t.integer(r, *cs) != 0) continue;
      samples.push_back({t.number(r, ct), t.number(r, cr)});
    }
  }
  const metrology::TargetMeans m = metrology::perTargetMeans(samples);
  return {m.target, m.mean};
}

}  // namespace

Profile readStraightness(const std::vector<io::NamedText>& files) {
  std::vector<io::TextTable> sim;
  Profile p;
  for (const io::NamedText& f : files) {
    io::TextTable t = io::TextTable::parse(f.text, f.name);
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
    const Profile m = meanProfile(sim);
    p.position.insert(p.position.end(), m.position.begin(), m.position.end());
    p.value.insert(p.value.end(), m.value.begin(), m.value.end());
  }
  return p;
}

std::vector<metrology::PositioningSample> readPositioningSamples(
    const std::vector<io::NamedText>& files) {
  std::vector<metrology::PositioningSample> samples;
  std::map<std::tuple<double, int, long long>, std::pair<std::string, std::size_t>> seen;
  for (const io::NamedText& f : files) {
    const io::TextTable t = io::TextTable::parse(f.text, f.name);
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

}  // namespace pkm::workflow::detail
