// The hexapod parts of a scenario (docs/formats.md, "Scenario files"): the true hexapod and the
// constrained-motion (dial gauge) measurements of Lee et al. ("Development of a Parallel-Typed CNC
// Machine").
#include "io/scenario_detail.hpp"
#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/io/machine_loader.hpp"

namespace pkm::io::detail {

namespace sim = pkm::simulation;
namespace kin = pkm::kinematics;

namespace {

/// Six [x, y, z] vectors.
std::array<Eigen::Vector3d, kin::kStruts> sixVectors(const JsonDoc& doc,
                                                     const json& v,
                                                     const std::string& ptr) {
  if (!v.is_array() || v.size() != kin::kStruts)
    doc.fail(ptr, "expected an array of 6 [x, y, z] vectors");
  std::array<Eigen::Vector3d, kin::kStruts> out;
  for (std::size_t i = 0; i < kin::kStruts; ++i)
    out[i] = doc.vec3(v[i], fmt::format("{}/{}", ptr, i));
  return out;
}

/// Six numbers, or one number for all six.
kin::StrutVector sixNumbers(const JsonDoc& doc, const json& v, const std::string& ptr) {
  if (v.is_number()) return kin::StrutVector::Constant(doc.number(v, ptr));
  if (!v.is_array() || v.size() != kin::kStruts)
    doc.fail(ptr, "expected a number or an array of 6 numbers");
  kin::StrutVector out;
  for (std::size_t i = 0; i < kin::kStruts; ++i)
    out[static_cast<Eigen::Index>(i)] = doc.number(v[i], fmt::format("{}/{}", ptr, i));
  return out;
}

}  // namespace

std::shared_ptr<sim::VirtualMachine> readHexapod(const JsonDoc& doc,
                                                 const json& m,
                                                 const std::string& ptr,
                                                 const std::string& machine_path) {
  doc.onlyKeys(m, ptr, {"kind", "machine", "errors", "actuation"});
  const HexapodMachine machine = loadHexapodMachine(machine_path);
  sim::HexapodAssemblyErrors errors;
  if (m.contains("errors")) {
    const json& e = m["errors"];
    const std::string ep = ptr + "/errors";
    doc.onlyKeys(e, ep, {"base_joint", "platform_joint", "length_offset"});
    if (e.contains("base_joint"))
      errors.base_joint = sixVectors(doc, e["base_joint"], ep + "/base_joint");
    if (e.contains("platform_joint"))
      errors.platform_joint = sixVectors(doc, e["platform_joint"], ep + "/platform_joint");
    if (e.contains("length_offset"))
      errors.length_offset = sixNumbers(doc, e["length_offset"], ep + "/length_offset");
  }
  sim::StrutActuation act;
  if (m.contains("actuation")) {
    const json& a = m["actuation"];
    const std::string ap = ptr + "/actuation";
    doc.onlyKeys(a, ap, {"encoder_resolution", "backlash", "repeatability_sigma"});
    act.encoder_resolution = doc.number(a, ap, "encoder_resolution", 0.0);
    if (a.contains("backlash")) act.backlash = sixNumbers(doc, a["backlash"], ap + "/backlash");
    act.repeatability_sigma = doc.number(a, ap, "repeatability_sigma", 0.0);
  }
  try {
    return std::make_shared<sim::HexapodVirtualMachine>(machine.model, errors, act);
  } catch (const InvalidArgument& ex) {
    doc.fail(ptr, ex.what());
  }
}

sim::DialGaugeSetup readDialGauges(const JsonDoc& doc, const json& obj, const std::string& ptr) {
  doc.onlyKeys(obj,
               ptr,
               {"name",
                "instrument",
                "reference",
                "stations",
                "gauge_points",
                "table_normal",
                "noise",
                "tolerance",
                "max_iterations"});
  sim::DialGaugeSetup s;
  s.name = measurementName(doc, obj, ptr);
  const json& ref = doc.required(obj, ptr, "reference");
  if (!ref.is_array() || ref.size() != 6)
    doc.fail(ptr + "/reference", "expected [x, y, z, a, b, c] (mm, deg)");
  s.reference = Eigen::VectorXd(6);
  for (std::size_t i = 0; i < 6; ++i) {
    const double v = doc.number(ref[i], fmt::format("{}/reference/{}", ptr, i));
    s.reference[static_cast<Eigen::Index>(i)] = i < 3 ? v : degToRad(v);
  }
  const json& st = doc.required(obj, ptr, "stations");
  if (!st.is_array() || st.empty())
    doc.fail(ptr + "/stations", "expected a non-empty array of [dx, dy, dc_deg]");
  for (std::size_t j = 0; j < st.size(); ++j) {
    Eigen::Vector3d v = doc.vec3(st[j], fmt::format("{}/stations/{}", ptr, j));
    v[2] = degToRad(v[2]);
    s.stations.push_back(v);
  }
  if (obj.contains("gauge_points")) {
    const json& g = obj["gauge_points"];
    if (!g.is_array() || g.size() != 3)
      doc.fail(ptr + "/gauge_points", "expected 3 [x, y, z] points");
    for (std::size_t k = 0; k < 3; ++k)
      s.gauge_points[k] = doc.vec3(g[k], fmt::format("{}/gauge_points/{}", ptr, k));
  }
  if (obj.contains("table_normal"))
    s.table_normal = doc.vec3(obj["table_normal"], ptr + "/table_normal");
  if (obj.contains("noise")) s.noise = readNoise(doc, obj["noise"], ptr + "/noise", 1.0);
  s.tolerance = doc.number(obj, ptr, "tolerance", s.tolerance);
  s.max_iterations = integer(doc, obj, ptr, "max_iterations", s.max_iterations, 1, 1000);
  try {
    s.validate();
  } catch (const InvalidArgument& e) {
    doc.fail(ptr, e.what());
  }
  return s;
}

}  // namespace pkm::io::detail
