/// @file
/// @brief Shared by the linuxcnc_hal tests: a kinematics.hal and hexapod.ini written like
/// LinuxCNC's hexapod-sim sample, genhexkins reference strut lengths, and a fixture writing them to
/// a fresh folder per test.
#pragma once

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>
#include <vector>

#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/io/linuxcnc_hal.hpp"
#include "pkm/kinematics/hexapod_data.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"
#include "support/sample_models.hpp"
#include "support/scratch_files.hpp"
#include "support/tolerances.hpp"

namespace pkm::test {

/// Reference strut lengths of the LinuxCNC hexapod-sim (genhexkins), inch, 6 decimals.
struct GenhexkinsReference {
  double pose[6];  ///< x y z (inch) a b c (deg)
  double lengths[6];
};
inline const GenhexkinsReference kReference[] = {
    {{0, 0, 20, 0, 0, 0}, {29.746680, 29.746680, 29.746715, 29.746363, 29.746363, 29.746715}},
    {{2, -1, 22, 3, -4, 10}, {31.597194, 31.713899, 29.975223, 32.850082, 27.921167, 33.441616}},
    {{-3, 2, 18, 10, 10, -15}, {30.022945, 29.402324, 29.682443, 25.351693, 33.820068, 24.667812}},
};

/// The pose x y z a b c (angles in degrees) of a reference row.
inline kinematics::PoseRpy poseOf(const double (&v)[6]) {
  kinematics::PoseRpy p;
  p.position = {v[0], v[1], v[2]};
  p.rpy = {degToRad(v[3]), degToRad(v[4]), degToRad(v[5])};
  return p;
}

/// Expects the IK of `model` at every reference pose to give genhexkins's strut lengths.
inline void expectReferenceLengths(const kinematics::HexapodModel& model) {
  kinematics::HexapodData data(model);
  for (const GenhexkinsReference& r : kReference) {
    const kinematics::StrutVector& q = kinematics::inverseKinematics(model, data, poseOf(r.pose));
    for (int i = 0; i < kinematics::kStruts; ++i)
      EXPECT_NEAR(q[i], r.lengths[i], kTolLinuxcnc) << "pose z " << r.pose[2] << " strut " << i;
  }
}

/// kinematics.hal as in the hexapod-sim sample configuration (written here, not copied), one entry
/// per line: line n is lines[n - 1]. `platform_z` moves the platform joints along the platform z
/// axis: -20 gives a geometry that is not singular at home 0 0 0 0 0 0 (used where no INI supplies
/// HOME).
inline std::vector<std::string> simHalLines(double platform_z = 0.0) {
  const kinematics::HexapodModel sim = linuxcncSimModel();
  std::vector<std::string> lines;
  char buf[128];
  lines.emplace_back("# Base joints positions in base (world) coordinates");  // 1
  for (int i = 0; i < kinematics::kStruts; ++i)                               // 2..19
    for (int a = 0; a < 3; ++a) {
      std::snprintf(buf,
                    sizeof buf,
                    "setp genhexkins.base.%d.%c %7.3f",
                    i,
                    "xyz"[a],
                    sim.struts[static_cast<std::size_t>(i)].world_p_base[a]);
      lines.emplace_back(buf);
    }
  lines.emplace_back("");                                                     // 20
  lines.emplace_back("# Platform joints positions in platform coordinates");  // 21
  for (int i = 0; i < kinematics::kStruts; ++i)                               // 22..39
    for (int a = 0; a < 3; ++a) {
      std::snprintf(buf,
                    sizeof buf,
                    "setp genhexkins.platform.%d.%c %7.3f",
                    i,
                    "xyz"[a],
                    sim.struts[static_cast<std::size_t>(i)].platform_p_joint[a] +
                        (a == 2 ? platform_z : 0.0));
      lines.emplace_back(buf);
    }
  lines.emplace_back("");                                                            // 40
  lines.emplace_back("net tool-offset genhexkins.tool-offset motion.tooloffset.z");  // 41
  lines.emplace_back("# setp genhexkins.convergence-criterion 1e-9");                // 42
  return lines;
}

/// 1-based line number of the line starting with `prefix`.
inline std::size_t lineOf(const std::vector<std::string>& lines, const std::string& prefix) {
  for (std::size_t n = 0; n < lines.size(); ++n)
    if (lines[n].starts_with(prefix)) return n + 1;
  ADD_FAILURE() << "no line " << prefix;
  return 0;
}

/// The lines joined, each ended by a newline.
inline std::string join(const std::vector<std::string>& lines) {
  std::string out;
  for (const auto& l : lines) out += l + "\n";
  return out;
}

/// hexapod.ini lines; HOME is line 10, LINEAR_UNITS line 11, [JOINT_n] MIN_LIMIT line 13 + 3n.
inline std::vector<std::string> simIniLines(const std::string& halfile = "kinematics.hal") {
  std::vector<std::string> lines = {
      "[EMC]",                        // 1
      "MACHINE = pkm test hexapod",   // 2
      "[KINS]",                       // 3
      "KINEMATICS = genhexkins",      // 4
      "JOINTS = 6",                   // 5
      "[HAL]",                        // 6
      "HALFILE = LIB:basic_sim.tcl",  // 7
      "HALFILE = " + halfile,         // 8
      "[TRAJ]",                       // 9
      "HOME = 0 0 20 0 0 0",          // 10
      "LINEAR_UNITS = inch",          // 11
  };
  for (int j = 0; j < 6; ++j) {
    lines.push_back("[JOINT_" + std::to_string(j) + "]");
    lines.emplace_back("MIN_LIMIT = -1000.0");
    lines.emplace_back("MAX_LIMIT = 1000.0");
  }
  return lines;
}

/// A fresh folder per test (removed afterwards) to write the HAL and INI files into.
class LinuxcncHalTest : public ScratchDirTest {
 protected:
  LinuxcncHalTest() : ScratchDirTest("hal_test") {}
  std::string writeHal(const std::vector<std::string>& lines,
                       const std::string& name = "kinematics.hal") const {
    return write(name, join(lines));
  }
  std::string writeIni(const std::vector<std::string>& lines,
                       const std::string& name = "hexapod.ini") const {
    return write(name, join(lines));
  }

  /// The IoError message of reading `hal` with `options` ("" when it does not throw).
  static std::string errorOf(const std::string& hal, const io::HalReadOptions& options = {}) {
    try {
      (void)io::readLinuxcncHal(hal, options);
    } catch (const IoError& e) {
      return e.what();
    }
    return {};
  }
};

/// Whether any notice contains `text`.
inline bool anyContains(const std::vector<std::string>& notices, const std::string& text) {
  for (const auto& n : notices)
    if (n.find(text) != std::string::npos) return true;
  return false;
}

}  // namespace pkm::test
