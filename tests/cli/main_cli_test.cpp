// The pkm program's top level (apps/pkm/main.cpp): a command line naming a command group builds
// that group alone, anything else builds them all. Every group listed by `pkm --help` must answer
// `pkm GROUP --help` with its own usage and the common footer, and a misspelt or missing group is
// still a usage error.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "support/cli_fixture.hpp"

namespace PKM_TEST_NS {

using ::testing::HasSubstr;

class MainCli : public pkm::test::CliTest {
 protected:
  /// The subcommand names `pkm --help` lists.
  std::vector<std::string> groups() const {
    const pkm::test::CliRun help = pkm({"--help"});
    EXPECT_EQ(help.code, 0) << help.err;
    std::vector<std::string> names;
    bool listing = false;
    for (const std::string& line : pkm::test::splitLines(help.out)) {
      if (line == "Subcommands:") {
        listing = true;
        continue;
      }
      if (listing && line.empty()) break;
      if (listing) names.push_back(line.substr(2, line.find(' ', 2) - 2));
    }
    return names;
  }
};

TEST_F(MainCli, EveryGroupAnswersItsOwnHelp) {
  const std::vector<std::string> names = groups();
  ASSERT_GE(names.size(), 15u);  // the built-in groups and the self-registering ones
  EXPECT_THAT(names, ::testing::Contains("hexapod"));
  EXPECT_THAT(names, ::testing::Contains("report"));  // the last self-registering one
  for (const std::string& name : names) {
    const pkm::test::CliRun r = pkm({name, "--help"});
    EXPECT_EQ(r.code, 0) << name << ": " << r.err;
    EXPECT_THAT(r.out, HasSubstr(name)) << name;
    EXPECT_THAT(r.out, HasSubstr("Exit codes:")) << name;  // the footer reaches every group
  }
}

TEST_F(MainCli, MisspeltOrMissingGroupIsAUsageError) {
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"hexapd", "fk"}, std::vector<std::string>{}}) {
    const pkm::test::CliRun r = pkm(args);
    EXPECT_EQ(r.code, pkm::test::kExitUsage);
    EXPECT_THAT(r.err, HasSubstr("A subcommand is required"));
  }
}

TEST_F(MainCli, AGroupRunsWithOnlyItselfBuilt) {
  const pkm::test::CliRun r = pkm({"machines"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("hexapod-linuxcnc-sim"));
  const pkm::test::CliRun version = pkm({"--version"});
  EXPECT_EQ(version.code, 0);
  EXPECT_THAT(version.out, HasSubstr("pkm "));
}

}  // namespace PKM_TEST_NS
