// The pkmhexkins parameter file: pkm's writer (io::linuxcncHexapodParameters) read back by the
// component's C parser (src/linuxcnc/pkmhexkins_params.c, compiled as C) gives the same model,
// and the parser refuses bad files with "line N: ..." / "missing NAME" / the geometry's reason.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>

#include "pkm/core/units.hpp"
#include "pkm/io/linuxcnc_hexapod_params.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"
#include "pkmhexkins_core.h"

namespace pkm::test {
namespace PKM_TEST_NS {

/// Parses `text`; the reason on failure ("" on success).
std::string parse(const std::string& text, pkm_hex_params& p) {
  char why[256] = "";
  return pkm_hex_parse_params(text.c_str(), &p, why, sizeof why) == 0 ? std::string() : why;
}

/// The machine with all 42 parameters, the tool, spindle offset and home moved (fixed seed).
io::HexapodMachine calibrated(io::HexapodMachine machine, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.05, 0.05);
  auto& m = machine.model;
  for (auto& s : m.struts) {
    for (int k = 0; k < 3; ++k) {
      s.world_p_base[k] += u(rng);
      s.platform_p_joint[k] += u(rng);
    }
    s.length_offset += u(rng);
  }
  m.tool_offset = {u(rng), u(rng), 1.0 / 3.0};
  m.spindle_offset = 0.1 + u(rng);
  m.home.position += Eigen::Vector3d(u(rng), u(rng), u(rng));
  m.home.rpy = {degToRad(1.0 / 3.0), degToRad(-2.5), degToRad(7.25)};
  machine.fk.tolerance = 2e-10;
  machine.fk.max_iterations = 77;
  return machine;
}

void expectSameModel(const io::HexapodMachine& machine, const pkm_hex_params& p) {
  const auto& m = machine.model;
  for (int i = 0; i < PKM_HEX_STRUTS; ++i) {
    const auto& s = m.struts[static_cast<std::size_t>(i)];
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(p.geometry.base[i][k], s.world_p_base[k]) << "strut " << i;
      EXPECT_EQ(p.geometry.platform[i][k], s.platform_p_joint[k]) << "strut " << i;
    }
    EXPECT_EQ(p.geometry.length_offset[i], s.length_offset) << "strut " << i;
  }
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(p.geometry.tool[k], m.tool_offset[k]);
    EXPECT_EQ(p.home[k], m.home.position[k]);
    // Degrees in the file: one rounding each way.
    EXPECT_NEAR(degToRad(p.home[3 + k]), m.home.rpy[k], 4e-16 * (1.0 + std::abs(m.home.rpy[k])));
  }
  EXPECT_EQ(p.geometry.spindle_offset, m.spindle_offset);
  EXPECT_EQ(p.options.tolerance, machine.fk.tolerance);
  EXPECT_EQ(p.options.max_iterations, machine.fk.max_iterations);
  EXPECT_EQ(p.options.max_backtracks, machine.fk.max_backtracks);
  EXPECT_EQ(p.options.singular_pivot_ratio, machine.fk.singular_pivot_ratio);
  EXPECT_EQ(p.options.max_step_translation, machine.fk.max_step_translation);
  EXPECT_EQ(p.options.max_step_rotation, machine.fk.max_step_rotation);
  EXPECT_EQ(p.options.continuation_step, machine.fk.continuation_step);
  EXPECT_TRUE(std::isinf(p.options.max_error));
}

TEST(HexkinsParams, WriterRoundTripsThroughTheComponentsParser) {
  for (const std::string& name : io::builtinMachineNames("hexapod")) {
    for (const std::uint32_t seed : {0u, 1u, 2u}) {
      const io::HexapodMachine machine =
          seed == 0 ? io::builtinMachine(name) : calibrated(io::builtinMachine(name), seed);
      SCOPED_TRACE(name + " seed " + std::to_string(seed));
      pkm_hex_params p{};
      const std::string text = io::linuxcncHexapodParameters(machine);
      ASSERT_EQ(parse(text, p), "") << text;
      expectSameModel(machine, p);
      // The same kinematics: the C inverse of the parsed file equals the library's at home.
      const auto& m = machine.model;
      double R[3][3];
      const double rpy[3] = {m.home.rpy.x(), m.home.rpy.y(), m.home.rpy.z()};
      pkm_hex_rotation_from_rpy(rpy, R);
      const double position[3] = {m.home.position.x(), m.home.position.y(), m.home.position.z()};
      double q[PKM_HEX_STRUTS];
      ASSERT_EQ(pkm_hex_inverse(&p.geometry, position, R, q), 0);
      kinematics::HexapodData data(m);
      const kinematics::StrutVector want = kinematics::inverseKinematics(m, data, m.home);
      for (int i = 0; i < PKM_HEX_STRUTS; ++i)
        EXPECT_NEAR(q[i], want[i], 1e-12 * (1.0 + std::abs(want[i]))) << "strut " << i;
    }
  }
}

TEST(HexkinsParams, BadFilesFailWithTheLineOrTheMissingName) {
  const std::string good =
      io::linuxcncHexapodParameters(io::builtinMachine("hexapod-linuxcnc-sim"));
  pkm_hex_params p{};
  ASSERT_EQ(parse(good, p), "");
  const auto replaced = [&](const std::string& from, const std::string& to) {
    std::string text = good;
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return text.replace(at, from.size(), to);
  };
  const auto lineOf = [&](const std::string& what) {
    return 1 + std::count(good.begin(), good.begin() + static_cast<long>(good.find(what)), '\n');
  };
  const std::string tool_line =
      good.substr(good.find("tool "), good.find('\n', good.find("tool ")) - good.find("tool ") + 1);
  const pkm_hex_params before = p;
  EXPECT_EQ(parse(replaced(tool_line, ""), p), "missing tool");
  EXPECT_EQ(std::memcmp(&p, &before, sizeof p), 0) << "a failed parse leaves the parameters";
  EXPECT_EQ(
      parse(replaced("spindle-offset", "spindel-offset"), p),
      "line " + std::to_string(lineOf("spindle-offset")) + ": unknown parameter 'spindel-offset'");
  EXPECT_EQ(
      parse(replaced("length-offset.2 0", "length-offset.2"), p),
      "line " + std::to_string(lineOf("length-offset.2")) + ": length-offset.2 needs 1 number");
  EXPECT_EQ(parse(replaced("limit-iterations 120", "limit-iterations 12.5"), p),
            "line " + std::to_string(lineOf("limit-iterations")) +
                ": limit-iterations needs 1 whole number");
  const std::string twice_tool = parse(good + "tool 0 0 0\n", p);
  EXPECT_EQ(twice_tool,
            "line " + std::to_string(1 + std::count(good.begin(), good.end(), '\n')) +
                ": tool given twice");
  EXPECT_EQ(parse(replaced("convergence-criterion 1e-09", "convergence-criterion 0"), p),
            "convergence-criterion must be > 0");
  EXPECT_EQ(parse(replaced("base.0 -22.95 13.25 0", "base.0 nan 13.25 0"), p),
            "a geometry value is not finite");
  // Geometries that do not assemble: one strut twice; platform joints on one line.
  // (base.4 is base.3 in this 3-3 hexapod; platform.4 becomes platform.3.)
  EXPECT_EQ(parse(replaced("platform.4 -9.459 -6.616 0", "platform.4 9.459 -6.616 0"), p),
            "struts 3 and 4 join the same joints");
  std::string line = good;  // platform joints on one line: turns about it are free
  for (int i = 0; i < PKM_HEX_STRUTS; ++i) {
    const std::string key = "platform." + std::to_string(i) + " ";
    const auto at = line.find(key);
    line.replace(at, line.find('\n', at) - at, key + std::to_string(2 * i - 5) + " 0 0");
  }
  EXPECT_NE(parse(line, p).find("singular at the home pose"), std::string::npos) << parse(line, p);
}

TEST(HexkinsParams, LoadReadsAFileAndNamesAFileItCannotRead) {
  char why[256] = "";
  pkm_hex_params p{};
  EXPECT_EQ(pkm_hex_load_params("/nonexistent/pkm.params", &p, why, sizeof why), -1);
  EXPECT_STREQ(why, "cannot read /nonexistent/pkm.params");
  const std::string path = ::testing::TempDir() + "pkmhexkins-params-test.params";
  {
    std::FILE* f = std::fopen(path.c_str(), "w");
    ASSERT_NE(f, nullptr);
    const std::string text = io::linuxcncHexapodParameters(io::builtinMachine("hexapod-default"));
    std::fputs(text.c_str(), f);
    std::fclose(f);
  }
  EXPECT_EQ(pkm_hex_load_params(path.c_str(), &p, why, sizeof why), 0) << why;
  std::remove(path.c_str());
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::test
