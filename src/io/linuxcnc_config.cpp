// LinuxCNC configuration files shared by the hexapod and the Exechon (io/linuxcnc_config.hpp):
// names, options, the INI, the simulator HAL file, the tool table, axis reach and limits.
#include "pkm/io/linuxcnc_config.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "detail/linuxcnc_config_detail.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/number_format.hpp"

namespace pkm::io {

namespace {

bool wordChar(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
         c == '-' || c == '.';
}

/// `name` reduced to a file-name stem of [A-Za-z0-9_.-] ("machine" when nothing is left).
std::string stem(const std::string& name) {
  std::string s;
  for (char c : name) s += wordChar(c) ? c : '-';
  while (!s.empty() && (s.front() == '.' || s.front() == '-')) s.erase(s.begin());
  return s.empty() ? "machine" : s;
}

}  // namespace

void LinuxcncConfigOptions::validate(int joints) const {
  if (display.empty() || !std::all_of(display.begin(), display.end(), wordChar))
    throw InvalidArgument(fmt::format(
        "display '{}': give a LinuxCNC display program name (axis, linuxcncrsh, ...)", display));
  std::set<int> seen;
  for (const LinuxcncCompReference& c : comp_files) {
    if (c.joint < 0 || c.joint >= joints)
      throw InvalidArgument(fmt::format(
          "compensation table for joint {}: the machine has joints 0 to {}", c.joint, joints - 1));
    if (!seen.insert(c.joint).second)
      throw InvalidArgument(
          fmt::format("joint {}: more than one compensation table given", c.joint));
    if (c.file.empty() || !std::all_of(c.file.begin(), c.file.end(), wordChar) ||
        c.file.front() == '.')
      throw InvalidArgument(fmt::format(
          "compensation table name '{}': a file name inside the configuration folder", c.file));
    if (c.type != 0 && c.type != 1)
      throw InvalidArgument(
          fmt::format("joint {}: COMP_FILE_TYPE must be 0 or 1, got {}", c.joint, c.type));
  }
}

LinuxcncConfigNames linuxcncConfigNames(const std::string& machine_name) {
  const std::string s = stem(machine_name);
  return {s + ".ini", "kinematics.hal", "sim.hal", "tool.tbl", s + ".params"};
}

namespace detail {

std::string linuxcncIni(const IniSpec& spec,
                        const LinuxcncConfigNames& names,
                        const LinuxcncConfigOptions& options) {
  const bool inch = spec.unit == LengthUnit::kInch;
  std::string coordinates;
  for (const IniAxis& a : spec.axes)
    coordinates += fmt::format("{}{}", coordinates.empty() ? "" : " ", a.letter);
  std::string o = spec.comment;
  o += fmt::format("\n[EMC]\nVERSION = 1.1\nMACHINE = {}\nDEBUG = 0\n", spec.machine);
  o += fmt::format(
      "\n[DISPLAY]\nDISPLAY = {}\nCYCLE_TIME = 0.100\nPOSITION_OFFSET = RELATIVE\n"
      "POSITION_FEEDBACK = ACTUAL\nMAX_FEED_OVERRIDE = 1.2\n",
      options.display);
  o += fmt::format(
      "\n[RS274NGC]\nPARAMETER_FILE = linuxcnc.var\nRS274NGC_STARTUP_CODE = {} G17 G40 G90\n",
      inch ? "G20" : "G21");
  o += "\n[EMCMOT]\nEMCMOT = motmod\nCOMM_TIMEOUT = 1.0\nSERVO_PERIOD = 1000000\n";
  o += "\n[TASK]\nTASK = milltask\nCYCLE_TIME = 0.010\n";
  o += fmt::format("\n[HAL]\nHALFILE = {}\nHALFILE = {}\n", names.kinematics, names.sim);
  for (const std::string& extra : options.extra_hal_files)
    o += fmt::format("HALFILE = {}\n", extra);
  o += fmt::format("\n[TRAJ]\nCOORDINATES = {}\nLINEAR_UNITS = {}\nANGULAR_UNITS = degree\n",
                   coordinates,
                   inch ? "inch" : "mm");
  o += fmt::format("HOME = {} {} {} {} {} {}\n",
                   formatNumber(spec.home[0]),
                   formatNumber(spec.home[1]),
                   formatNumber(spec.home[2]),
                   formatNumber(spec.home[3]),
                   formatNumber(spec.home[4]),
                   formatNumber(spec.home[5]));
  o += fmt::format(
      "DEFAULT_LINEAR_VELOCITY = {}\nMAX_LINEAR_VELOCITY = {}\nDEFAULT_LINEAR_ACCELERATION = {}\n"
      "MAX_LINEAR_ACCELERATION = {}\nDEFAULT_ANGULAR_VELOCITY = {}\nMAX_ANGULAR_VELOCITY = {}\n",
      formatNumber(spec.linear_velocity / 10.0),
      formatNumber(spec.linear_velocity),
      formatNumber(spec.linear_acceleration),
      formatNumber(spec.linear_acceleration),
      formatNumber(spec.angular_velocity / 10.0),
      formatNumber(spec.angular_velocity));
  o +=
      fmt::format("\n[EMCIO]\nEMCIO = io\nCYCLE_TIME = 0.100\nTOOL_TABLE = {}\n", names.tool_table);
  o += fmt::format("\n[KINS]\nKINEMATICS = {}\nJOINTS = {}\n", spec.kinematics, spec.joints.size());
  for (const IniAxis& a : spec.axes)
    o += fmt::format(
        "\n[AXIS_{}]\nMIN_LIMIT = {}\nMAX_LIMIT = {}\nMAX_VELOCITY = {}\nMAX_ACCELERATION = {}\n",
        a.letter,
        formatNumber(a.min),
        formatNumber(a.max),
        formatNumber(a.velocity),
        formatNumber(a.acceleration));
  for (std::size_t i = 0; i < spec.joints.size(); ++i) {
    const IniJoint& j = spec.joints[i];
    o += fmt::format(
        "\n[JOINT_{}]\nTYPE = {}\nHOME = {}\nHOME_OFFSET = {}\nHOME_SEQUENCE = 0\nMIN_LIMIT = {}\n"
        "MAX_LIMIT = {}\nMAX_VELOCITY = {}\nMAX_ACCELERATION = {}\n",
        i,
        j.angular ? "ANGULAR" : "LINEAR",
        formatNumber(j.home),
        formatNumber(j.home),
        formatNumber(j.min),
        formatNumber(j.max),
        formatNumber(j.velocity),
        formatNumber(j.acceleration));
    for (const LinuxcncCompReference& c : options.comp_files)
      if (c.joint == static_cast<int>(i))
        o += fmt::format("COMP_FILE = {}\nCOMP_FILE_TYPE = {}\n", c.file, c.type);
  }
  return o;
}

std::string simulatorHal(int joints, const std::string& tool_pin) {
  std::string o =
      "# A simulated machine (written by pkm): the motion controller on the servo thread, each\n"
      "# joint's position command looped back as its feedback (no drives), E-stop and tool\n"
      "# changes answered at once. For a real machine, replace this file with its drives' HAL and\n"
      "# keep the tool-offset line.\n"
      "loadrt [EMCMOT]EMCMOT servo_period_nsec=[EMCMOT]SERVO_PERIOD num_joints=[KINS]JOINTS\n"
      "addf motion-command-handler servo-thread\naddf motion-controller servo-thread\n\n"
      "net estop-loop iocontrol.0.user-enable-out => iocontrol.0.emc-enable-in\n"
      "net tool-prepare-loop iocontrol.0.tool-prepare => iocontrol.0.tool-prepared\n"
      "net tool-change-loop iocontrol.0.tool-change => iocontrol.0.tool-changed\n\n";
  for (int j = 0; j < joints; ++j)
    o += fmt::format("net j{0}-pos joint.{0}.motor-pos-cmd => joint.{0}.motor-pos-fb\n", j);
  o += fmt::format(
      "\n# The G43 tool length into the kinematics (added along the tool direction)\n"
      "net tool-offset motion.tooloffset.z => {}\n",
      tool_pin);
  return o;
}

std::string toolTable(LengthUnit unit) {
  return fmt::format("T1 P1 Z0 D0 ;tool 1, length 0 {}: set it with G10 L1 P1 Z...\n",
                     toString(unit));
}

double reach(const std::function<bool(double)>& ok, double cap) {
  constexpr int kSteps = 64;
  double good = 0.0;
  for (int k = 1; k <= kSteps; ++k) {
    const double t = cap * k / kSteps;
    if (ok(t)) {
      good = t;
      continue;
    }
    double bad = t;
    for (int n = 0; n < 50 && bad - good > 1e-12 * cap; ++n) {
      const double mid = 0.5 * (good + bad);
      (ok(mid) ? good : bad) = mid;
    }
    return good;
  }
  return cap;
}

std::array<double, 2> axisLimits(double home, double below, double above, double step) {
  // n / 10^k (or n · 10^k) is the double nearest the decimal, so the limits print short.
  const int e = static_cast<int>(std::lround(std::log10(step)));
  const double scale = std::pow(10.0, std::abs(e));
  auto value = [&](double n) { return e < 0 ? n / scale : n * scale; };
  const double lo = value(std::ceil((home - below) / step));
  const double hi = value(std::floor((home + above) / step));
  return {std::min(lo, home), std::max(hi, home)};
}

double limitStep(double length) { return std::pow(10.0, std::floor(std::log10(length)) - 3.0); }

}  // namespace detail
std::string linuxcncTruthHal(const std::string& program,
                             const std::string& truth,
                             const std::vector<double>& joint_offsets) {
  for (const std::string* v : {&program, &truth})
    PKM_CHECK(!v->empty() && v->find_first_of(" \t\n#") == std::string::npos,
              "'{}': a HAL file cannot name it (empty, whitespace or '#')",
              *v);
  std::string o =
      "# The simulated physical machine (written by pkm linuxcnc config --simulate-truth;\n"
      "# docs/linuxcnc.md, \"A simulated machine in the loop\"): pkm-truth takes each joint's\n"
      "# motor command as the real struts would, moves the true machine of the truth file and\n"
      "# gives its sensors as pins: pkmtruth.gauge-0..2 (three dial gauges on the platform, mm),\n"
      "# pkmtruth.laser-x (a laser along x, mm), pkmtruth.x .. .c (the true pose); a rising edge\n"
      "# of pkmtruth.zero zeroes them. For the real machine, delete this file and its HALFILE\n"
      "# line and connect your gauge interface's pins to the names `pkm calibrate hexapod --live\n"
      "# --gauges` is given.\n";
  std::string offsets;
  for (const double v : joint_offsets) offsets += (offsets.empty() ? "" : ",") + formatNumber(v);
  o += fmt::format("loadusr -Wn pkmtruth {} --truth {} --name pkmtruth --joint-offset {}\n",
                   program,
                   truth,
                   offsets);
  for (std::size_t j = 0; j < joint_offsets.size(); ++j)
    o += fmt::format("net j{}-pos => pkmtruth.joint-{}\n", j, j);
  return o;
}

}  // namespace pkm::io
