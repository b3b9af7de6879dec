// Scenario files (docs/formats.md, "Scenario files"): parsing into a simulation::Campaign.
#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/detail/error_table_json.hpp"
#include "io/detail/json_doc.hpp"
#include "io/scenario_detail.hpp"
#include "io/scenario_probe.hpp"
#include "io/scenario_tracker.hpp"
#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/io/scenario.hpp"
#include "pkm/simulation/hybrid_virtual_machine.hpp"

namespace pkm::io {

namespace sim = pkm::simulation;
namespace geo = pkm::geometry;
using detail::json;
using detail::JsonDoc;

namespace {

constexpr double kMaxSeed = 9007199254740992.0;  // 2^53: every integer below is exact in JSON

using detail::numbers;

std::shared_ptr<sim::VirtualMachine> readCartesian(const JsonDoc& doc,
                                                   const json& m,
                                                   const std::string& ptr) {
  doc.onlyKeys(m, ptr, {"kind", "order", "tool_offset", "errors", "actuation"});
  sim::CartesianLayout layout;
  layout.order = doc.string(m, ptr, "order", "XYZ");
  if (m.contains("tool_offset"))
    layout.tool_offset = doc.vec3(m["tool_offset"], ptr + "/tool_offset");
  sim::CartesianErrors errors;
  if (m.contains("errors")) {
    const json& e = m["errors"];
    const std::string ep = ptr + "/errors";
    doc.onlyKeys(e, ep, {"squareness_urad", "x", "y", "z"});
    if (e.contains("squareness_urad")) {
      const json& s = e["squareness_urad"];
      const std::string sp = ep + "/squareness_urad";
      doc.onlyKeys(s, sp, {"xy", "xz", "yz"});
      errors.squareness = {doc.number(s, sp, "xy", 0.0) / kUradPerRad,
                           doc.number(s, sp, "xz", 0.0) / kUradPerRad,
                           doc.number(s, sp, "yz", 0.0) / kUradPerRad};
    }
    const char* axes[] = {"x", "y", "z"};
    for (std::size_t k = 0; k < 3; ++k)
      if (e.contains(axes[k]))
        errors.axes[k] = detail::readErrorTable(doc, e[axes[k]], ep + "/" + axes[k]);
  }
  sim::CartesianActuation actuation;
  if (m.contains("actuation"))
    actuation = detail::readCartesianActuation(doc, m["actuation"], ptr + "/actuation");
  try {
    return std::make_shared<sim::CartesianMachine>(
        std::move(layout), std::move(errors), std::move(actuation));
  } catch (const InvalidArgument& ex) {
    doc.fail(ptr, ex.what());
  }
}

std::string resolve(const std::string& spec, const std::string& base_dir) {
  if (base_dir.empty() || std::filesystem::path(spec).is_absolute()) return spec;
  const std::filesystem::path p = std::filesystem::path(base_dir) / spec;
  std::error_code ec;
  return std::filesystem::is_regular_file(p, ec) ? p.string() : spec;
}

std::shared_ptr<sim::VirtualMachine> readHybrid(const JsonDoc& doc,
                                                const json& m,
                                                const std::string& ptr,
                                                const std::string& base_dir,
                                                Scenario& out) {
  doc.onlyKeys(m, ptr, {"kind", "machine", "errors", "tripod_errors"});
  out.machine_spec = doc.string(m, ptr, "machine", kDefaultExechonMachine);
  out.errors_spec = doc.string(m, ptr, "errors", "");
  const ExechonMachine machine = loadExechonMachine(resolve(out.machine_spec, base_dir));
  if (!machine.hybrid)
    doc.fail(ptr + "/machine",
             fmt::format("machine '{}' has no \"hybrid\" section", out.machine_spec));
  kinematics::GeometricErrors errors;
  if (!out.errors_spec.empty()) errors = loadGeometricErrors(resolve(out.errors_spec, base_dir));
  std::optional<sim::HybridTripod> tripod;  // none (the chain exactly) when absent or all zero
  if (m.contains("tripod_errors")) {
    const std::string tp = ptr + "/tripod_errors";
    const sim::ExechonTripodErrors t = detail::readTripodErrors(doc, m["tripod_errors"], tp);
    try {
      if (!t.isZero()) tripod.emplace(machine.model, t, machine.fk);
    } catch (const InvalidArgument& ex) {
      doc.fail(tp, ex.what());
    }
  }
  try {
    return std::make_shared<sim::HybridVirtualMachine>(
        *machine.hybrid, std::move(errors), std::move(tripod));
  } catch (const InvalidArgument& ex) {
    doc.fail(ptr, ex.what());
  }
}

}  // namespace

Scenario parseScenarioJson(const std::string& text,
                           const std::string& source,
                           const std::string& base_dir) {
  const json root = detail::parseJson(text, source);
  const JsonDoc doc(text, source);
  doc.onlyKeys(
      root,
      "",
      {"schema", "type", "name", "description", "seed", "machine", "measurements", "environment"});
  if (doc.string(root, "", "schema", "pkm.scenario/1") != "pkm.scenario/1")
    doc.fail("/schema", "must be \"pkm.scenario/1\"");
  if (doc.string(root, "", "type", "") != "simulation_scenario")
    doc.fail("/type", "must be \"simulation_scenario\"");
  Scenario out;
  out.text = text;
  out.source = source;
  out.campaign.name = doc.string(root, "", "name", std::filesystem::path(source).stem().string());
  out.campaign.description = doc.string(root, "", "description", "");
  const double seed = doc.number(root, "", "seed", 1.0);
  if (seed != std::floor(seed) || seed < 0 || seed >= kMaxSeed)
    doc.fail("/seed", "must be an integer in [0, 2^53)");
  out.seed = static_cast<std::uint64_t>(seed);
  const json& m = doc.required(root, "", "machine");
  out.machine_kind = doc.string(m, "/machine", "kind", "");
  if (out.machine_kind == "cartesian")
    out.campaign.machine = readCartesian(doc, m, "/machine");
  else if (out.machine_kind == "hybrid")
    out.campaign.machine = readHybrid(doc, m, "/machine", base_dir, out);
  else if (out.machine_kind == "hexapod") {
    out.machine_spec = doc.string(m, "/machine", "machine", kDefaultMachine);
    out.campaign.machine =
        detail::readHexapod(doc, m, "/machine", resolve(out.machine_spec, base_dir));
  } else
    doc.fail("/machine/kind", "must be \"cartesian\", \"hybrid\" or \"hexapod\"");
  if (root.contains("environment"))
    out.campaign.environment = detail::readEnvironment(doc, root["environment"], "/environment");
  const json& list = doc.required(root, "", "measurements");
  if (!list.is_array()) doc.fail("/measurements", "expected an array");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string ptr = fmt::format("/measurements/{}", i);
    const std::string instrument = doc.string(list[i], ptr, "instrument", "laser");
    if (instrument == "dial_gauges")
      out.campaign.constrained.push_back(detail::readDialGauges(doc, list[i], ptr));
    else if (instrument == "laser_tracker" && out.machine_kind == "hybrid" &&
             doc.string(list[i], ptr, "mode", "pkm") == "hybrid")
      out.campaign.hybrid_trackers.push_back(detail::readHybridTracker(doc, list[i], ptr));
    else if (instrument == "laser_tracker" && out.machine_kind == "hybrid") {
      if (doc.string(list[i], ptr, "mode", "pkm") != "pkm")
        doc.fail(ptr + "/mode", "on a hybrid machine: \"pkm\" (default) or \"hybrid\"");
      out.campaign.exechon_trackers.push_back(detail::readExechonTracker(doc, list[i], ptr));
    } else if (instrument == "laser_tracker")
      out.campaign.trackers.push_back(detail::readTracker(doc, list[i], ptr));
    else if (instrument == "touch_probe")
      out.campaign.probes.push_back(detail::readTouchProbe(
          doc, list[i], ptr, out.machine_kind, resolve(out.machine_spec, base_dir), out.campaign));
    else if (instrument == "laser")
      out.campaign.measurements.push_back(
          detail::readLineSetup(doc, list[i], ptr, *out.campaign.machine));
    else
      doc.fail(ptr + "/instrument",
               "must be \"laser\" (default), \"dial_gauges\", \"laser_tracker\" or "
               "\"touch_probe\"");
  }
  sim::applyProbeEnvironment(out.campaign);
  sim::applyMachineEnvironment(out.campaign);
  try {
    sim::applyGeometryEnvironment(out.campaign, out.seed);
    out.campaign.validate();
    sim::validateTrackers(out.campaign);
  } catch (const InvalidArgument& e) {
    doc.fail("/measurements", e.what());
  }
  return out;
}

}  // namespace pkm::io
