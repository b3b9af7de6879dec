// Touch-probe measurements of a scenario (docs/formats.md, "Scenario files", "truth.json").
#include "io/scenario_probe.hpp"

#include <fmt/format.h>

#include <memory>

#include "io/scenario_detail.hpp"
#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/io/number_format.hpp"
#include "pkm/simulation/hybrid_virtual_machine.hpp"

namespace pkm::io::detail {

namespace sim = pkm::simulation;

namespace {

Eigen::Vector2d vec2(const JsonDoc& doc, const json& v, const std::string& ptr) {
  if (!v.is_array() || v.size() != 2) doc.fail(ptr, "expected an array of 2 numbers");
  return {doc.number(v[0], ptr + "/0"), doc.number(v[1], ptr + "/1")};
}

std::string array(std::initializer_list<double> v) {
  std::string out = "[";
  bool first = true;
  for (const double x : v) {
    out += (first ? "" : ", ") + formatNumber(x);
    first = false;
  }
  return out + "]";
}

}  // namespace

sim::TouchProbeSetup readTouchProbe(const JsonDoc& doc,
                                    const json& obj,
                                    const std::string& ptr,
                                    const std::string& machine_kind,
                                    const std::string& machine_path,
                                    const sim::Campaign& campaign) {
  doc.onlyKeys(obj,
               ptr,
               {"name",
                "instrument",
                "offset_ring_center",
                "circle_ring_center",
                "ring_diameter",
                "ring_form",
                "ball_radius",
                "stylus_offset",
                "direction",
                "circle_points",
                "runs",
                "start_angle_deg",
                "noise"});
  if (machine_kind != "hybrid")
    doc.fail(ptr + "/instrument", "a touch probe needs a \"hybrid\" (Exechon) machine");
  sim::TouchProbeSetup s;
  s.name = measurementName(doc, obj, ptr);
  for (const auto& m : campaign.measurements)
    if (m.name == s.name) doc.fail(ptr + "/name", "another measurement has this name");
  for (const auto& m : campaign.constrained)
    if (m.name == s.name) doc.fail(ptr + "/name", "another measurement has this name");
  for (const auto& m : campaign.trackers)
    if (m.name == s.name) doc.fail(ptr + "/name", "another measurement has this name");
  for (const auto& m : campaign.probes)
    if (m.name == s.name) doc.fail(ptr + "/name", "another measurement has this name");
  if (obj.contains("offset_ring_center"))
    s.offset_ring_center = doc.vec3(obj["offset_ring_center"], ptr + "/offset_ring_center");
  if (obj.contains("circle_ring_center"))
    s.circle_ring_center = doc.vec3(obj["circle_ring_center"], ptr + "/circle_ring_center");
  s.ring_diameter = doc.number(obj, ptr, "ring_diameter", s.ring_diameter);
  s.ring_form = doc.number(obj, ptr, "ring_form", s.ring_form);
  s.ball_radius = doc.number(obj, ptr, "ball_radius", s.ball_radius);
  if (obj.contains("stylus_offset"))
    s.stylus_offset = vec2(doc, obj["stylus_offset"], ptr + "/stylus_offset");
  if (obj.contains("direction")) s.direction = doc.vec3(obj["direction"], ptr + "/direction");
  s.circle_points = integer(doc, obj, ptr, "circle_points", s.circle_points, 4, 100000);
  s.runs = integer(doc, obj, ptr, "runs", s.runs, 1, 1000);
  s.start_angle = degToRad(doc.number(obj, ptr, "start_angle_deg", 0.0));
  if (obj.contains("noise")) s.noise = readNoise(doc, obj["noise"], ptr + "/noise", 1.0);
  s.machine =
      std::make_shared<const kinematics::ExechonModel>(loadExechonMachine(machine_path).model);
  // The machine's tripod errors move the tool at every touch (the campaign's machine owns it).
  if (const auto* hybrid = dynamic_cast<const sim::HybridVirtualMachine*>(campaign.machine.get());
      hybrid != nullptr && hybrid->tripod())
    s.tripod = std::shared_ptr<const sim::HybridTripod>(campaign.machine, &*hybrid->tripod());
  try {
    s.validate();
  } catch (const InvalidArgument& e) {
    doc.fail(ptr, e.what());
  }
  return s;
}

std::string touchProbeTruthJson(const sim::Campaign& campaign) {
  if (campaign.probes.empty()) return {};
  std::string out = ",\n  \"touch_probes\": [";
  for (std::size_t i = 0; i < campaign.probes.size(); ++i) {
    const sim::TouchProbeSetup& s = campaign.probes[i];
    const Eigen::Vector2d& d = s.stylus_offset;
    out += fmt::format(
        "{}\n    {{\"name\": \"{}\", \"stylus_offset\": {}, \"o_probe\": {}, "
        "\"ring_diameter\": {}, \"ring_form\": {}, \"ball_radius\": {}, \"ball_path_radius\": {},\n"
        "     \"offset_ring_center\": {}, \"circle_ring_center\": {}, \"direction\": {}}}",
        i ? "," : "",
        s.name,
        array({d.x(), d.y()}),
        array({-d.x(), -d.y()}),
        formatNumber(s.ring_diameter),
        formatNumber(s.ring_form),
        formatNumber(s.ball_radius),
        formatNumber(s.ring_diameter / 2.0 - s.ball_radius),
        array({s.offset_ring_center.x(), s.offset_ring_center.y(), s.offset_ring_center.z()}),
        array({s.circle_ring_center.x(), s.circle_ring_center.y(), s.circle_ring_center.z()}),
        array({s.direction.x(), s.direction.y(), s.direction.z()}));
  }
  return out + "\n  ]";
}

}  // namespace pkm::io::detail
