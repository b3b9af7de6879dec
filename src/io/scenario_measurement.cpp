// One element of a scenario's "measurements" array (docs/formats.md, "Scenario files").
#include <cmath>

#include "io/scenario_detail.hpp"
#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"

namespace pkm::io::detail {

namespace sim = pkm::simulation;

namespace {

/// A command: one value per axis, angular axes in degrees (converted to radians).
Eigen::VectorXd command(const JsonDoc& doc,
                        const json& v,
                        const std::string& ptr,
                        const sim::VirtualMachine& machine) {
  const std::vector<bool> angular = machine.angularAxes();
  const auto axes = static_cast<Eigen::Index>(angular.size());
  if (!v.is_array() || static_cast<Eigen::Index>(v.size()) != axes)
    doc.fail(ptr, fmt::format("expected an array of {} axis positions", axes));
  Eigen::VectorXd c(axes);
  for (Eigen::Index i = 0; i < axes; ++i) {
    const double x = doc.number(v[static_cast<std::size_t>(i)], fmt::format("{}/{}", ptr, i));
    c[i] = angular[static_cast<std::size_t>(i)] ? degToRad(x) : x;
  }
  return c;
}

sim::LineQuantity quantity(const JsonDoc& doc, const json& obj, const std::string& ptr) {
  const std::string q = doc.string(obj, ptr, "quantity", "");
  if (q == "linear") return sim::LineQuantity::kLinear;
  if (q == "straightness") return sim::LineQuantity::kStraightness;
  if (q == "angular") return sim::LineQuantity::kAngular;
  doc.fail(ptr + "/quantity", "must be \"linear\", \"straightness\" or \"angular\"");
}

}  // namespace

sim::NoiseModel readNoise(const JsonDoc& doc,
                          const json& obj,
                          const std::string& ptr,
                          double scale) {
  if (obj.is_string()) {
    const auto preset = sim::instrumentNoise(obj.get<std::string>());
    if (!preset)
      doc.fail(ptr, fmt::format("unknown instrument noise '{}'", obj.get<std::string>()));
    return *preset;
  }
  doc.onlyKeys(obj, ptr, {"sigma", "sigma_ppm", "resolution"});
  // `scale`: reading units per model unit (1e6 µrad per rad for angular readings).
  sim::NoiseModel n{doc.number(obj, ptr, "sigma", 0.0) / scale,
                    doc.number(obj, ptr, "sigma_ppm", 0.0),
                    doc.number(obj, ptr, "resolution", 0.0) / scale};
  try {
    n.validate();
  } catch (const InvalidArgument& e) {
    doc.fail(ptr, e.what());
  }
  return n;
}

std::string measurementName(const JsonDoc& doc, const json& obj, const std::string& ptr) {
  const std::string name = doc.string(obj, ptr, "name", "");
  if (name.empty() ||
      name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789-_") != std::string::npos)
    doc.fail(ptr + "/name",
             "required: lower-case letters, digits, '-' and '_' (it names the files)");
  return name;
}

sim::LineSetup readLineSetup(const JsonDoc& doc,
                             const json& obj,
                             const std::string& ptr,
                             const sim::VirtualMachine& machine) {
  doc.onlyKeys(obj,
               ptr,
               {"name",
                "instrument",
                "quantity",
                "procedure",
                "from",
                "to",
                "targets",
                "target_jitter",
                "runs",
                "overshoot",
                "bidirectional",
                "reflector_offset",
                "lateral",
                "misalignment_urad",
                "noise"});
  sim::LineSetup s;
  s.name = measurementName(doc, obj, ptr);
  s.quantity = quantity(doc, obj, ptr);
  const std::string procedure = doc.string(obj, ptr, "procedure", "continuous");
  if (procedure == "step_diagonal")
    s.procedure = sim::LineProcedure::kStepDiagonal;
  else if (procedure != "continuous")
    doc.fail(ptr + "/procedure", "must be \"continuous\" or \"step_diagonal\"");
  const auto axes = static_cast<Eigen::Index>(machine.axisNames().size());
  const Eigen::VectorXd from = command(doc, doc.required(obj, ptr, "from"), ptr + "/from", machine);
  const Eigen::VectorXd to = command(doc, doc.required(obj, ptr, "to"), ptr + "/to", machine);
  const double travel =
      (machine.nominalPose(to).translation() - machine.nominalPose(from).translation()).norm();
  if (!(travel > 0.0)) doc.fail(ptr + "/to", "the line has no nominal tool travel");
  s.line.direction = (to - from) / travel;
  // A single-axis line is measured in that axis's coordinate; any other line from 0 at "from".
  Eigen::Index moving = -1, count = 0;
  for (Eigen::Index i = 0; i < axes; ++i)
    if (to[i] != from[i]) {
      ++count;
      moving = i;
    }
  const double first = count == 1 && to[moving] > from[moving] ? from[moving] : 0.0;
  s.line.start = from - first * s.line.direction;
  s.cycle.first = first;
  s.cycle.last = first + travel;
  s.cycle.targets = integer(doc, obj, ptr, "targets", 11, 2, 100000);
  s.cycle.target_jitter = doc.number(obj, ptr, "target_jitter", 0.0);
  s.cycle.runs = integer(doc, obj, ptr, "runs", 5, 1, 1000);
  s.cycle.overshoot = doc.number(obj, ptr, "overshoot", 0.0);
  if (obj.contains("bidirectional")) {
    if (!obj["bidirectional"].is_boolean())
      doc.fail(ptr + "/bidirectional", "expected true or false");
    s.cycle.bidirectional = obj["bidirectional"].get<bool>();
  }
  if (obj.contains("reflector_offset"))
    s.reflector_offset = doc.vec3(obj["reflector_offset"], ptr + "/reflector_offset");
  if (obj.contains("lateral")) s.lateral = doc.vec3(obj["lateral"], ptr + "/lateral");
  s.misalignment = doc.number(obj, ptr, "misalignment_urad", 0.0) / kUradPerRad;
  const double scale = s.quantity == sim::LineQuantity::kAngular ? kUradPerRad : 1.0;
  if (obj.contains("noise")) s.noise = readNoise(doc, obj["noise"], ptr + "/noise", scale);
  try {
    s.validate();
    if (s.quantity == sim::LineQuantity::kStraightness) {
      const Eigen::Vector3d beam =
          (machine.nominalPose(to).translation() - machine.nominalPose(from).translation()) /
          travel;
      PKM_CHECK((s.lateral - s.lateral.dot(beam) * beam).norm() > 1e-6,
                "the lateral direction is parallel to the line");
    }
  } catch (const InvalidArgument& e) {
    doc.fail(ptr, e.what());
  }
  return s;
}

}  // namespace pkm::io::detail
