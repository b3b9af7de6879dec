// The Exechon machine description writer (pkm.machine/1, "type": "exechon";
// io/exechon_machine.hpp): the layout parseExechonJson reads, numbers in their shortest round-trip
// form.
#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "io/detail/exechon_tripod_keys.hpp"
#include "pkm/core/units.hpp"
#include "pkm/geometry/so3.hpp"
#include "pkm/io/exechon_machine.hpp"
#include "pkm/io/joint_rates.hpp"
#include "pkm/io/number_format.hpp"

namespace pkm::io {

namespace kin = pkm::kinematics;
using detail::kTripodKeyCount;
using detail::kTripodKeys;
using detail::kZoppiKeys;
using detail::tripodField;
using nlohmann::json;

namespace {

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

/// Appends "tripod": the dimensions (leg B's offsets only when non-zero) and the branch signs.
void appendTripod(std::string& out, kin::ExechonTripodGeometry t) {
  out += "  \"tripod\": {";
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
}

/// Appends "legs" and "limits" (degrees).
void appendLegsAndLimits(std::string& out, const kin::ExechonModel& m) {
  const double deg = radToDeg(1.0);
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
}

/// Appends "wrist", "world_T_zoppi" and "home" (degrees).
void appendWristAndHome(std::string& out, const kin::ExechonModel& m) {
  const double deg = radToDeg(1.0);
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
}

/// Appends "hybrid": the serial axes' strokes, the PKM bounds and the frame offsets.
void appendHybrid(std::string& out, const kin::HybridMachineModel& h) {
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

}  // namespace

std::string writeExechonJson(const ExechonMachine& machine) {
  const kin::ExechonModel& m = machine.model;
  std::string out = "{\n  \"schema\": \"pkm.machine/1\",\n  \"type\": \"exechon\",\n";
  out += fmt::format("  \"name\": {},\n", json(m.name).dump());
  out += fmt::format("  \"description\": {},\n", json(machine.description).dump());
  out += fmt::format("  \"units\": \"{}\",\n", toString(m.unit));
  appendTripod(out, m.tripod);
  appendLegsAndLimits(out, m);
  appendWristAndHome(out, m);
  out += fmt::format("  \"max_condition\": {},\n", formatNumber(m.max_condition));
  out += fmt::format("  \"forward_kinematics\": {{\"tolerance\": {}, \"max_iterations\": {}}}",
                     formatNumber(machine.fk.tolerance),
                     machine.fk.max_iterations);
  if (machine.joint_rates) out += ",\n  " + jointRatesJson(*machine.joint_rates, true);
  if (machine.hybrid) appendHybrid(out, *machine.hybrid);
  out += "\n}\n";
  return out;
}

}  // namespace pkm::io
