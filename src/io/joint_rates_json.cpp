#include "io/detail/joint_rates_json.hpp"

#include <fmt/format.h>

#include <cmath>

#include "pkm/io/joint_rates.hpp"
#include "pkm/io/number_format.hpp"

namespace pkm::io {

namespace detail {

JointRateSpec readJointRates(const JsonDoc& doc,
                             const json& v,
                             const std::string& ptr,
                             bool wrist) {
  if (wrist)
    doc.onlyKeys(
        v, ptr, {"velocity", "acceleration", "wrist_velocity_deg", "wrist_acceleration_deg"});
  else
    doc.onlyKeys(v, ptr, {"velocity", "acceleration"});
  JointRateSpec r;
  const auto positive = [&](const char* key) {
    const double x = doc.number(v, ptr, key, std::numeric_limits<double>::quiet_NaN());
    if (v.contains(key) && !(x > 0.0)) doc.fail(ptr + "/" + key, "must be > 0");
    return x;
  };
  r.velocity = positive("velocity");
  r.acceleration = positive("acceleration");
  if (wrist) {
    r.wrist_velocity_deg = positive("wrist_velocity_deg");
    r.wrist_acceleration_deg = positive("wrist_acceleration_deg");
  }
  return r;
}

}  // namespace detail

std::string jointRatesJson(const JointRateSpec& rates, bool wrist) {
  std::string out = "\"joint_rates\": {";
  bool first = true;
  const auto add = [&](const char* key, double value) {
    if (std::isnan(value)) return;
    out += fmt::format("{}\"{}\": {}", first ? "" : ", ", key, formatNumber(value));
    first = false;
  };
  add("velocity", rates.velocity);
  add("acceleration", rates.acceleration);
  if (wrist) {
    add("wrist_velocity_deg", rates.wrist_velocity_deg);
    add("wrist_acceleration_deg", rates.wrist_acceleration_deg);
  }
  return out + "}";
}

}  // namespace pkm::io
