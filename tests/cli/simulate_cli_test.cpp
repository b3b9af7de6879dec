// The CLI contract of `pkm simulate`: --list, the files written, byte-identical output for the same
// seed, refusal to overwrite without --force, and exit code 2 with FILE:LINE on a bad scenario.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

namespace PKM_TEST_NS {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

constexpr int kExitUsage = 2;

struct CliRun {
  int code = -1;
  std::string out, err;
};

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) {
    if (c == '\'')
      q.append("'\\''");
    else
      q.push_back(c);
  }
  q.push_back('\'');
  return q;
}

class SimulateCli : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = "pkm_simulate_test_";
    name.append(std::to_string(::getpid())).append("_").append(info->name());
    dir_ = fs::temp_directory_path() / name;
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  CliRun pkm(const std::vector<std::string>& args) const {
    std::string cmd = quote(PKM_BINARY);
    for (const auto& a : args) cmd.append(" ").append(quote(a));
    cmd.append(" < /dev/null > ").append(quote((dir_ / "stdout.txt").string()));
    cmd.append(" 2> ").append(quote((dir_ / "stderr.txt").string()));
    const int status = std::system(cmd.c_str());
    CliRun r;
    r.code = status != -1 && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = slurp(dir_ / "stdout.txt");
    r.err = slurp(dir_ / "stderr.txt");
    return r;
  }

  /// Every file of `sub` by name, with its contents.
  std::map<std::string, std::string> files(const std::string& sub) const {
    std::map<std::string, std::string> out;
    for (const auto& e : fs::directory_iterator(dir_ / sub))
      out[e.path().filename().string()] = slurp(e.path());
    return out;
  }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  fs::path dir_;
};

TEST_F(SimulateCli, ListsTheBuiltinScenarios) {
  const CliRun r = pkm({"simulate", "--list"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("seed000-parallelism\t"));
  EXPECT_THAT(r.out, HasSubstr("seed001-diagonals\t"));
  EXPECT_THAT(r.out, HasSubstr("seed004-hexapod-calibration\t"));
}

TEST_F(SimulateCli, SameSeedGivesByteIdenticalFiles) {
  ASSERT_EQ(pkm({"simulate", "seed001-diagonals", "--out", path("a")}).code, 0);
  ASSERT_EQ(pkm({"simulate", "seed001-diagonals", "--out", path("b"), "--seed", "1"}).code, 0);
  ASSERT_EQ(pkm({"simulate", "seed001-diagonals", "--out", path("c"), "--seed", "2"}).code, 0);
  const auto a = files("a"), b = files("b"), c = files("c");
  EXPECT_EQ(a, b);
  ASSERT_TRUE(a.count("truth.json") && a.count("scenario.json") && a.count("diag-ppp_run1.csv"));
  EXPECT_EQ(a.size(), 26U * 3U + 2U);  // 26 measurements (12 shifted diagonals) of three runs
  EXPECT_NE(a.at("diag-ppp_run1.csv"), c.at("diag-ppp_run1.csv"));
  EXPECT_THAT(a.at("linear-x_run2.csv"), HasSubstr("\ntarget_mm,run,direction,reading_mm\n0,2,+,"));
  // scenario.json reproduces the run.
  ASSERT_EQ(pkm({"simulate", path("c/scenario.json"), "--out", path("d")}).code, 0);
  const auto d = files("d");
  EXPECT_EQ(d.at("diag-ppp_run1.csv"), c.at("diag-ppp_run1.csv"));
}

TEST_F(SimulateCli, RefusesToOverwriteWithoutForce) {
  ASSERT_EQ(pkm({"simulate", "seed000-parallelism", "--out", path("o")}).code, 0);
  std::ofstream(dir_ / "o" / "truth.json") << "mine";
  const CliRun r = pkm({"simulate", "seed000-parallelism", "--out", path("o")});
  EXPECT_EQ(r.code, kExitUsage);
  EXPECT_THAT(r.err, HasSubstr("refusing to overwrite (use --force)"));
  EXPECT_EQ(slurp(dir_ / "o" / "truth.json"), "mine");
  EXPECT_EQ(pkm({"simulate", "seed000-parallelism", "--out", path("o"), "--force"}).code, 0);
  EXPECT_THAT(slurp(dir_ / "o" / "truth.json"), HasSubstr("\"schema\": \"pkm.truth/1\""));
}

TEST_F(SimulateCli, BadInputExitsWithCode2) {
  std::ofstream(dir_ / "bad.json")
      << "{\"type\": \"simulation_scenario\",\n \"machine\": {\"kind\": \"cartesian\"},\n"
         " \"measurements\": [{\"name\": \"Bad Name\"}]}\n";
  CliRun r = pkm({"simulate", path("bad.json"), "--out", path("x")});
  EXPECT_EQ(r.code, kExitUsage);
  EXPECT_THAT(r.err, HasSubstr("bad.json:3: /measurements/0/name"));
  EXPECT_FALSE(fs::exists(dir_ / "x"));
  r = pkm({"simulate", "no-such-scenario", "--out", path("x")});
  EXPECT_EQ(r.code, kExitUsage);
  EXPECT_THAT(r.err, HasSubstr("not a built-in scenario"));
  EXPECT_EQ(pkm({"simulate", "seed001-diagonals"}).code, kExitUsage);
}

}  // namespace PKM_TEST_NS
