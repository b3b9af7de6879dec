#include "pkm/io/linuxcnc_exechon.hpp"

#include <fmt/format.h>

#include <cmath>
#include <initializer_list>
#include <string_view>

#include "pkm/core/units.hpp"

namespace pkm::io {

namespace {

/// One `name v1 v2 ...` line; infinities as `inf`/`-inf` (strtod reads them).
void line(std::string& out, std::string_view name, std::initializer_list<double> values) {
  out += name;
  for (const double v : values) {
    if (std::isinf(v))
      out += v > 0.0 ? " inf" : " -inf";
    else
      out += fmt::format(" {}", v);
  }
  out += '\n';
}

void rangeLine(std::string& out, std::string_view name, const kinematics::AngleRange& range) {
  line(out, name, {radToDeg(range.min), radToDeg(range.max)});
}

void tripodLines(std::string& out, const kinematics::ExechonTripodGeometry& g) {
  out += "# Zoppi's tripod (docs/conventions.md, \"Exechon tripod\"), machine length unit\n";
  const std::pair<std::string_view, double> lengths[] = {{"dA", g.dA},
                                                         {"dB", g.dB},
                                                         {"dC", g.dC},
                                                         {"l12A", g.l12A},
                                                         {"l12C", g.l12C},
                                                         {"l12B", g.l12B},
                                                         {"l23B", g.l23B},
                                                         {"pA", g.pA},
                                                         {"pB", g.pB},
                                                         {"pC", g.pC},
                                                         {"hA", g.hA},
                                                         {"hC", g.hC},
                                                         {"hx", g.hx},
                                                         {"hz", g.hz}};
  for (const auto& [name, value] : lengths) line(out, name, {value});
  line(out, "delta1B", {static_cast<double>(g.delta1B)});
  line(out, "delta2B", {static_cast<double>(g.delta2B)});
  line(out, "deltaA", {static_cast<double>(g.deltaA)});
  line(out, "deltaC", {static_cast<double>(g.deltaC)});
}

void legAndLimitLines(std::string& out, const kinematics::ExechonModel& m) {
  out += "# legs A, B, C: reading + length_offset = geometric length; stroke of the reading\n";
  line(out,
       "length_offset",
       {m.legs[0].length_offset, m.legs[1].length_offset, m.legs[2].length_offset});
  line(out, "stroke_min", {m.legs[0].min_reading, m.legs[1].min_reading, m.legs[2].min_reading});
  line(out, "stroke_max", {m.legs[0].max_reading, m.legs[1].max_reading, m.legs[2].max_reading});
  out += "# angle ranges [min, max], degrees (inf: open)\n";
  rangeLine(out, "alpha_range_deg", m.limits.alpha);
  rangeLine(out, "beta_range_deg", m.limits.beta);
  rangeLine(out, "c_range_deg", m.limits.c);
  rangeLine(out, "a_range_deg", m.limits.a);
}

void wristAndFrameLines(std::string& out, const kinematics::ExechonModel& m) {
  const kinematics::ExechonWrist& w = m.wrist;
  out += "# C/A wrist (docs/conventions.md, \"C/A wrist\"): axes in the platform frame\n";
  line(out, "c_axis", {w.c_axis.x(), w.c_axis.y(), w.c_axis.z()});
  line(out, "a_axis", {w.a_axis.x(), w.a_axis.y(), w.a_axis.z()});
  line(out, "c0_deg", {radToDeg(w.c0)});
  line(out, "a0_deg", {radToDeg(w.a0)});
  line(out, "c_sign", {static_cast<double>(w.c_sign)});
  line(out, "a_sign", {static_cast<double>(w.a_sign)});
  line(out, "tool_length", {w.tool_length});
  out += "# world_T_zoppi: rotation (row-major) and the Zoppi origin in the world frame\n";
  const Eigen::Matrix3d R = m.world_T_zoppi.linear();
  line(out,
       "world_R_zoppi",
       {R(0, 0), R(0, 1), R(0, 2), R(1, 0), R(1, 1), R(1, 2), R(2, 0), R(2, 1), R(2, 2)});
  const Eigen::Vector3d p = m.world_T_zoppi.translation();
  line(out, "world_p_zoppi", {p.x(), p.y(), p.z()});
}

}  // namespace

std::string linuxcncExechonParameters(const ExechonMachine& machine) {
  const kinematics::ExechonModel& m = machine.model;
  std::string out =
      fmt::format("# pkmexechonkins parameters of the Exechon '{}' ({}), written by pkm; unit {}\n",
                  m.name,
                  machine.source,
                  toString(m.unit));
  tripodLines(out, m.tripod);
  legAndLimitLines(out, m);
  wristAndFrameLines(out, m);
  out += "# home configuration (alpha, beta, h, C, A)\n";
  line(out, "home_alpha_deg", {radToDeg(m.home.e[0])});
  line(out, "home_beta_deg", {radToDeg(m.home.e[1])});
  line(out, "home_h", {m.home.e[2]});
  line(out, "home_c_deg", {radToDeg(m.home.c)});
  line(out, "home_a_deg", {radToDeg(m.home.a)});
  out += "# limits of the solvers\n";
  line(out, "max_condition", {m.max_condition});
  line(out, "fk_tolerance", {machine.fk.tolerance});
  line(out, "fk_max_iterations", {static_cast<double>(machine.fk.max_iterations)});
  line(out, "fk_max_backtracks", {static_cast<double>(machine.fk.max_backtracks)});
  line(out, "fk_singular_pivot_ratio", {machine.fk.singular_pivot_ratio});
  return out;
}

}  // namespace pkm::io
