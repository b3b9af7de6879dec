#include <cmath>

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

/// Zoppi's 12 dimensions, then leg B's base-joint offsets (written only when non-zero).
constexpr const char* kTripodKeys[] = {
    "dA", "dB", "dC", "l12A", "l12C", "pA", "pB", "pC", "hA", "hC", "hx", "hz", "l12B", "l23B"};
constexpr int kZoppiKeys = 12;
constexpr int kTripodKeyCount = 14;

double* tripodField(kin::ExechonTripodGeometry& t, int i) {
  double* fields[] = {&t.dA,
                      &t.dB,
                      &t.dC,
                      &t.l12A,
                      &t.l12C,
                      &t.pA,
                      &t.pB,
                      &t.pC,
                      &t.hA,
                      &t.hC,
                      &t.hx,
                      &t.hz,
                      &t.l12B,
                      &t.l23B};
  return fields[i];
}

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

std::string rangeText(double lo, double hi, double scale) {
  const auto bound = [scale](double v) {
    return std::isfinite(v) ? formatNumber(v * scale) : std::string("null");
  };
  return fmt::format("[{}, {}]", bound(lo), bound(hi));
}

std::string vecText(const Eigen::Vector3d& v) {
  return fmt::format("[{}, {}, {}]", formatNumber(v.x()), formatNumber(v.y()), formatNumber(v.z()));
}

/// As vecText with null for an infinite (unbounded) element.
std::string boundText(const Eigen::Vector3d& v) {
  const auto bound = [](double x) {
    return std::isfinite(x) ? formatNumber(x) : std::string("null");
  };
  return fmt::format("[{}, {}, {}]", bound(v.x()), bound(v.y()), bound(v.z()));
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
  if (root.contains("legs")) {
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
  if (root.contains("limits")) {
    const json& l = root["limits"];
    doc.onlyKeys(l, "/limits", {"alpha_deg", "beta_deg", "c_deg", "a_deg"});
    readRange(doc, l, "/limits", "alpha_deg", model.limits.alpha);
    readRange(doc, l, "/limits", "beta_deg", model.limits.beta);
    readRange(doc, l, "/limits", "c_deg", model.limits.c);
    readRange(doc, l, "/limits", "a_deg", model.limits.a);
  }
  if (root.contains("wrist")) readWrist(doc, root["wrist"], model.wrist);
  if (root.contains("world_T_zoppi")) {
    const json& t = root["world_T_zoppi"];
    doc.onlyKeys(t, "/world_T_zoppi", {"position", "rpy_deg"});
    Eigen::Vector3d p = Eigen::Vector3d::Zero(), rpy = Eigen::Vector3d::Zero();
    if (t.contains("position")) p = doc.vec3(t["position"], "/world_T_zoppi/position");
    if (t.contains("rpy_deg"))
      rpy = doc.vec3(t["rpy_deg"], "/world_T_zoppi/rpy_deg") * degToRad(1.0);
    model.world_T_zoppi.setIdentity();
    model.world_T_zoppi.linear() = geometry::rotationFromRpy(rpy);
    model.world_T_zoppi.translation() = p;
  }
  const json& home = doc.required(root, "", "home");
  doc.onlyKeys(home, "/home", {"alpha_deg", "beta_deg", "h", "c_deg", "a_deg"});
  doc.required(home, "/home", "h");
  model.home.e = {degToRad(doc.number(home, "/home", "alpha_deg", 0.0)),
                  degToRad(doc.number(home, "/home", "beta_deg", 0.0)),
                  doc.number(home, "/home", "h", 0.0)};
  model.home.c = degToRad(doc.number(home, "/home", "c_deg", 0.0));
  model.home.a = degToRad(doc.number(home, "/home", "a_deg", 0.0));
  model.max_condition = doc.number(root, "", "max_condition", model.max_condition);
  if (root.contains("forward_kinematics"))
    detail::readFkOptions(doc, root["forward_kinematics"], m.fk);
  if (root.contains("joint_rates"))
    m.joint_rates = detail::readJointRates(doc, root["joint_rates"], "/joint_rates", true);
  if (root.contains("hybrid")) {
    m.hybrid.emplace();
    m.hybrid->name = model.name;
    m.hybrid->unit = model.unit;
    readHybrid(doc, root["hybrid"], *m.hybrid);
    try {
      m.hybrid->validate();
    } catch (const InvalidArgument& e) {
      doc.fail("/hybrid", e.what());
    }
  }
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

std::string writeExechonJson(const ExechonMachine& machine) {
  const kin::ExechonModel& m = machine.model;
  const double deg = radToDeg(1.0);
  std::string out = "{\n  \"schema\": \"pkm.machine/1\",\n  \"type\": \"exechon\",\n";
  out += fmt::format("  \"name\": {},\n", json(m.name).dump());
  out += fmt::format("  \"description\": {},\n", json(machine.description).dump());
  out += fmt::format("  \"units\": \"{}\",\n  \"tripod\": {{", toString(m.unit));
  kin::ExechonTripodGeometry t = m.tripod;
  for (int i = 0; i < kTripodKeyCount; ++i) {
    if (i >= kZoppiKeys && *tripodField(t, i) == 0.0) continue;  // an ideal S joint
    out += fmt::format("{}\"{}\": {}",
                       i == 0 ? "" : (i % 6 == 0 ? ",\n             " : ", "),
                       kTripodKeys[i],
                       formatNumber(*tripodField(t, i)));
  }
  out += fmt::format(
      ",\n             \"branch\": {{\"delta1B\": {}, \"delta2B\": {}, \"deltaA\": {}, \"deltaC\": "
      "{}}}}},\n",
      t.delta1B,
      t.delta2B,
      t.deltaA,
      t.deltaC);
  out += "  \"legs\": [\n";
  for (int i = 0; i < kin::kExechonLegs; ++i) {
    const kin::ExechonLeg& l = m.legs[static_cast<std::size_t>(i)];
    out += fmt::format("    {{\"length_offset\": {}, \"stroke\": {}}}{}\n",
                       formatNumber(l.length_offset),
                       rangeText(l.min_reading, l.max_reading, 1.0),
                       i + 1 < kin::kExechonLegs ? "," : "");
  }
  out += "  ],\n";
  out += fmt::format(
      "  \"limits\": {{\"alpha_deg\": {}, \"beta_deg\": {}, \"c_deg\": {}, \"a_deg\": {}}},\n",
      rangeText(m.limits.alpha.min, m.limits.alpha.max, deg),
      rangeText(m.limits.beta.min, m.limits.beta.max, deg),
      rangeText(m.limits.c.min, m.limits.c.max, deg),
      rangeText(m.limits.a.min, m.limits.a.max, deg));
  const kin::ExechonWrist& w = m.wrist;
  out += fmt::format(
      "  \"wrist\": {{\"c_axis\": {}, \"a_axis\": {}, \"c0_deg\": {}, \"a0_deg\": {}, \"c_sign\": "
      "{}, \"a_sign\": {}, "
      "\"tool_length\": {}}},\n",
      vecText(w.c_axis),
      vecText(w.a_axis),
      formatNumber(w.c0 * deg),
      formatNumber(w.a0 * deg),
      w.c_sign,
      w.a_sign,
      formatNumber(w.tool_length));
  out += fmt::format("  \"world_T_zoppi\": {{\"position\": {}, \"rpy_deg\": {}}},\n",
                     vecText(m.world_T_zoppi.translation()),
                     vecText(geometry::rpyFromRotation(m.world_T_zoppi.linear()) * deg));
  out += fmt::format(
      "  \"home\": {{\"alpha_deg\": {}, \"beta_deg\": {}, \"h\": {}, \"c_deg\": {}, \"a_deg\": "
      "{}}},\n",
      formatNumber(m.home.e[0] * deg),
      formatNumber(m.home.e[1] * deg),
      formatNumber(m.home.e[2]),
      formatNumber(m.home.c * deg),
      formatNumber(m.home.a * deg));
  out += fmt::format("  \"max_condition\": {},\n", formatNumber(m.max_condition));
  out += fmt::format("  \"forward_kinematics\": {{\"tolerance\": {}, \"max_iterations\": {}}}",
                     formatNumber(machine.fk.tolerance),
                     machine.fk.max_iterations);
  if (machine.joint_rates) out += ",\n  " + jointRatesJson(*machine.joint_rates, true);
  if (machine.hybrid) {
    const kin::HybridMachineModel& h = *machine.hybrid;
    out += fmt::format(
        ",\n  \"hybrid\": {{\"x2_stroke\": {}, \"y2_stroke\": {},\n             \"pkm_min\": {}, "
        "\"pkm_max\": {},\n"
        "             \"X2_p_P\": {}, \"P_p_tcp0\": {}, \"Y2_p_work\": {}}}",
        rangeText(h.x2_stroke.min, h.x2_stroke.max, 1.0),
        rangeText(h.y2_stroke.min, h.y2_stroke.max, 1.0),
        boundText(h.pkm_min),
        boundText(h.pkm_max),
        vecText(h.X2_p_P),
        vecText(h.P_p_tcp0),
        vecText(h.Y2_p_work));
  }
  out += "\n}\n";
  return out;
}

}  // namespace pkm::io
