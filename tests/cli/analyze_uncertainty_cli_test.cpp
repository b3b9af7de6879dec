// The uncertainty part of `pkm analyze iso230-2`: the budgets in JSON (U = k·u_c with Student's t
// at ν_eff), the ISO 14253-1 decisions of --tolerance, the table's value ± U, and --uncertainty
// files (docs/analysis.md, "Budgets and their propagation").
#include <fmt/format.h>

#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "support/cli_fixture.hpp"

namespace pkm::test {
namespace PKM_TEST_NS {

using Json = nlohmann::json;
using ::testing::HasSubstr;

constexpr double kTolJson = 1e-12;  ///< JSON numbers are printed at full precision

class AnalyzeUncertaintyCli : public CliTest {};

TEST_F(AnalyzeUncertaintyCli, UncertaintyBudgetsToleranceDecisionsAndSourcesFile) {
  // Five targets over 400 mm, two runs per direction (deviations in mm); a reversal of 8 µm,
  // larger than U(B) with its Student's t factor for so few runs.
  std::string csv = "target,direction,run,measured\n";
  for (int i = 0; i < 5; ++i) {
    const double t = 100.0 * i;
    for (int run = 1; run <= 2; ++run) {
      const double d = 1e-3 * i + (run == 1 ? 0.5e-3 : -0.5e-3);
      csv += fmt::format("{},+,{},{}\n{},-,{},{}\n", t, run, t + d, t, run, t + d - 8e-3);
    }
  }
  const std::string f = write("pos.csv", csv);
  const CliRun r = pkm({"analyze", "iso230-2", "--data", f, "--json", "--tolerance", "E=1,B=1e-6"});
  ASSERT_EQ(r.code, 0) << r.err;
  const Json j = Json::parse(r.out);
  for (const char* q : {"E", "M", "A", "B", "R"}) {
    ASSERT_TRUE(j["uncertainty"].contains(q)) << q;
    EXPECT_EQ(j["uncertainty"][q]["value"].get<double>(), j[q].get<double>()) << q;
    EXPECT_GT(j["uncertainty"][q]["U"].get<double>(), 0.0) << q;
    // U = k u_c, k Student's t at ν_eff (Welch–Satterthwaite): above 2 for two runs.
    EXPECT_NEAR(j["uncertainty"][q]["U"].get<double>(),
                j["uncertainty"][q]["k"].get<double>() * j["uncertainty"][q]["u_c"].get<double>(),
                kTolJson);
    EXPECT_GE(j["uncertainty"][q]["k"].get<double>(), 2.0);
    EXPECT_FALSE(j["uncertainty"][q]["budget"].empty());
  }
  EXPECT_EQ(j["conformance"][0]["decision"], "conforms");
  EXPECT_EQ(j["conformance"][1]["decision"], "does not conform");
  // The table shows value ± U.
  const CliRun t = pkm({"analyze", "iso230-2", "--data", f});
  EXPECT_THAT(t.out, HasSubstr("uncertainty (k = 2)\nE\t"));
  EXPECT_THAT(t.out, HasSubstr(" ± "));
  // A larger material temperature error widens U(E); a bad file stops with FILE:LINE.
  const std::string hot = write("hot.json", R"({"laser": {"material_temperature_accuracy_k": 1}})");
  const Json h =
      Json::parse(pkm({"analyze", "iso230-2", "--data", f, "--json", "--uncertainty", hot}).out);
  EXPECT_GT(h["uncertainty"]["E"]["U"].get<double>(), j["uncertainty"]["E"]["U"].get<double>());
  const std::string bad = write("bad.json", "{\n  \"laser\": {\"x\": 1}\n}\n");
  const CliRun b = pkm({"analyze", "iso230-2", "--data", f, "--uncertainty", bad});
  EXPECT_EQ(b.code, 2);
  EXPECT_THAT(b.err, HasSubstr("bad.json:2: /laser/x: unknown key"));
  const CliRun tol = pkm({"analyze", "iso230-2", "--data", f, "--tolerance", "Q=1"});
  EXPECT_EQ(tol.code, 2);
  EXPECT_THAT(tol.err, HasSubstr("'Q'"));
}

TEST_F(AnalyzeUncertaintyCli, BudgetsUseTheFilesRecordedConditionsAndShowTheAssumedOnes) {
  // The same axis measured warm (material 21.5 °C, air 20.6–21.0 °C, a 100 mm dead path, as a
  // laser's compensation unit logs them) and without records.
  std::string plain = "target,direction,run,measured\n";
  std::string logged =
      "# dead path mm: 100\ntarget,direction,run,measured,air temp (C),pressure (hPa),"
      "humidity,material temp (C)\n";
  for (int i = 0; i < 5; ++i)
    for (int run = 1; run <= 2; ++run)
      for (const char* dir : {"+", "-"}) {
        const double t = 200.0 * i;
        const double m = t + 1e-3 * i + (run == 1 ? 0.5e-3 : -0.5e-3);
        plain += fmt::format("{},{},{},{}\n", t, dir, run, m);
        logged += fmt::format(
            "{},{},{},{},{},1010.5,45,{}\n", t, dir, run, m, 20.6 + 0.1 * (i % 5), 21.5);
      }
  const auto json = [&](const std::string& name, const std::string& text) {
    const CliRun r = pkm({"analyze", "iso230-2", "--data", write(name, text), "--json"});
    EXPECT_EQ(r.code, 0) << r.err;
    return Json::parse(r.out)["uncertainty"]["E"];
  };
  const Json a = json("plain.csv", plain);
  const Json w = json("logged.csv", logged);
  EXPECT_GT(w["U"].get<double>(), a["U"].get<double>());
  std::map<std::string, Json> by_name;
  for (const Json& c : w["conditions"]) by_name[c["name"]] = c;
  EXPECT_EQ(by_name["material temperature"]["value"].get<double>(), 21.5);
  EXPECT_EQ(by_name["material temperature"]["origin"], "recorded");
  EXPECT_NEAR(by_name["air temperature variation"]["value"].get<double>(), 0.4, 1e-12);
  EXPECT_EQ(by_name["dead path"]["value"].get<double>(), 100.0);
  EXPECT_EQ(by_name["air pressure"]["value"].get<double>(), 101050.0);
  EXPECT_EQ(by_name["beam alignment"]["origin"], "default");
  for (const Json& c : a["conditions"]) EXPECT_EQ(c["origin"], "default") << c["name"];
  // The table lists the conditions, an assumed one as such.
  const CliRun t = pkm({"analyze", "iso230-2", "--data", write("logged2.csv", logged)});
  EXPECT_THAT(t.out, HasSubstr("condition\tmaterial temperature\t21.5 degC\trecorded"));
  EXPECT_THAT(t.out, HasSubstr("condition\tbeam alignment\t5e-05 rad\tassumed (default)"));
  // A record that cannot be right stops with FILE:LINE.
  std::string kelvin = logged;
  kelvin.replace(kelvin.find(",20.6,1010.5"), 5, ",293");  // the first reading, line 3
  const CliRun bad = pkm({"analyze", "iso230-2", "--data", write("k.csv", kelvin)});
  EXPECT_EQ(bad.code, 2);
  EXPECT_THAT(bad.err, HasSubstr("k.csv:3: air temperature 293 is outside the plausible range"));
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::test
