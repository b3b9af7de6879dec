// The `pkm gcode run` report as text and JSON (io/gcode_run_report.hpp).
#include "pkm/io/gcode_run_report.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "pkm/io/number_format.hpp"

namespace pkm::io {

namespace {

using Json = nlohmann::ordered_json;

Json eventJson(const GcodeCheckEvent& e) {
  Json j;
  j["line"] = e.line;
  j["position"] = std::vector<double>(e.position.begin(), e.position.end());
  j["item"] = e.item;
  j["value"] = e.value;
  j["limit"] = e.limit;
  j["margin"] = e.margin;
  j["unit"] = e.unit;
  return j;
}

Json checksJson(const std::vector<GcodeCheckSummary>& checks) {
  Json all;
  for (const GcodeCheckSummary& c : checks) {
    Json j;
    j["enabled"] = c.enabled;
    if (!c.enabled && !c.off_reason.empty()) j["off_reason"] = c.off_reason;
    j["violations"] = c.violations;
    j["unit"] = c.unit;
    if (c.enabled && std::isfinite(c.worst.margin)) j["worst"] = eventJson(c.worst);
    if (c.violations > 0) j["first_violation"] = eventJson(c.first);
    all[c.name] = j;
  }
  return all;
}

/// The settings lines: program, orientation, interpolation, limits, cycle time.
void appendSettings(const GcodeRunReport& r, std::string& s) {
  s += fmt::format("gcode run: {} on {} ({} lines, {} motions, {} points)\n",
                   r.program,
                   r.machine,
                   r.lines,
                   r.motions,
                   r.points);
  if (r.exechon())
    s += fmt::format("orientation: {} (A/C words are {})\n",
                     r.orientation,
                     r.orientation == "vector" ? "the tool vector's angles in the world frame"
                                               : "the wrist axes' readings");
  // Lengths in the machine's unit (the report's JSON keeps mm, as its keys say).
  const double per_mm = r.units == "inch" ? 1.0 / 25.4 : 1.0;
  s += fmt::format(
      "interpolation: tolerance {} {}, max step {:.4g} {}, max rotary step {:.4g} deg\n",
      fmt::format("{:.4g}", r.tolerance_mm * per_mm),
      r.units,
      r.max_step_mm * per_mm,
      r.units,
      r.max_angle_step_deg);
  s += fmt::format("limits: joint velocity {} {}/s, joint acceleration {} {}/s^2, ",
                   r.max_joint_velocity,
                   r.units,
                   r.max_joint_acceleration,
                   r.units);
  if (r.exechon())
    s += fmt::format("wrist velocity {} deg/s, wrist acceleration {} deg/s^2, ",
                     r.max_wrist_velocity_deg_per_s,
                     r.max_wrist_acceleration_deg_per_s2);
  const std::vector<std::string>& from = r.limits_from_machine_file;
  s +=
      fmt::format("rapid {} {}/min{}\n",
                  fmt::format("{:.6g}", r.rapid_rate_mm_per_min * per_mm),
                  r.units,
                  from.empty() ? std::string()
                               : fmt::format(" ({} from the machine file)", fmt::join(from, ", ")));
  if (!r.rapid_limits.empty()) s += fmt::format("rapid limits: {}\n", r.rapid_limits);
  s += fmt::format(
      "cycle time: {:.3f} s{}\n",
      r.cycle_time_s,
      r.dwell_time_s > 0.0 ? fmt::format(" (dwells {:.3f} s)", r.dwell_time_s) : std::string());
}

/// "-" for a margin that no evaluation set (+infinity), else the margin and its unit.
std::string marginText(const GcodeCheckEvent& e) {
  if (std::isinf(e.margin)) return "-";
  return fmt::format("{:.4g} {}", e.margin, e.unit);
}

void appendTable(const GcodeRunReport& r, std::string& s) {
  s += fmt::format("{:<19} {:<9} {:>10} {:>14} {:>7}  {}\n",
                   "check",
                   "status",
                   "violations",
                   "worst margin",
                   "line",
                   "item");
  for (const GcodeCheckSummary& c : r.checks) {
    const char* status = !c.enabled ? "n/a" : c.violations > 0 ? "VIOLATED" : "ok";
    if (!c.enabled) {
      s += c.off_reason.empty() ? fmt::format("{:<19} {:<9}\n", c.name, status)
                                : fmt::format("{:<19} {:<9} {}\n", c.name, status, c.off_reason);
      continue;
    }
    s += fmt::format("{:<19} {:<9} {:>10} {:>14} {:>7}  {}\n",
                     c.name,
                     status,
                     c.violations,
                     marginText(c.worst),
                     std::isfinite(c.worst.margin) ? std::to_string(c.worst.line) : "-",
                     c.worst.item);
  }
}

void appendViolations(const GcodeRunReport& r, std::string& s) {
  // Positions in the machine's unit: mm exactly as computed, inches to 6 significant digits.
  const auto position = [&r](double mm) {
    return r.units == "inch" ? fmt::format("{:.6g}", mm / 25.4) : formatNumber(mm);
  };
  for (const GcodeCheckSummary& c : r.checks) {
    if (c.violations == 0) continue;
    const GcodeCheckEvent& e = c.first;
    s += fmt::format(
        "{}:{}: {} violated first at X{} Y{} Z{} A{} B{} C{}: {} value {:.6g}, "
        "limit {:.6g}, margin {:.4g} {}\n",
        r.program,
        e.line,
        c.name,
        position(e.position[0]),
        position(e.position[1]),
        position(e.position[2]),
        formatNumber(e.position[3]),
        formatNumber(e.position[4]),
        formatNumber(e.position[5]),
        e.item,
        e.value,
        e.limit,
        e.margin,
        e.unit);
  }
}

}  // namespace

std::string gcodeRunJson(const GcodeRunReport& r) {
  Json j;
  j["program"] = r.program;
  j["machine"] = r.machine;
  j["machine_type"] = r.machine_type;
  j["units"] = r.units;
  if (r.exechon()) j["orientation"] = r.orientation;
  j["tolerance_mm"] = r.tolerance_mm;
  j["max_step_mm"] = r.max_step_mm;
  j["max_angle_step_deg"] = r.max_angle_step_deg;
  j["max_joint_velocity"] = r.max_joint_velocity;
  j["max_joint_acceleration"] = r.max_joint_acceleration;
  if (r.exechon()) {
    j["max_wrist_velocity_deg_per_s"] = r.max_wrist_velocity_deg_per_s;
    j["max_wrist_acceleration_deg_per_s2"] = r.max_wrist_acceleration_deg_per_s2;
  }
  j["rapid_rate_mm_per_min"] = r.rapid_rate_mm_per_min;
  j["limits_from_machine_file"] = r.limits_from_machine_file;
  if (!r.rapid_limits.empty()) j["rapid_limits"] = r.rapid_limits;
  j["motions"] = r.motions;
  j["points"] = r.points;
  j["cycle_time_s"] = r.cycle_time_s;
  j["dwell_time_s"] = r.dwell_time_s;
  j["ok"] = r.ok;
  j["checks"] = checksJson(r.checks);
  return j.dump(2) + "\n";
}

std::string gcodeRunText(const GcodeRunReport& r) {
  std::string s;
  appendSettings(r, s);
  appendTable(r, s);
  appendViolations(r, s);
  s += r.ok ? "result: all checks pass\n" : "result: VIOLATIONS (exit code 1)\n";
  return s;
}

}  // namespace pkm::io
