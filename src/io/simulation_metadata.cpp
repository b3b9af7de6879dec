// Metadata of simulated measurement files (simulation_metadata.hpp).
#include "pkm/io/simulation_metadata.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <string>
#include <vector>

#include "pkm/core/units.hpp"
#include "pkm/io/number_format.hpp"

namespace pkm::io {

namespace sim = pkm::simulation;

namespace {

std::string valuesText(const Eigen::VectorXd& v) {
  std::string out = "(";
  for (Eigen::Index i = 0; i < v.size(); ++i) out += (i ? ", " : "") + formatNumber(v[i]);
  return out + ")";
}

/// A command with its angular axes in degrees.
std::string commandText(const Eigen::VectorXd& v, const std::vector<bool>& angular) {
  Eigen::VectorXd w = v;
  for (Eigen::Index i = 0; i < w.size(); ++i)
    if (angular[static_cast<std::size_t>(i)]) w[i] = radToDeg(w[i]);
  return valuesText(w);
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

Metadata lineRunMetadata(const Scenario& s,
                         std::uint64_t seed,
                         const sim::LineSetup& m,
                         int run,
                         const std::vector<sim::LineRun>& runs) {
  const std::vector<std::string> axes = s.campaign.machine->axisNames();
  const std::vector<bool> angular_axes = s.campaign.machine->angularAxes();
  const bool angular = m.quantity == sim::LineQuantity::kAngular;
  const char* unit = angular ? "urad" : "mm";
  const double scale = angular ? 1e6 : 1.0;
  Metadata md = {
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
      {"reflector offset mm", valuesText(m.reflector_offset)},
      {"noise",
       fmt::format("sigma {} {}, {} ppm, resolution {} {}",
                   formatNumber(m.noise.sigma * scale),
                   unit,
                   formatNumber(m.noise.sigma_ppm),
                   formatNumber(m.noise.resolution * scale),
                   unit)},
  };
  if (m.quantity != sim::LineQuantity::kLinear) md.emplace_back("lateral", valuesText(m.lateral));
  if (m.quantity == sim::LineQuantity::kStraightness)
    md.emplace_back("misalignment urad", formatNumber(m.misalignment * 1e6));
  // The set-up a laser's budget needs (docs/formats.md, "Environment records").
  const sim::Environment& env = s.campaign.environment;
  if (m.quantity == sim::LineQuantity::kLinear && env.air.enabled)
    md.emplace_back("dead path mm", formatNumber(env.air.dead_path_mm));
  if (m.quantity == sim::LineQuantity::kLinear && env.setup.enabled) {
    md.emplace_back("beam alignment urad", formatNumber(env.setup.beam_misalignment_rad * 1e6));
    // The engineer's bound of the reflector's distance from the tool point: the set-up's own
    // offset and three standard deviations of its unknown part; the rotation range as angular
    // optics read it along the line.
    const double range = sim::rotationRange(runs);
    if (range > 0.0) {
      md.emplace_back(
          "abbe offset mm",
          formatNumber(m.reflector_offset.norm() + 3.0 * env.setup.reflector_offset_mm));
      md.emplace_back("angular range urad", fmt::format("{:.2f}", range * 1e6));
    }
  }
  return md;
}

namespace {

std::string pointsText(const std::array<Eigen::Vector3d, 3>& points) {
  std::string out;
  for (const Eigen::Vector3d& p : points) out += (out.empty() ? "" : ", ") + valuesText(p);
  return out;
}

}  // namespace

Metadata gaugeSetupMetadata(const sim::DialGaugeSetup& d, const std::string& instrument) {
  return {
      {"format", "pkm.constrained-motion/1"},
      {"instrument", instrument},
      {"gauge points mm", pointsText(d.gauge_points)},
      {"table normal", valuesText(d.table_normal)},
      {"tolerance mm", formatNumber(d.tolerance)},
  };
}

Metadata dialGaugeMetadata(const Scenario& s, std::uint64_t seed, const sim::DialGaugeSetup& d) {
  Metadata m =
      gaugeSetupMetadata(d, "three dial gauges on the platform, tips on the table (simulated)");
  m.insert(
      m.begin() + 1,
      {{"scenario", s.campaign.name}, {"seed", std::to_string(seed)}, {"measurement", d.name}});
  m.push_back({"noise",
               fmt::format("sigma {} mm, resolution {} mm",
                           formatNumber(d.noise.sigma),
                           formatNumber(d.noise.resolution))});
  return m;
}

}  // namespace pkm::io
