#include <cmath>

#include "io/detail/exechon_tripod_keys.hpp"
#include "io/detail/joint_rates_json.hpp"
#include "io/detail/json_doc.hpp"
#include "pkm/core/error.hpp"
#include "pkm/geometry/so3.hpp"
#include "pkm/io/exechon_machine.hpp"
#include "pkm/io/hexapod_machine.hpp"
#include "pkm/io/number_format.hpp"

namespace pkm::io {

namespace kin = pkm::kinematics;
using detail::json;
using detail::JsonDoc;

namespace {

using detail::kTripodKeyCount;
using detail::kTripodKeys;
using detail::tripodField;

void readTripod(const JsonDoc& doc, const json& t, kin::ExechonTripodGeometry& g) {
  const std::string ptr = "/tripod";
  doc.onlyKeys(t,
               ptr,
               {"dA",
                "dB",
                "dC",
                "l12A",
                "l12C",
                "pA",
                "pB",
                "pC",
                "hA",
                "hC",
                "hx",
                "hz",
                "l12B",
                "l23B",
                "branch"});
  for (int i = 0; i < kTripodKeyCount; ++i) {
    const char* key = kTripodKeys[i];
    // dA, dB, dC are required: a tripod without a base is a typo, not a default.
    if (i < 3) doc.required(t, ptr, key);
    *tripodField(g, i) = doc.number(t, ptr, key, 0.0);
  }
  if (t.contains("branch")) {
    const json& b = t["branch"];
    const std::string bp = ptr + "/branch";
    doc.onlyKeys(b, bp, {"delta1B", "delta2B", "deltaA", "deltaC"});
    g.delta1B = doc.sign(b, bp, "delta1B", 1);
    g.delta2B = doc.sign(b, bp, "delta2B", 1);
    g.deltaA = doc.sign(b, bp, "deltaA", 1);
    g.deltaC = doc.sign(b, bp, "deltaC", 1);
  }
}

void readRange(const JsonDoc& doc,
               const json& obj,
               const std::string& ptr,
               const char* key,
               kin::AngleRange& r) {
  if (!obj.contains(key)) return;
  const auto [lo, hi] = doc.range(obj[key], ptr + "/" + key, degToRad(1.0));
  r.min = lo;
  r.max = hi;
}

void readWrist(const JsonDoc& doc, const json& w, kin::ExechonWrist& wrist) {
  const std::string ptr = "/wrist";
  doc.onlyKeys(w, ptr, {"c_axis", "a_axis", "c0_deg", "a0_deg", "c_sign", "a_sign", "tool_length"});
  if (w.contains("c_axis")) wrist.c_axis = doc.vec3(w["c_axis"], ptr + "/c_axis");
  if (w.contains("a_axis")) wrist.a_axis = doc.vec3(w["a_axis"], ptr + "/a_axis");
  wrist.c0 = degToRad(doc.number(w, ptr, "c0_deg", 0.0));
  wrist.a0 = degToRad(doc.number(w, ptr, "a0_deg", 0.0));
  wrist.c_sign = doc.sign(w, ptr, "c_sign", 1);
  wrist.a_sign = doc.sign(w, ptr, "a_sign", 1);
  wrist.tool_length = doc.number(w, ptr, "tool_length", 0.0);
}

/// [x, y, z] of a working-volume bound; null means unbounded on that axis (`unbounded` =
/// ±infinity).
Eigen::Vector3d boundVec(const JsonDoc& doc,
                         const json& v,
                         const std::string& ptr,
                         double unbounded) {
  if (!v.is_array() || v.size() != 3)
    doc.fail(ptr, "expected an array of 3 numbers (null = unbounded)");
  Eigen::Vector3d out;
  for (std::size_t i = 0; i < 3; ++i)
    out[static_cast<Eigen::Index>(i)] =
        v[i].is_null() ? unbounded : doc.number(v[i], fmt::format("{}/{}", ptr, i));
  return out;
}

void readHybrid(const JsonDoc& doc, const json& h, kin::HybridMachineModel& m) {
  const std::string ptr = "/hybrid";
  doc.onlyKeys(
      h, ptr, {"x2_stroke", "y2_stroke", "pkm_min", "pkm_max", "X2_p_P", "P_p_tcp0", "Y2_p_work"});
  if (h.contains("x2_stroke"))
    std::tie(m.x2_stroke.min, m.x2_stroke.max) = doc.range(h["x2_stroke"], ptr + "/x2_stroke");
  if (h.contains("y2_stroke"))
    std::tie(m.y2_stroke.min, m.y2_stroke.max) = doc.range(h["y2_stroke"], ptr + "/y2_stroke");
  if (h.contains("pkm_min")) m.pkm_min = boundVec(doc, h["pkm_min"], ptr + "/pkm_min", -INFINITY);
  if (h.contains("pkm_max")) m.pkm_max = boundVec(doc, h["pkm_max"], ptr + "/pkm_max", INFINITY);
  if (h.contains("X2_p_P")) m.X2_p_P = doc.vec3(h["X2_p_P"], ptr + "/X2_p_P");
  if (h.contains("P_p_tcp0")) m.P_p_tcp0 = doc.vec3(h["P_p_tcp0"], ptr + "/P_p_tcp0");
  if (h.contains("Y2_p_work")) m.Y2_p_work = doc.vec3(h["Y2_p_work"], ptr + "/Y2_p_work");
  for (int i = 0; i < 3; ++i)
    if (m.pkm_min[i] > m.pkm_max[i]) doc.fail(ptr + "/pkm_min", "pkm_min is larger than pkm_max");
}

/// Reads "legs": three {"length_offset", "stroke"} (A, B, C).
void readLegs(const JsonDoc& doc, const json& root, kin::ExechonModel& model) {
  if (!root.contains("legs")) return;
  const json& legs = root["legs"];
  if (!legs.is_array() || legs.size() != kin::kExechonLegs)
    doc.fail("/legs", "expected an array of 3 legs (A, B, C)");
  for (std::size_t i = 0; i < legs.size(); ++i) {
    const std::string ptr = fmt::format("/legs/{}", i);
    doc.onlyKeys(legs[i], ptr, {"length_offset", "stroke"});
    model.legs[i].length_offset = doc.number(legs[i], ptr, "length_offset", 0.0);
    if (legs[i].contains("stroke"))
      std::tie(model.legs[i].min_reading, model.legs[i].max_reading) =
          doc.range(legs[i]["stroke"], ptr + "/stroke");
  }
}

/// Reads "limits": the joint-angle ranges (degrees).
void readLimits(const JsonDoc& doc, const json& root, kin::ExechonModel& model) {
  if (!root.contains("limits")) return;
  const json& l = root["limits"];
  doc.onlyKeys(l, "/limits", {"alpha_deg", "beta_deg", "c_deg", "a_deg"});
  readRange(doc, l, "/limits", "alpha_deg", model.limits.alpha);
  readRange(doc, l, "/limits", "beta_deg", model.limits.beta);
  readRange(doc, l, "/limits", "c_deg", model.limits.c);
  readRange(doc, l, "/limits", "a_deg", model.limits.a);
}

/// Reads "world_T_zoppi": {"position", "rpy_deg"}.
void readWorldTZoppi(const JsonDoc& doc, const json& root, kin::ExechonModel& model) {
  if (!root.contains("world_T_zoppi")) return;
  const json& t = root["world_T_zoppi"];
  doc.onlyKeys(t, "/world_T_zoppi", {"position", "rpy_deg"});
  Eigen::Vector3d p = Eigen::Vector3d::Zero(), rpy = Eigen::Vector3d::Zero();
  if (t.contains("position")) p = doc.vec3(t["position"], "/world_T_zoppi/position");
  if (t.contains("rpy_deg")) rpy = doc.vec3(t["rpy_deg"], "/world_T_zoppi/rpy_deg") * degToRad(1.0);
  model.world_T_zoppi.setIdentity();
  model.world_T_zoppi.linear() = geometry::rotationFromRpy(rpy);
  model.world_T_zoppi.translation() = p;
}

/// Reads the required "home": {"alpha_deg", "beta_deg", "h", "c_deg", "a_deg"}.
void readHome(const JsonDoc& doc, const json& root, kin::ExechonModel& model) {
  const json& home = doc.required(root, "", "home");
  doc.onlyKeys(home, "/home", {"alpha_deg", "beta_deg", "h", "c_deg", "a_deg"});
  doc.required(home, "/home", "h");
  model.home.e = {degToRad(doc.number(home, "/home", "alpha_deg", 0.0)),
                  degToRad(doc.number(home, "/home", "beta_deg", 0.0)),
                  doc.number(home, "/home", "h", 0.0)};
  model.home.c = degToRad(doc.number(home, "/home", "c_deg", 0.0));
  model.home.a = degToRad(doc.number(home, "/home", "a_deg", 0.0));
}

/// Reads "hybrid" (the machine's serial axes) into m.hybrid and validates it.
void readHybridSection(const JsonDoc& doc, const json& root, ExechonMachine& m) {
  if (!root.contains("hybrid")) return;
  m.hybrid.emplace();
  m.hybrid->name = m.model.name;
  m.hybrid->unit = m.model.unit;
  readHybrid(doc, root["hybrid"], *m.hybrid);
  try {
    m.hybrid->validate();
  } catch (const InvalidArgument& e) {
    doc.fail("/hybrid", e.what());
  }
}

}  // namespace

ExechonMachine parseExechonJson(const std::string& text, const std::string& source) {
  const json root = detail::parseJson(text, source);
  const JsonDoc doc(text, source);
  if (!root.is_object()) doc.fail("", "expected an object");
  if (doc.string(root, "", "type", "") != "exechon")
    doc.fail("/type", "this reader handles \"type\": \"exechon\" machines");
  doc.onlyKeys(root,
               "",
               {"schema",
                "type",
                "name",
                "description",
                "units",
                "tripod",
                "legs",
                "limits",
                "wrist",
                "world_T_zoppi",
                "home",
                "max_condition",
                "forward_kinematics",
                "joint_rates",
                "hybrid"});
  ExechonMachine m;
  m.source = source;
  kin::ExechonModel& model = m.model;
  model.name = doc.string(root, "", "name", "exechon");
  m.description = doc.string(root, "", "description", "");
  model.unit = detail::readSchemaAndUnits(doc, root, "pkm.machine/1");

  readTripod(doc, doc.required(root, "", "tripod"), model.tripod);
  readLegs(doc, root, model);
  readLimits(doc, root, model);
  if (root.contains("wrist")) readWrist(doc, root["wrist"], model.wrist);
  readWorldTZoppi(doc, root, model);
  readHome(doc, root, model);
  model.max_condition = doc.number(root, "", "max_condition", model.max_condition);
  if (root.contains("forward_kinematics"))
    detail::readFkOptions(doc, root["forward_kinematics"], m.fk);
  if (root.contains("joint_rates"))
    m.joint_rates = detail::readJointRates(doc, root["joint_rates"], "/joint_rates", true);
  readHybridSection(doc, root, m);
  try {
    model.validate();
  } catch (const InvalidArgument& e) {
    doc.fail("", e.what());
  }
  return m;
}

ExechonMachine readExechonJson(const std::string& path) {
  return parseExechonJson(readTextFile(path), path);
}

}  // namespace pkm::io
