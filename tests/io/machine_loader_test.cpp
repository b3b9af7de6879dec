// Tests of pkm::io::loadHexapodMachine and the embedded machines (pkm/io/machine_loader.hpp).
#include "pkm/io/machine_loader.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "pkm/core/error.hpp"
#include "pkm/io/linuxcnc_hal.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"
#include "support/sample_models.hpp"
#include "support/tolerances.hpp"

namespace pkm::io::detail {
// The embedded machine files (generated at build time by cmake/PkmEmbed.cmake).
const std::vector<std::pair<std::string_view, std::string_view>>& embeddedMachines();
}  // namespace pkm::io::detail

namespace PKM_TEST_NS {

namespace fs = std::filesystem;
namespace kin = pkm::kinematics;
using pkm::IoError;
using pkm::io::HexapodMachine;
using pkm::io::loadHexapodMachine;
using ::testing::Contains;
using ::testing::HasSubstr;
using ::testing::Not;
using ::testing::UnorderedElementsAre;

std::string dataFile(const char* stem) {
  return std::string(PKM_SOURCE_DIR) + "/data/machines/" + stem + ".json";
}

void expectSameGeometry(const kin::HexapodModel& a, const kin::HexapodModel& b) {
  EXPECT_EQ(a.unit, b.unit);
  EXPECT_EQ(a.home.position, b.home.position);
  EXPECT_EQ(a.tool_offset, b.tool_offset);
  for (std::size_t i = 0; i < kin::kStruts; ++i) {
    EXPECT_EQ(a.struts[i].world_p_base, b.struts[i].world_p_base) << i;
    EXPECT_EQ(a.struts[i].platform_p_joint, b.struts[i].platform_p_joint) << i;
    EXPECT_EQ(a.struts[i].length_offset, b.struts[i].length_offset) << i;
  }
}

class MachineLoaderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           (std::string("pkm_loader_test_") + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  std::string write(const std::string& name, const std::string& content) const {
    const fs::path p = dir_ / name;
    std::ofstream out(p, std::ios::binary);
    out << content;
    return p.string();
  }
  fs::path dir_;
};

TEST(MachineLoader, BuiltinNames) {
  const auto names = pkm::io::builtinMachineNames();
  EXPECT_THAT(names, Contains("hexapod-default"));
  EXPECT_THAT(names, Contains("hexapod-linuxcnc-sim"));
  EXPECT_THAT(names, Contains(std::string(pkm::io::kDefaultMachine)));
  for (const auto& n : names) EXPECT_NO_THROW((void)pkm::io::builtinMachine(n)) << n;
}

TEST(MachineLoader, BuiltinsEqualTheShippedFiles) {
  for (const char* stem : {"hexapod-default", "hexapod-linuxcnc-sim"}) {
    SCOPED_TRACE(stem);
    const HexapodMachine builtin = pkm::io::builtinMachine(stem);
    const HexapodMachine file = pkm::io::readHexapodJson(dataFile(stem));
    EXPECT_EQ(builtin.source, std::string("builtin:") + stem);
    EXPECT_EQ(builtin.model.name, file.model.name);
    expectSameGeometry(builtin.model, file.model);
  }
}

TEST(MachineLoader, DefaultAlias) {
  const HexapodMachine a = loadHexapodMachine("default");
  const HexapodMachine b = loadHexapodMachine("hexapod-default");
  EXPECT_EQ(a.source, "builtin:hexapod-default");
  EXPECT_EQ(a.model.name, "pkm-hx1200");
  expectSameGeometry(a.model, b.model);
  EXPECT_EQ(pkm::io::builtinMachine("default").source, "builtin:hexapod-default");
}

TEST(MachineLoader, LinuxcncSimBuiltinMatchesReference) {
  const HexapodMachine m = loadHexapodMachine("hexapod-linuxcnc-sim");
  expectSameGeometry(m.model, [] {
    kin::HexapodModel ref = pkm::test::linuxcncSimModel();
    return ref;
  }());
  kin::HexapodData data(m.model);
  const kin::StrutVector& q = kin::inverseKinematics(m.model, data, m.model.home);
  EXPECT_NEAR(q[0], 29.746680, pkm::test::kTolLinuxcnc);
  EXPECT_NEAR(q[3], 29.746363, pkm::test::kTolLinuxcnc);
}

TEST(MachineLoader, UnknownNameListsBuiltins) {
  try {
    (void)loadHexapodMachine("no-such-machine");
    FAIL() << "no error";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("no-such-machine"));
    EXPECT_THAT(e.what(), HasSubstr("not a built-in hexapod machine"));
    EXPECT_THAT(e.what(), ::testing::Not(HasSubstr("mxt700s-like")));  // only hexapods are offered
    EXPECT_THAT(e.what(), HasSubstr("hexapod-default"));
    EXPECT_THAT(e.what(), HasSubstr("hexapod-linuxcnc-sim"));
  }
  EXPECT_THROW((void)pkm::io::builtinMachine("hexapod"), IoError);
}

// ---------------------------------------------------------------------------------------------
// Machine types and Exechon machines

/// The type of every shipped machine file.
const std::map<std::string, std::string> kShippedTypes = {
    {"hexapod-default", "hexapod"},
    {"hexapod-linuxcnc-sim", "hexapod"},
    {"exechon-zoppi2010", "exechon"},
    {"mxt700s-like", "exechon"},
};

TEST(MachineLoader, BuiltinNamesByType) {
  EXPECT_THAT(pkm::io::builtinMachineNames("exechon"),
              UnorderedElementsAre("exechon-zoppi2010", "mxt700s-like"));
  EXPECT_THAT(pkm::io::builtinMachineNames("hexapod"),
              UnorderedElementsAre("hexapod-default", "hexapod-linuxcnc-sim"));
  EXPECT_EQ(pkm::io::builtinMachineNames(), pkm::io::builtinMachineNames("hexapod"));
  EXPECT_THAT(pkm::io::builtinMachineNames(""),
              UnorderedElementsAre(
                  "hexapod-default", "hexapod-linuxcnc-sim", "exechon-zoppi2010", "mxt700s-like"));
  EXPECT_TRUE(pkm::io::builtinMachineNames("scara").empty());
  EXPECT_THAT(pkm::io::builtinMachineNames("exechon"),
              Contains(std::string(pkm::io::kDefaultExechonMachine)));
}

TEST(MachineLoader, MachineTypeOfEachEmbeddedFile) {
  const auto& embedded = pkm::io::detail::embeddedMachines();
  ASSERT_EQ(embedded.size(), kShippedTypes.size());
  for (const auto& [stem, content] : embedded) {
    SCOPED_TRACE(stem);
    const std::string name(stem);
    ASSERT_EQ(kShippedTypes.count(name), 1u);
    EXPECT_EQ(pkm::io::machineType(std::string(content)), kShippedTypes.at(name));
    // The embedded text is the file in data/machines.
    std::ifstream in(dataFile(name.c_str()), std::ios::binary);
    const std::string file((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(file, content);
  }
}

TEST(MachineLoader, MachineTypeOfOtherTexts) {
  EXPECT_EQ(pkm::io::machineType("{\"type\": \"exechon\"}"), "exechon");
  EXPECT_EQ(pkm::io::machineType("{\"type\": \"anything\", \"x\": 1}"), "anything");
  // Absent, not a string, not an object, or not JSON at all: "hexapod" (the typed readers report).
  EXPECT_EQ(pkm::io::machineType("{\"units\": \"mm\"}"), "hexapod");
  EXPECT_EQ(pkm::io::machineType("{\"type\": 3}"), "hexapod");
  EXPECT_EQ(pkm::io::machineType("[\"exechon\"]"), "hexapod");
  EXPECT_EQ(pkm::io::machineType("{\"type\": \"exechon\""), "hexapod");
  EXPECT_EQ(pkm::io::machineType(""), "hexapod");
}

TEST(MachineLoader, ExechonDefaultIsMxt700sLike) {
  const pkm::io::ExechonMachine m = pkm::io::loadExechonMachine("default");
  EXPECT_EQ(m.source, "builtin:mxt700s-like");
  EXPECT_EQ(m.model.name, "mxt700s-like");
  EXPECT_TRUE(m.hybrid.has_value());
  const pkm::io::ExechonMachine z = pkm::io::loadExechonMachine("exechon-zoppi2010");
  EXPECT_EQ(z.source, "builtin:exechon-zoppi2010");
  EXPECT_FALSE(z.hybrid.has_value());
  // The built-ins equal the shipped files.
  for (const char* stem : {"exechon-zoppi2010", "mxt700s-like"}) {
    SCOPED_TRACE(stem);
    const pkm::io::ExechonMachine b = pkm::io::loadExechonMachine(stem);
    const pkm::io::ExechonMachine f = pkm::io::readExechonJson(dataFile(stem));
    EXPECT_EQ(pkm::io::writeExechonJson(b), pkm::io::writeExechonJson(f));
  }
}

TEST(MachineLoader, HexapodNameIsNotAnExechonMachine) {
  try {
    (void)pkm::io::loadExechonMachine("hexapod-default");
    FAIL() << "no error";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("hexapod-default"));
    EXPECT_THAT(e.what(), HasSubstr("not a built-in exechon machine"));
    EXPECT_THAT(e.what(), HasSubstr("exechon-zoppi2010"));
    EXPECT_THAT(e.what(), HasSubstr("mxt700s-like"));
    EXPECT_THAT(e.what(), Not(HasSubstr("hexapod-linuxcnc-sim")));  // only Exechons are offered
  }
  // And the other way round.
  try {
    (void)loadHexapodMachine("mxt700s-like");
    FAIL() << "no error";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("not a built-in hexapod machine"));
    EXPECT_THAT(e.what(), Not(HasSubstr("exechon-zoppi2010")));
  }
}

TEST_F(MachineLoaderTest, ExechonFileByPath) {
  std::ifstream in(dataFile("exechon-zoppi2010"));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string path = write("zoppi", text);
  const pkm::io::ExechonMachine m = pkm::io::loadExechonMachine(path);
  EXPECT_EQ(m.source, path);
  EXPECT_EQ(m.model.name, "exechon-zoppi2010");
  // A hexapod file given to the Exechon loader: the reader names the file and the type line.
  const std::string hex = write("hex.json", "{\n  \"type\": \"hexapod\"\n}\n");
  try {
    (void)pkm::io::loadExechonMachine(hex);
    FAIL() << "no error";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), ::testing::StartsWith(hex + ":2: /type: "));
  }
}

TEST_F(MachineLoaderTest, DirectoryIsAnError) {
  try {
    (void)loadHexapodMachine(dir_.string());
    FAIL() << "no error";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr(dir_.string()));
    EXPECT_THAT(e.what(), HasSubstr("is a directory"));
  }
}

TEST_F(MachineLoaderTest, JsonFileByPath) {
  std::ifstream in(dataFile("hexapod-linuxcnc-sim"));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string path = write("my-machine", text);  // no extension needed
  const HexapodMachine m = loadHexapodMachine(path);
  EXPECT_EQ(m.source, path);
  EXPECT_EQ(m.model.unit, pkm::LengthUnit::kInch);
}

TEST_F(MachineLoaderTest, FileTakesPrecedenceOverBuiltinName) {
  // A file in the working directory named like a built-in is read as a file.
  const fs::path old = fs::current_path();
  fs::current_path(dir_);
  write("hexapod-default", "{\n  \"bad\": 1\n}\n");
  try {
    (void)loadHexapodMachine("hexapod-default");
    ADD_FAILURE() << "no error";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("hexapod-default:2: /bad: unknown key"));
  }
  fs::current_path(old);
}

TEST_F(MachineLoaderTest, MalformedJsonFileNamesFileAndLine) {
  const std::string path = write("broken.json", "{\n  \"units\": \"mm\",\n  \"struts\": [,]\n}\n");
  try {
    (void)loadHexapodMachine(path);
    FAIL() << "no error";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), ::testing::StartsWith(path + ":3: "));
  }
}

TEST_F(MachineLoaderTest, HalFileDispatch) {
  const kin::HexapodModel sim = pkm::test::linuxcncSimModel();
  HexapodMachine src;
  src.model = sim;
  std::string setp;  // the setp block without its "# pkm:" home/units lines, as a hand-written file
  std::istringstream in(pkm::io::writeLinuxcncSetp(src));
  for (std::string line; std::getline(in, line);)
    if (line.rfind("# pkm:", 0) != 0) setp += line + "\n";
  const std::string hal = write("machine.hal", setp);
  // Not discovered (it names no HALFILE): without it the planar sim geometry is singular at home 0.
  const std::string ini = write("other.ini", "[TRAJ]\nHOME = 0 0 20 0 0 0\nLINEAR_UNITS = inch\n");
  try {
    (void)loadHexapodMachine(hal);
    ADD_FAILURE() << "no error";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), ::testing::StartsWith(hal + ": "));
    EXPECT_THAT(e.what(), HasSubstr("--ini"));
  }
  pkm::io::HalReadOptions opt;
  opt.ini_path = ini;
  const HexapodMachine with_ini = loadHexapodMachine(hal, opt);
  EXPECT_EQ(with_ini.source, hal);
  EXPECT_EQ(with_ini.model.unit, pkm::LengthUnit::kInch);
  EXPECT_EQ(with_ini.model.home.position, Eigen::Vector3d(0, 0, 20));
  expectSameGeometry(with_ini.model, sim);
  // An INI in the same folder that loads the HAL file is found without being named.
  write("sim.ini",
        "[HAL]\nHALFILE = machine.hal\n[TRAJ]\nHOME = 0 0 20 0 0 0\nLINEAR_UNITS = inch\n");
  const HexapodMachine discovered = loadHexapodMachine(hal);
  expectSameGeometry(discovered.model, sim);
}

TEST_F(MachineLoaderTest, MissingHalFileIsAnErrorNotABuiltinLookup) {
  const std::string hal = (dir_ / "absent.hal").string();
  try {
    (void)loadHexapodMachine(hal);
    FAIL() << "no error";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), ::testing::StartsWith(hal + ": "));
    EXPECT_THAT(e.what(), ::testing::Not(HasSubstr("built-in")));
  }
}

}  // namespace PKM_TEST_NS
