// Built-in scenarios, loading by name or file, and the scenario.json / truth.json outputs.
#include <fmt/ranges.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/scenario_detail.hpp"
#include "io/scenario_probe.hpp"
#include "io/scenario_tracker.hpp"
#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/io/geometric_errors.hpp"
#include "pkm/io/number_format.hpp"
#include "pkm/io/scenario.hpp"
#include "pkm/simulation/hexapod_virtual_machine.hpp"
#include "pkm/simulation/hybrid_virtual_machine.hpp"

namespace pkm::io {

namespace sim = pkm::simulation;

namespace {

std::string array(const std::vector<double>& v) {
  std::string out = "[";
  for (std::size_t i = 0; i < v.size(); ++i) out += (i ? ", " : "") + formatNumber(v[i]);
  return out + "]";
}

/// A Cartesian axis table in the scenario's error-table form.
std::string tableJson(const geometry::ErrorTable1d& t) {
  std::string out = fmt::format("{{\"out_of_range\": \"{}\", \"positions\": {}",
                                t.outOfRange() == geometry::OutOfRange::kClamp ? "clamp" : "error",
                                array(t.positions()));
  for (Eigen::Index c = 0; c < 6; ++c) {
    std::vector<double> col;
    for (Eigen::Index i = 0; i < t.values().rows(); ++i)
      col.push_back(t.values()(i, c) * (c < 3 ? 1.0 : kUradPerRad));
    out +=
        fmt::format(", \"{}\": {}", detail::kErrorColumns[static_cast<std::size_t>(c)], array(col));
  }
  return out + "}";
}

std::string cartesianErrorsJson(const sim::CartesianMachine& m) {
  const sim::CartesianSquareness& s = m.errors().squareness;
  std::string out = fmt::format(
      "{{\n    \"squareness_urad\": {{\"xy\": {}, \"xz\": {}, \"yz\": {}}},\n"
      "    \"iso_squareness_urad\": {{\"EC0Y\": {}, \"EB0Z\": {}, \"EA0Z\": {}}}",
      formatNumber(s.xy * kUradPerRad),
      formatNumber(s.xz * kUradPerRad),
      formatNumber(s.yz * kUradPerRad),
      formatNumber(s.xy * kUradPerRad),
      formatNumber(-s.xz * kUradPerRad),
      formatNumber(s.yz * kUradPerRad));
  const char* axes[] = {"x", "y", "z"};
  for (std::size_t k = 0; k < 3; ++k)
    if (m.errors().axes[k])
      out += fmt::format(",\n    \"{}\": {}", axes[k], tableJson(*m.errors().axes[k]));
  return out + "\n  }";
}

std::string vec3(const Eigen::Vector3d& v) { return array({v[0], v[1], v[2]}); }

/// The hexapod part of truth.json: the true joint centres and offsets, and the actuation.
std::string hexapodTruth(const sim::HexapodVirtualMachine& m, const std::string& machine_spec) {
  std::string base, platform;
  std::vector<double> offsets, true_offsets, backlash;
  for (std::size_t i = 0; i < kinematics::kStruts; ++i) {
    const kinematics::Strut& n = m.nominal().struts[i];
    const kinematics::Strut& t = m.truth().struts[i];
    base += fmt::format("{}{}", i ? ", " : "", vec3(t.world_p_base - n.world_p_base));
    platform += fmt::format("{}{}", i ? ", " : "", vec3(t.platform_p_joint - n.platform_p_joint));
    offsets.push_back(t.length_offset - n.length_offset);
    true_offsets.push_back(t.length_offset);
    backlash.push_back(m.actuation().backlash[static_cast<Eigen::Index>(i)]);
  }
  std::string true_base, true_platform;
  for (std::size_t i = 0; i < kinematics::kStruts; ++i) {
    true_base += fmt::format("{}{}", i ? ", " : "", vec3(m.truth().struts[i].world_p_base));
    true_platform += fmt::format("{}{}", i ? ", " : "", vec3(m.truth().struts[i].platform_p_joint));
  }
  return fmt::format(
      "  \"machine\": {},\n  \"errors\": {{\n    \"base_joint\": [{}],\n    \"platform_joint\": "
      "[{}],\n"
      "    \"length_offset\": {}\n  }},\n  \"true_geometry\": {{\n    \"base\": [{}],\n    "
      "\"platform\": [{}],\n"
      "    \"length_offset\": {}\n  }},\n  \"actuation\": {{\"encoder_resolution\": {}, "
      "\"backlash\": {}, "
      "\"repeatability_sigma\": {}}}\n}}\n",
      nlohmann::json(machine_spec).dump(),
      base,
      platform,
      array(offsets),
      true_base,
      true_platform,
      array(true_offsets),
      formatNumber(m.actuation().encoder_resolution),
      array(backlash),
      formatNumber(m.actuation().repeatability_sigma));
}

}  // namespace

std::vector<std::string> builtinScenarioNames() {
  std::vector<std::string> names;
  for (const auto& [name, text] : detail::embeddedScenarios()) names.emplace_back(name);
  std::sort(names.begin(), names.end());
  return names;
}

Scenario loadScenario(const std::string& spec) {
  std::error_code ec;
  if (std::filesystem::is_regular_file(spec, ec)) {
    std::ifstream in(spec, std::ios::binary);
    if (!in) throw IoError(locate(spec, 0, "cannot open the file"));
    std::ostringstream text;
    text << in.rdbuf();
    return parseScenarioJson(text.str(), spec, std::filesystem::path(spec).parent_path().string());
  }
  for (const auto& [stem, text] : detail::embeddedScenarios())
    if (stem == spec) return parseScenarioJson(std::string(text), "builtin:" + spec);
  throw IoError(fmt::format("{}: no such file, and not a built-in scenario (built-in: {})",
                            spec,
                            fmt::join(builtinScenarioNames(), ", ")));
}

std::string scenarioJsonWithSeed(const Scenario& scenario, std::uint64_t seed) {
  nlohmann::ordered_json j = nlohmann::ordered_json::parse(scenario.text);
  j["seed"] = seed;
  return j.dump(2) + "\n";
}

std::string truthJson(const Scenario& scenario, std::uint64_t seed) {
  std::string out = fmt::format(
      "{{\n  \"schema\": \"pkm.truth/1\",\n  \"scenario\": {},\n  \"seed\": {},\n  "
      "\"machine_kind\": \"{}\",\n",
      nlohmann::json(scenario.campaign.name).dump(),
      seed,
      scenario.machine_kind);
  if (const auto* c = dynamic_cast<const sim::CartesianMachine*>(scenario.campaign.machine.get())) {
    out += fmt::format(
        "  \"order\": \"{}\",\n  \"tool_offset\": {},\n  \"errors\": {}\n}}\n",
        c->layout().order,
        array({c->layout().tool_offset[0], c->layout().tool_offset[1], c->layout().tool_offset[2]}),
        cartesianErrorsJson(*c));
  } else if (const auto* h =
                 dynamic_cast<const sim::HybridVirtualMachine*>(scenario.campaign.machine.get())) {
    const nlohmann::ordered_json errors =
        nlohmann::ordered_json::parse(writeGeometricErrorsJson(h->errors()));
    const std::string tripod = h->tripod()
                                   ? fmt::format(",\n  \"tripod_errors\": {}",
                                                 detail::tripodErrorsJson(h->tripod()->errors()))
                                   : std::string();
    out += fmt::format("  \"machine\": {},\n  \"errors\": {}{}\n}}\n",
                       nlohmann::json(scenario.machine_spec).dump(),
                       errors.dump(2),
                       tripod);
  } else if (const auto* x =
                 dynamic_cast<const sim::HexapodVirtualMachine*>(scenario.campaign.machine.get())) {
    out += hexapodTruth(*x, scenario.machine_spec);
  } else {
    out += "  \"errors\": null\n}\n";
  }
  out.insert(out.size() - 3, detail::extraTruthJson(scenario.campaign));  // before "\n}\n"
  out.insert(out.size() - 3, detail::touchProbeTruthJson(scenario.campaign));
  out.insert(out.size() - 3, detail::geometryTruthJson(scenario.campaign));
  return out;
}

}  // namespace pkm::io
