// A scenario environment's "geometry" (docs/formats.md, "Scenario files";
// docs/simulation-errors.md, "Geometry the kinematic models cannot represent") and the drawn
// geometry in truth.json.
#include <fmt/format.h>

#include <string>

#include "io/scenario_detail.hpp"
#include "pkm/io/number_format.hpp"
#include "pkm/simulation/campaign.hpp"
#include "pkm/simulation/hexapod_virtual_machine.hpp"
#include "pkm/simulation/hybrid_virtual_machine.hpp"

namespace pkm::io::detail {

namespace sim = pkm::simulation;

namespace {

std::string leadJson(const sim::ScrewLeadError& e) {
  return fmt::format(
      "{{\"progressive_ppm\": {}, \"reference_mm\": {}, \"wave_um\": {}, \"wave_length_mm\": {}, "
      "\"wave_phase_rad\": {}, \"periodic_um\": {}, \"lead_mm\": {}, \"periodic_phase_rad\": {}}}",
      formatNumber(e.progressive * 1e6),
      formatNumber(e.reference),
      formatNumber(e.wave_amplitude * 1e3),
      formatNumber(e.wave_length),
      formatNumber(e.wave_phase),
      formatNumber(e.periodic_amplitude * 1e3),
      formatNumber(e.lead),
      formatNumber(e.periodic_phase));
}

std::string jointJson(const sim::UJointOffset& j) {
  return fmt::format("{{\"first_axis\": [{}, {}, {}], \"offset_um\": {}}}",
                     formatNumber(j.first_axis.x()),
                     formatNumber(j.first_axis.y()),
                     formatNumber(j.first_axis.z()),
                     formatNumber(j.offset * 1e3));
}

template <typename List, typename Write>
std::string list(const List& items, Write write) {
  std::string out = "[";
  for (std::size_t i = 0; i < items.size(); ++i)
    out += (i ? ",\n      " : "\n      ") + write(items[i]);
  return out + "]";
}

}  // namespace

void readGeometry(const JsonDoc& doc,
                  const json& obj,
                  const std::string& ptr,
                  sim::GeometryEnvironment& g) {
  doc.onlyKeys(obj,
               ptr,
               {"enabled",
                "lead_progressive_ppm",
                "lead_wave_um",
                "lead_wave_length_mm",
                "lead_periodic_um",
                "screw_lead_mm",
                "joint_axis_offset_um"});
  g.enabled = true;
  if (obj.contains("enabled")) {
    if (!obj["enabled"].is_boolean()) doc.fail(ptr + "/enabled", "expected true or false");
    g.enabled = obj["enabled"].get<bool>();
  }
  g.lead_progressive = doc.number(obj, ptr, "lead_progressive_ppm", g.lead_progressive * 1e6) / 1e6;
  g.lead_wave_mm = doc.number(obj, ptr, "lead_wave_um", g.lead_wave_mm * 1e3) / 1e3;
  g.lead_wave_length_mm = doc.number(obj, ptr, "lead_wave_length_mm", g.lead_wave_length_mm);
  g.lead_periodic_mm = doc.number(obj, ptr, "lead_periodic_um", g.lead_periodic_mm * 1e3) / 1e3;
  g.screw_lead_mm = doc.number(obj, ptr, "screw_lead_mm", g.screw_lead_mm);
  g.joint_axis_offset_mm =
      doc.number(obj, ptr, "joint_axis_offset_um", g.joint_axis_offset_mm * 1e3) / 1e3;
  std::string why;
  if (!g.isValid(&why)) doc.fail(ptr, why);
}

std::string geometryTruthJson(const sim::Campaign& campaign) {
  if (const auto* h = dynamic_cast<const sim::HexapodVirtualMachine*>(campaign.machine.get())) {
    const sim::HexapodUnmodelledGeometry& g = h->unmodelledGeometry();
    if (g.isZero()) return "";
    return fmt::format(
        ",\n  \"unmodelled_geometry\": {{\n    \"strut_lead\": {},\n    \"base_joint\": {},\n    "
        "\"platform_joint\": {}\n  }}",
        list(g.lead, leadJson),
        list(g.base_joint, jointJson),
        list(g.platform_joint, jointJson));
  }
  if (const auto* y = dynamic_cast<const sim::HybridVirtualMachine*>(campaign.machine.get());
      y != nullptr && y->tripod()) {
    const sim::ExechonLegLeadErrors& lead = y->tripod()->legLeadErrors();
    bool zero = true;
    for (const sim::ScrewLeadError& e : lead) zero = zero && e.isZero();
    if (zero) return "";
    return fmt::format(",\n  \"unmodelled_geometry\": {{\n    \"leg_lead\": {}\n  }}",
                       list(lead, leadJson));
  }
  return "";
}

}  // namespace pkm::io::detail
