// Scenario files: the "tripod_errors" of a hybrid machine (parsing, FILE:LINE errors, truth.json).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "pkm/core/error.hpp"
#include "pkm/io/scenario.hpp"
#include "pkm/simulation/campaign.hpp"
#include "pkm/simulation/hybrid_virtual_machine.hpp"

namespace PKM_TEST_NS {

namespace io = pkm::io;
namespace sim = pkm::simulation;
using ::testing::HasSubstr;

constexpr double kUradPerRad = 1e6;

const char* kTripod = R"({
  "type": "simulation_scenario",
  "name": "tripod",
  "seed": 3,
  "machine": {"kind": "hybrid", "machine": "mxt700s-like",
              "tripod_errors": {"dB": 0.02, "pC": -0.015, "l23B": 0.04, "length_offset": [0.01, -0.02, 0.005],
                                "c0_urad": 25, "tool_length": 0.03}},
  "measurements": [
    {"name": "lin-pz", "quantity": "linear", "from": [400, 100, 0, 0, -50], "to": [400, 100, 0, 0, 250],
     "targets": 4, "runs": 1}
  ]
})";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  text.replace(text.find(from), from.size(), to);
  return text;
}

std::string messageOf(const std::string& text) {
  try {
    (void)io::parseScenarioJson(text, "t.json");
  } catch (const pkm::IoError& e) {
    return e.what();
  }
  return "no error";
}

const sim::HybridVirtualMachine& hybridOf(const io::Scenario& s) {
  const auto* m = dynamic_cast<const sim::HybridVirtualMachine*>(s.campaign.machine.get());
  if (m == nullptr) throw std::logic_error("not a hybrid machine");
  return *m;
}

TEST(ScenarioTripod, ParsesTheTripodErrors) {
  const io::Scenario s = io::parseScenarioJson(kTripod, "t.json");
  const sim::HybridVirtualMachine& m = hybridOf(s);
  ASSERT_TRUE(m.tripod().has_value());
  const sim::ExechonTripodErrors& e = m.tripod()->errors();
  EXPECT_EQ(e.dB, 0.02);
  EXPECT_EQ(e.pC, -0.015);
  EXPECT_EQ(e.l23B, 0.04);
  EXPECT_EQ(e.l12B, 0.0);
  EXPECT_EQ(e.dA, 0.0);
  EXPECT_EQ(e.length_offset, Eigen::Vector3d(0.01, -0.02, 0.005));
  EXPECT_EQ(e.c0, 25 / kUradPerRad);  // µrad in the file, rad in the model
  EXPECT_EQ(e.tool_length, 0.03);
  EXPECT_EQ(m.tripod()->actual().tripod.dB, m.tripod()->nominal().tripod.dB + 0.02);
  // The measurement runs on the PKM with the tripod errors.
  EXPECT_EQ(sim::runCampaign(s.campaign, s.seed).size(), 1U);
}

TEST(ScenarioTripod, AbsentOrZeroTripodErrorsKeepTheCartesianChain) {
  const std::string zero =
      replaced(kTripod,
               R"("dB": 0.02, "pC": -0.015, "l23B": 0.04, "length_offset": [0.01, -0.02, 0.005],
                                "c0_urad": 25, "tool_length": 0.03)",
               R"("dB": 0)");
  EXPECT_FALSE(hybridOf(io::parseScenarioJson(zero, "t.json")).tripod().has_value());
  const std::string absent = replaced(zero,
                                      R"(,
              "tripod_errors": {"dB": 0})",
                                      "");
  const io::Scenario s = io::parseScenarioJson(absent, "t.json");
  EXPECT_FALSE(hybridOf(s).tripod().has_value());
  EXPECT_EQ(io::truthJson(s, 1).find("tripod_errors"), std::string::npos);
}

TEST(ScenarioTripod, ErrorsNameTheFileLineAndPointer) {
  EXPECT_THAT(messageOf(replaced(kTripod, R"("dB": 0.02)", R"("dB": "x")")),
              HasSubstr("t.json:6: /machine/tripod_errors/dB: expected a number"));
  EXPECT_THAT(messageOf(replaced(kTripod, R"("pC": -0.015)", R"("pD": -0.015)")),
              HasSubstr("/machine/tripod_errors/pD: unknown key 'pD'"));
  EXPECT_THAT(messageOf(replaced(kTripod, "[0.01, -0.02, 0.005]", "[0.01, -0.02]")),
              HasSubstr("t.json:6: /machine/tripod_errors/length_offset: expected an array of 3"));
  // dB + error = 0: the true tripod is degenerate (ExechonModel::validate).
  EXPECT_THAT(messageOf(replaced(kTripod, R"("dB": 0.02)", R"("dB": -345.5)")),
              HasSubstr("t.json:6: /machine/tripod_errors: "));
}

TEST(ScenarioTripod, TruthJsonHoldsTheInjectedErrors) {
  const io::Scenario s = io::parseScenarioJson(kTripod, "t.json");
  const nlohmann::json truth = nlohmann::json::parse(io::truthJson(s, 7));
  ASSERT_TRUE(truth.contains("tripod_errors"));
  const nlohmann::json& t = truth["tripod_errors"];
  EXPECT_EQ(t["dB"].get<double>(), 0.02);
  EXPECT_EQ(t["pC"].get<double>(), -0.015);
  EXPECT_EQ(t["hz"].get<double>(), 0.0);
  EXPECT_EQ(t["length_offset"][1].get<double>(), -0.02);
  EXPECT_DOUBLE_EQ(t["c0_urad"].get<double>(), 25.0);
  EXPECT_EQ(t["tool_length"].get<double>(), 0.03);
  EXPECT_TRUE(truth.contains("errors"));
  // The truth's object is a valid "tripod_errors" again (same keys and units).
  nlohmann::json again = nlohmann::json::parse(kTripod);
  again["machine"]["tripod_errors"] = t;
  const io::Scenario s2 = io::parseScenarioJson(again.dump(), "t2.json");
  EXPECT_EQ(hybridOf(s2).tripod()->errors().length_offset,
            hybridOf(s).tripod()->errors().length_offset);
  EXPECT_DOUBLE_EQ(hybridOf(s2).tripod()->errors().c0, hybridOf(s).tripod()->errors().c0);
}

}  // namespace PKM_TEST_NS
