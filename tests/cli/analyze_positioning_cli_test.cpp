// The CLI contract of `pkm analyze iso230-2 | straightness | parallelism | squareness`: the input
// formats (plain CSV and `pkm simulate` measurement files), the JSON keys, exit code 2 with
// FILE:LINE on bad input, and recovery of seed 000's injected squareness from simulated files.
#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "support/cli_fixture.hpp"

namespace pkm::test {
namespace PKM_TEST_NS {

using Json = nlohmann::json;
using ::testing::HasSubstr;
using ::testing::Not;

constexpr double kTolJson = 1e-12;  ///< JSON numbers are printed at full precision
constexpr double kMrad = 1e-3;
/// Simulated seed 000 X2-Y2 diagonal with the PDGE tables the scenario measures (positioning of X2
/// and Y2, straightness of Y2 in x over 0-300 mm). It has no X2 straightness in y: the unremoved
/// EYX of X2 (a 3.9 µm hump over 875 mm, mean about 2.6 µm) biases szX2 by up to about 10 µrad
/// (face_diagonal_test removes it and recovers szX2 within 2 µrad).
constexpr double kTolSzX2 = 15e-6;
/// Slopes from simulated straightness runs agree with the injected angles to first order
/// (parallelism_test: sxP·syP/2 = 32 µrad is the largest second-order term).
constexpr double kTolFirstOrder = 40e-6;

class AnalyzePositioningCli : public CliTest {};

TEST_F(AnalyzePositioningCli, Iso230_2JsonKeysAndHandComputedValues) {
  // Targets 0 and 10: up {1, 3} / {0, 2}, down {-1, -1} / {2, 4} (deviations, ISO 230-2:2014).
  const std::string f = write("pos.csv",
                              "target,direction,run,measured\n"
                              "0,+,1,1\n0,+,2,3\n10,+,1,10\n10,+,2,12\n"
                              "10,-,1,12\n10,-,2,14\n0,-,1,-1\n0,-,2,-1\n");
  const CliRun r = pkm({"analyze", "iso230-2", "--data", f, "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  const Json j = Json::parse(r.out);
  for (const char* key : {"B",
                          "B_mean",
                          "R_up",
                          "R_down",
                          "R",
                          "E_up",
                          "E_down",
                          "E",
                          "M",
                          "A_up",
                          "A_down",
                          "A",
                          "targets"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  const double q = std::sqrt(2.0);
  EXPECT_NEAR(j["B"].get<double>(), 3.0, kTolJson);
  EXPECT_NEAR(j["R"].get<double>(), 4.0 * q + 2.0, kTolJson);
  EXPECT_NEAR(j["A"].get<double>(), 2.0 + 4.0 * q, kTolJson);
  EXPECT_NEAR(j["M"].get<double>(), 1.5, kTolJson);
  ASSERT_EQ(j["targets"].size(), 2u);
  EXPECT_NEAR(j["targets"][0]["reversal"].get<double>(), 3.0, kTolJson);
  const CliRun k3 = pkm({"analyze", "iso230-2", "--data", f, "--json", "--coverage", "3"});
  ASSERT_EQ(k3.code, 0) << k3.err;
  EXPECT_NEAR(Json::parse(k3.out)["R_up"].get<double>(), 6.0 * q, kTolJson);
  const CliRun table = pkm({"analyze", "iso230-2", "--data", f});
  ASSERT_EQ(table.code, 0) << table.err;
  EXPECT_THAT(table.out, HasSubstr("A_down"));
}

TEST_F(AnalyzePositioningCli, Iso230_2UnidirectionalGivesNull) {
  const std::string f = write(
      "up.csv", "target,direction,run,measured\n0,+,1,0.001\n0,+,2,0.002\n5,+,1,5\n5,+,2,5\n");
  const CliRun r = pkm({"analyze", "iso230-2", "--data", f, "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  const Json j = Json::parse(r.out);
  EXPECT_TRUE(j["B"].is_null());
  EXPECT_TRUE(j["A"].is_null());
  EXPECT_FALSE(j["A_up"].is_null());
  EXPECT_FALSE(j["bidirectional"].get<bool>());
  // The direction's own quantities carry their budgets (ISO/TR 230-9), the missing ones none.
  for (const char* q : {"E_up", "A_up", "R_up"}) {
    EXPECT_EQ(j["uncertainty"][q]["value"].get<double>(), j[q].get<double>()) << q;
    EXPECT_GT(j["uncertainty"][q]["U"].get<double>(), 0.0) << q;
  }
  EXPECT_FALSE(j["uncertainty"].contains("E"));
}

TEST_F(AnalyzePositioningCli, Iso230_2DuplicateAcrossFilesNamesFileAndLine) {
  const std::string a = write("a.csv", "target,direction,run,measured\n0,+,1,0\n0,+,2,0\n");
  const std::string b = write("b.csv", "target,direction,run,measured\n\n0,+,2,0.1\n");
  const CliRun r = pkm({"analyze", "iso230-2", "--data", a, b});
  const std::string err = expectUsageError(r, "b.csv:3:");
  EXPECT_THAT(err, HasSubstr("duplicate"));
  EXPECT_THAT(err, HasSubstr("a.csv:3"));
  const std::string one = write("one.csv", "target,direction,run,measured\n0,+,1,0\n");
  // An error of the data, not the parser, names the file it comes from.
  const std::string lone =
      expectUsageError(pkm({"analyze", "iso230-2", "--data", one}), "only 1 run");
  EXPECT_THAT(lone, HasSubstr("one.csv: ISO 230-2:"));
  const std::string bad = write("bad.csv", "target,direction,run,measured\n0,x,1,0\n");
  expectUsageError(pkm({"analyze", "iso230-2", "--data", bad}), "bad.csv:2:");
}

TEST_F(AnalyzePositioningCli, StraightnessReferencesAndContacts) {
  const std::string f = write("s.csv", "position,deviation\n0,0\n1,1\n2,0\n");
  for (const char* ref : {"endpoint", "lsq", "minzone"}) {
    const CliRun r = pkm({"analyze", "straightness", "--data", f, "--reference", ref, "--json"});
    ASSERT_EQ(r.code, 0) << r.err;
    const Json j = Json::parse(r.out);
    EXPECT_EQ(j["reference"], ref);
    EXPECT_NEAR(j["slope"].get<double>(), 0.0, kTolJson);
    EXPECT_NEAR(j["straightness"].get<double>(), 1.0, kTolJson);
    EXPECT_EQ(j.contains("contact_points"), std::string(ref) == "minzone");
  }
  expectUsageError(
      pkm({"analyze", "straightness", "--data", write("one.csv", "position,deviation\n1,2\n")}),
      "at least 2");
  expectUsageError(
      pkm({"analyze", "straightness", "--data", write("nan.csv", "position,deviation\n1,x\n")}),
      "nan.csv:2:");
}

TEST_F(AnalyzePositioningCli, SquarenessClosedFormWithScale) {
  // First-order face diagonals (docs/conventions.md): EC0Y = D (ΔD_NP - ΔD_PP) / (2 a b).
  const double a = 600, b = 450, D = std::hypot(a, b), dPP = -0.0123, dNP = 0.0051;
  const std::string pp = write("pp.csv", "u,v,deviation\n0,0,0\n600,450,-0.0123\n");
  const std::string np = write("np.csv", "u,v,deviation\n0,0,0\n-600,450,0.0051\n");
  const CliRun r = pkm({"analyze", "squareness", "--data", pp, np, "--scale", "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  const Json j = Json::parse(r.out);
  EXPECT_NEAR(j["squareness"].get<double>(), D * (dNP - dPP) / (2 * a * b), kTolJson);
  EXPECT_NEAR(j["residual_rms"].get<double>(), 0.0, kTolJson);
  ASSERT_TRUE(j.contains("scale"));
  EXPECT_NEAR(j["scale"][0].get<double>(), (dPP + dNP) / (2 * D), kTolJson);
  const CliRun single = pkm({"analyze", "squareness", "--data", pp, "--json"});
  ASSERT_EQ(single.code, 0) << single.err;
  EXPECT_FALSE(Json::parse(single.out).contains("scale"));
  const std::string pp3 =
      write("pp3.csv", "u,v,deviation\n0,0,0\n300,225,-0.006\n600,450,-0.0123\n");
  expectUsageError(pkm({"analyze", "squareness", "--data", pp3, "--scale"}), "not separable");
  expectUsageError(pkm({"analyze", "squareness", "--data", pp, "--scale"}), "at least 2");
  expectUsageError(pkm({"analyze", "squareness", "--data", pp, "--pdge", "xx=" + pp}), "--pdge");
}

TEST_F(AnalyzePositioningCli, RecoversSeed000FromSimulatedFiles) {
  const std::string dir = path("sim");
  const CliRun sim = pkm({"simulate", "seed000-parallelism", "--out", dir});
  ASSERT_EQ(sim.code, 0) << sim.err;
  const auto runs = [&](const std::string& name) {
    std::vector<std::string> files;
    for (int k = 1; k <= 3; ++k)
      files.push_back(dir + "/" + name + "_run" + std::to_string(k) + ".csv");
    return files;
  };
  // ISO 230-2 on the X2 positioning runs (simulator format).
  std::vector<std::string> args{"analyze", "iso230-2", "--json", "--data"};
  for (const auto& f : runs("linear-x2")) args.push_back(f);
  const CliRun iso = pkm(args);
  ASSERT_EQ(iso.code, 0) << iso.err;
  const Json ji = Json::parse(iso.out);
  EXPECT_EQ(ji["targets"].size(), 15u);
  EXPECT_GT(ji["E"].get<double>(), 0.07);  // EXX of X2 reaches -0.078 mm over 875 mm
  EXPECT_LT(ji["E"].get<double>(), 0.09);

  // szX2 from the X2-Y2 face diagonal after removing the X2 and Y2 positioning errors.
  std::vector<std::string> sq{"analyze",
                              "squareness",
                              "--json",
                              "--second-moves-work",
                              "--pdge",
                              "uu=" + runs("linear-x2")[0],
                              "--pdge",
                              "vv=" + runs("linear-y2")[0],
                              "--pdge",
                              "vu=" + runs("straightness-y2-h")[0],
                              "--data"};
  for (const auto& f : runs("diagonal-x2-y2")) sq.push_back(f);
  const CliRun square = pkm(sq);
  ASSERT_EQ(square.code, 0) << square.err;
  const double szX2 = Json::parse(square.out)["squareness"].get<double>();
  EXPECT_NEAR(szX2, -0.034 * kMrad, kTolSzX2);

  // Parallelism of the PKM's y to Y2 (same beam; +y2 moves the tool along -y): dgamma, dalpha.
  const auto parallel = [&](const char* plane, const char* ref, const char* axis) {
    std::vector<std::string> a{"analyze",
                               "parallelism",
                               "--json",
                               "--plane",
                               plane,
                               "--reference-sign",
                               "-1",
                               "--szX2",
                               std::to_string(szX2),
                               "--reference"};
    for (const auto& f : runs(ref)) a.push_back(f);
    a.push_back("--axis");
    for (const auto& f : runs(axis)) a.push_back(f);
    const CliRun r = pkm(a);
    EXPECT_EQ(r.code, 0) << r.err;
    return Json::parse(r.out);
  };
  const Json h = parallel("horizontal", "straightness-y2-h", "straightness-py-h");
  const Json v = parallel("vertical", "straightness-y2-v", "straightness-py-v");
  EXPECT_NEAR(h["szP"].get<double>(), -2.85 * kMrad, kTolFirstOrder);
  EXPECT_NEAR(v["sxP"].get<double>(), -14.74 * kMrad, kTolFirstOrder);
  EXPECT_NEAR(v["dalpha"].get<double>(), v["sxP"].get<double>(), kTolJson);
  EXPECT_NEAR(v["parallelism"].get<double>(), v["dalpha"].get<double>() * 300.0, 1e-9);
  // Eq. 11's budgets: the parallelism budget over the 300 mm travel (rad); szX2 taken as exact.
  const Json& uh = h["uncertainty"];
  const Json& uv = v["uncertainty"];
  EXPECT_EQ(uv["sxP"]["value"], v["sxP"]);
  EXPECT_EQ(uh["szP"]["unit"], "rad");
  EXPECT_NEAR(uv["sxP"]["U"].get<double>(), uv["parallelism"]["U"].get<double>() / 300.0, 1e-12);
  EXPECT_NEAR(uh["szP"]["U"].get<double>(), uh["parallelism"]["U"].get<double>() / 300.0, 1e-12);
  // The face-diagonal squareness has its budget with the Monte Carlo check beside it.
  const Json us = Json::parse(square.out)["uncertainty"]["squareness"];
  EXPECT_GT(us["U"].get<double>(), 0.0);
  EXPECT_NEAR(
      us["monte_carlo"]["U"].get<double>(), us["U"].get<double>(), 0.05 * us["U"].get<double>());
}

// --- real instrument exports (regressions of a first try with real data) -----------------

/// A laser's export of the standard test cycle (5 runs each way, 6 targets over 500 mm).
std::string laserExport() {
  std::string t = "Target (mm),Run,Direction,Error (µm)\n";
  const double targets[] = {0.0, 97.3, 201.6, 298.0, 402.8, 500.0};
  for (int run = 1; run <= 5; ++run)
    for (const char* dir : {"Forward", "Reverse"})
      for (double target : targets)
        t += fmt::format("{},{},{},{}\n", target, run, dir, 1.0 + 0.01 * target + run * 0.1);
  return t;
}

TEST_F(AnalyzePositioningCli, AnInstrumentExportIsReadWithoutConversion) {
  const CliRun r =
      pkm({"analyze", "iso230-2", "--data", write("laser.csv", laserExport()), "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  const Json j = Json::parse(r.out);
  // Deviations 1 + 0.01 t + 0.1 run µm, the same both ways: mean 1.3 µm at 0, 6.3 µm at 500 mm.
  EXPECT_NEAR(j["E"].get<double>(), 0.005, 1e-12);
  EXPECT_TRUE(j["iso230_2_conditions"]["met"].get<bool>());
  EXPECT_FALSE(j.contains("warnings"));
}

TEST_F(AnalyzePositioningCli, MissingColumnsAreListedOnceWithTheColumnsFound) {
  const std::string f = write("odd.csv",
                              "Pos (mm),Pass,Way,Err (um)\n0,1,F,1\n0,2,F,2\n9,1,F,3\n9,2,F,4\n"
                              "9,1,R,1\n9,2,R,2\n0,1,R,3\n0,2,R,4\n");
  const CliRun r = pkm({"analyze", "iso230-2", "--data", f});
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.err, HasSubstr("odd.csv:1: missing columns: target ("));
  EXPECT_THAT(r.err, HasSubstr("found 'Pos (mm)', 'Pass', 'Way', 'Err (um)'"));
  const CliRun ok = pkm({"analyze",
                         "iso230-2",
                         "--data",
                         f,
                         "--columns",
                         "target=Pos,run=Pass,direction=Way,error=Err"});
  EXPECT_EQ(ok.code, 0) << ok.err;
  EXPECT_THAT(ok.out, HasSubstr("nonconforming\t2 runs in the + direction"));
}

TEST_F(AnalyzePositioningCli, AHeaderWithoutRowsIsAnErrorNamingTheFile) {
  const std::string pos = write("pos.csv", "target,direction,run,measured\n");
  const std::string line = write("line.csv", "position,deviation\n");
  const std::string xy = write("xy.csv", "x,y\n");
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"analyze", "iso230-2", "--data", pos},
        {"analyze", "straightness", "--data", line},
        {"analyze", "parallelism", "--reference", line, "--axis", line},
        {"analyze", "squareness", "--data", line},
        {"analyze", "circle", "--data", xy},
        {"compensate",
         "table",
         "--data",
         pos,
         "--format",
         "linuxcnc1",
         "--axis",
         "X",
         "--out",
         path("x.comp")}}) {
    const CliRun r = pkm(args);
    EXPECT_EQ(r.code, 2) << args[1];
    EXPECT_THAT(r.err, HasSubstr(": no data rows (only a header)")) << args[1] << ": " << r.err;
  }
}

TEST_F(AnalyzePositioningCli, DeviationsInTheMeasuredColumnAreFlagged) {
  // Errors in µm put in the measured column: E = 990 without a word before.
  std::string t = "target,direction,run,measured\n";
  for (int run = 1; run <= 5; ++run)
    for (const char* dir : {"+", "-"})
      for (int target : {0, 200, 400, 600, 800, 1000})
        t += fmt::format("{},{},{},{}\n", target, dir, run, 2 + run);
  const std::string f = write("um.csv", t);
  const CliRun r = pkm({"analyze", "iso230-2", "--data", f});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("warning\tdeviations up to"));
  EXPECT_THAT(r.out, HasSubstr("µm read as mm"));
  const CliRun strict = pkm({"analyze", "iso230-2", "--data", f, "--strict"});
  EXPECT_EQ(strict.code, 2);
  EXPECT_THAT(strict.err, HasSubstr("--strict: deviations up to"));
}

TEST_F(AnalyzePositioningCli, AFileWithoutUnitsOnAnInchMachineIsFlagged) {
  std::string t = "target,direction,run,measured\n";
  for (int run = 1; run <= 5; ++run)
    for (const char* dir : {"+", "-"})
      for (int target : {0, 2, 4, 6, 8, 10})
        t += fmt::format("{},{},{},{}\n", target, dir, run, target + 0.0001 * run);
  const std::string f = write("noinch.csv", t);
  const CliRun r = pkm({"analyze", "iso230-2", "--data", f, "--machine", "hexapod-linuxcnc-sim"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("warning\t" + f + ": its header states no length unit"));
  EXPECT_EQ(
      pkm({"analyze", "iso230-2", "--data", f, "--machine", "hexapod-linuxcnc-sim", "--strict"})
          .code,
      2);
  const CliRun inch = pkm(
      {"analyze", "iso230-2", "--data", f, "--machine", "hexapod-linuxcnc-sim", "--unit", "in"});
  EXPECT_THAT(inch.out, Not(HasSubstr("warning")));
}

TEST_F(AnalyzePositioningCli, ANonConformingDataSetIsEvaluatedAndFlagged) {
  // Three runs instead of five, and one of them incomplete.
  const std::string f = write("two.csv",
                              "target,direction,run,measured\n"
                              "0,+,1,0.001\n0,+,2,0.002\n0,+,3,0.001\n"
                              "5,+,1,5.001\n5,+,2,5.002\n5,+,3,5.001\n"
                              "0,-,1,0.003\n0,-,2,0.002\n0,-,3,0.003\n5,-,1,5.003\n5,-,2,5.002\n");
  const CliRun r = pkm({"analyze", "iso230-2", "--data", f, "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  const Json j = Json::parse(r.out);
  EXPECT_FALSE(j["iso230_2_conditions"]["met"].get<bool>());
  const std::string all = j["iso230_2_conditions"]["nonconformities"].dump();
  EXPECT_THAT(all, HasSubstr("3 runs in the + direction"));
  EXPECT_THAT(all, HasSubstr("run counts in the - direction differ between targets"));
  const CliRun table = pkm({"analyze", "iso230-2", "--data", f});
  EXPECT_THAT(table.out, HasSubstr("nonconforming\t3 runs in the + direction"));
  EXPECT_EQ(pkm({"analyze", "iso230-2", "--data", f, "--strict"}).code, 2);
}

TEST_F(AnalyzePositioningCli, OneStraightnessAnswerWhateverTheHeader) {
  // Two runs per position: the per-target mean, whether the columns are named as a plain table
  // or as a simulator file, with the raw scatter beside it.
  std::string plain = "position,deviation\n", sim = "target_mm,direction,run,reading_mm\n";
  const double dev[2][5] = {{0, 0.002, 0.001, 0.004, 0}, {0, 0.0035, -0.001, 0.003, 0.001}};
  for (int run = 0; run < 2; ++run)
    for (int k = 0; k < 5; ++k) {
      plain += fmt::format("{},{}\n", 100 * k, dev[run][k]);
      sim += fmt::format("{},+,{},{}\n", 100 * k, run + 1, dev[run][k]);
    }
  const CliRun a = pkm({"analyze", "straightness", "--data", write("plain.csv", plain), "--json"});
  const CliRun b = pkm({"analyze", "straightness", "--data", write("sim.csv", sim), "--json"});
  ASSERT_EQ(a.code, 0) << a.err;
  ASSERT_EQ(b.code, 0) << b.err;
  const Json ja = Json::parse(a.out), jb = Json::parse(b.out);
  EXPECT_EQ(ja["straightness"], jb["straightness"]);
  EXPECT_EQ(ja["points"], 5);
  EXPECT_EQ(ja["raw"]["points"], 10);
  EXPECT_GT(ja["raw"]["straightness"].get<double>(), ja["straightness"].get<double>());
}

TEST_F(AnalyzePositioningCli, HelpStatesTheExitCodes) {
  const CliRun r = pkm({"analyze", "iso230-2", "--help"});
  EXPECT_EQ(r.code, 0);
  EXPECT_THAT(r.out, HasSubstr("Exit codes: 0 success; 1 the job ran and a check failed"));
  EXPECT_THAT(r.out, HasSubstr("--columns"));
  EXPECT_THAT(r.out, HasSubstr("--error-unit"));
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::test
