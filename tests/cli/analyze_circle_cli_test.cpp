// `pkm analyze circle | circular | probe-offset`: the contract keys on a constructed circle,
// ISO 230-4 on two runs, and the seed003-probe-offset simulation read back exactly as written
// (offset recovered, DRM compensation lowers the roundness); input errors.
#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>

#include "support/cli_fixture.hpp"

namespace PKM_TEST_NS {

using pkm::test::CliTest;
using ::testing::HasSubstr;

class AnalyzeCircleCli : public CliTest {};

constexpr double kTolCli = 1e-9;  ///< exact inputs through the CLI (full-precision JSON), mm
constexpr double kTolProbeOffset = 1e-3;  ///< seed003: offset within 1 µm (RMP600 noise 0.125 µm)

/// Four alternating extremes at R ± h about (cx, cy) and 32 points strictly inside the zone.
std::string zoneCircle(double cx, double cy, double r, double h) {
  std::string s = "x,y\n";
  for (int k = 0; k < 36; ++k) {
    const double t = 2.0 * std::numbers::pi * k / 36.0;
    const double rad = (k % 9 == 0) ? (k % 18 == 0 ? r + h : r - h) : r + 0.3 * h * std::sin(5 * t);
    s += fmt::format("{:.17g},{:.17g}\n", cx + rad * std::cos(t), cy + rad * std::sin(t));
  }
  return s;
}

TEST_F(AnalyzeCircleCli, CircleJsonHasTheContractKeys) {
  const std::string f = write("c.csv", zoneCircle(10.0, -4.0, 25.0, 0.002));
  const auto r = pkm({"analyze", "circle", "--data", f, "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* key : {"center", "radius", "roundness_lsc", "roundness_mzc", "mzc_center"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_NEAR(j["mzc_center"][0].get<double>(), 10.0, kTolCli);
  EXPECT_NEAR(j["mzc_center"][1].get<double>(), -4.0, kTolCli);
  EXPECT_NEAR(j["roundness_mzc"].get<double>(), 0.004, kTolCli);
  EXPECT_LE(j["roundness_mzc"].get<double>(), j["roundness_lsc"].get<double>());
  EXPECT_TRUE(j["mzc_certified"].get<bool>());
  ASSERT_EQ(j["mzc_contacts"].size(), 4u);
  for (const auto& c : j["mzc_contacts"]) {
    const int line = c["line"].get<int>();  // header on line 1; extremes at k = 0, 9, 18, 27
    EXPECT_EQ((line - 2) % 9, 0);
    EXPECT_EQ(c["circle"].get<std::string>(), (line - 2) % 18 == 0 ? "outer" : "inner");
  }
  const auto t = pkm({"analyze", "circle", "--data", f});
  ASSERT_EQ(t.code, 0);
  EXPECT_THAT(t.out, HasSubstr("roundness MZC"));
}

/// Blank-separated text (a CMM's export) and several files: the same circle, contacts located in
/// their own file and line.
TEST_F(AnalyzeCircleCli, ReadsBlankSeparatedFilesAndConcatenates) {
  std::string text = zoneCircle(10.0, -4.0, 25.0, 0.002);
  const std::string csv = write("c.csv", text);
  for (char& c : text) c = c == ',' ? ' ' : c;
  const std::string txt = write("c.txt", "# exported\n" + text);
  const auto a = pkm({"analyze", "circle", "--data", csv, "--json"});
  const auto b = pkm({"analyze", "circle", "--data", txt, "--json"});
  ASSERT_EQ(b.code, 0) << b.err;
  const auto ja = nlohmann::json::parse(a.out), jb = nlohmann::json::parse(b.out);
  EXPECT_EQ(ja["radius"], jb["radius"]);
  EXPECT_EQ(ja["mzc_contacts"][0]["line"].get<int>() + 1, jb["mzc_contacts"][0]["line"].get<int>());
  const auto both = pkm({"analyze", "circle", "--data", csv, txt, "--json"});
  ASSERT_EQ(both.code, 0) << both.err;
  const auto j = nlohmann::json::parse(both.out);
  EXPECT_EQ(j["points"].get<int>(), 72);
  EXPECT_NEAR(j["radius"].get<double>(), ja["radius"].get<double>(), kTolCli);
  const auto bad = pkm({"analyze", "circle", "--data", write("bad.txt", "x y\n1 2\n3 4 5\n")});
  EXPECT_EQ(bad.code, 2);
  EXPECT_THAT(bad.err, HasSubstr("bad.txt:3: expected 2 fields, found 3"));
}

TEST_F(AnalyzeCircleCli, FitChoosesTheCircle) {
  const std::string f = write("c.csv", zoneCircle(10.0, -4.0, 25.0, 0.002));
  const auto l = pkm({"analyze", "circle", "--data", f, "--fit", "lsc", "--json"});
  ASSERT_EQ(l.code, 0) << l.err;
  const auto j = nlohmann::json::parse(l.out);
  EXPECT_EQ(j["fit"], "lsc");
  EXPECT_TRUE(j.contains("radius") && !j.contains("roundness_mzc") && !j.contains("mzc_center"));
  EXPECT_FALSE(j["uncertainty"].contains("roundness_mzc"));
  const auto m = pkm({"analyze", "circle", "--data", f, "--fit", "mzc"});
  ASSERT_EQ(m.code, 0) << m.err;
  EXPECT_THAT(m.out, HasSubstr("roundness MZC"));
  EXPECT_EQ(m.out.find("LSC radius"), std::string::npos);
  expectUsageError(pkm({"analyze", "circle", "--data", f, "--fit", "lse"}), "--fit 'lse'");
}

TEST_F(AnalyzeCircleCli, GanderPointsGiveTheGlobalMinimumZone) {
  // Gander, Golub and Strebel, BIT 34 (1994): the global minimum zone of these six points is
  // 1.353615 wide about (105/22, 9/22); a local search stops at 1.387853 about (4.6, 4.4).
  const std::string f = write("gander.csv", "x,y\n1,7\n2,6\n5,8\n7,7\n9,5\n3,7\n");
  const auto r = pkm({"analyze", "circle", "--data", f, "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  constexpr double kTolPublished = 5e-7;  // the width as printed to 6 decimals
  EXPECT_NEAR(j["roundness_mzc"].get<double>(), 1.353615, kTolPublished);
  constexpr double kTolCentre = 1e-6;  // the zone's width is flat to second order at its centre
  EXPECT_NEAR(j["mzc_center"][0].get<double>(), 105.0 / 22.0, kTolCentre);
  EXPECT_NEAR(j["mzc_center"][1].get<double>(), 9.0 / 22.0, kTolCentre);
  EXPECT_TRUE(j["mzc_certified"].get<bool>());
}

TEST_F(AnalyzeCircleCli, CircularGivesGAndH) {
  std::string cw = "x,y\n", ccw = "x,y\n";
  for (int k = 0; k < 72; ++k) {
    const double t = 2.0 * std::numbers::pi * k / 72.0;
    const double r = 100.0 + 0.003 * std::cos(2 * t);
    cw += fmt::format("{:.17g},{:.17g}\n", r * std::cos(-t), r * std::sin(-t));
    ccw += fmt::format("{:.17g},{:.17g}\n", (r + 0.001) * std::cos(t), (r + 0.001) * std::sin(t));
  }
  const auto r = pkm({"analyze",
                      "circular",
                      "--data",
                      write("cw.csv", cw),
                      "--data",
                      write("ccw.csv", ccw),
                      "--nominal-radius",
                      "100",
                      "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(j["G_cw"].get<double>(), 0.006, kTolCli);
  EXPECT_NEAR(j["G_bidirectional"].get<double>(), 0.007, kTolCli);
  EXPECT_NEAR(j["H"].get<double>(), 0.001, kTolCli);
  EXPECT_NEAR(j["ccw"]["F_mean"].get<double>(), 0.001, kTolCli);
  // Every reported deviation carries its budget (ISO/TR 230-9), F too with a nominal radius.
  for (const char* q :
       {"G_cw", "G_ccw", "G_bidirectional", "H", "F_max_cw", "F_min_cw", "F_max_ccw", "F_min_ccw"})
    EXPECT_GT(j["uncertainty"][q]["U"].get<double>(), 0.0) << q;
  EXPECT_EQ(j["uncertainty"]["G_cw"]["value"].get<double>(), j["G_cw"].get<double>());
  const auto text =
      pkm({"analyze", "circular", "--data", path("cw.csv"), "--data", path("ccw.csv")});
  ASSERT_EQ(text.code, 0) << text.err;
  EXPECT_THAT(text.out, HasSubstr("uncertainty (k = 2)"));
}

TEST_F(AnalyzeCircleCli, ReadsTheSimulatedSeed003FilesAndRecoversTheOffset) {
  ASSERT_EQ(pkm({"simulate", "seed003-probe-offset", "--out", path("S")}).code, 0);
  const auto truth = nlohmann::json::parse(slurp(dir_ / "S" / "truth.json"));
  const auto& probe = truth["touch_probes"][0];
  const auto r = pkm({"analyze",
                      "probe-offset",
                      "--data",
                      path("S/probe_offset.csv"),
                      "--ring-diameter",
                      "40.001",
                      "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(
        j["offset"][i].get<double>(), probe["stylus_offset"][i].get<double>(), kTolProbeOffset);
    EXPECT_NEAR(
        j["eq8_o_probe"][i].get<double>(), probe["o_probe"][i].get<double>(), kTolProbeOffset);
  }
  EXPECT_NEAR(j["effective_stylus_radius"].get<double>(),
              probe["ball_radius"].get<double>(),
              kTolProbeOffset);
  const auto without =
      pkm({"analyze", "circle", "--data", path("S/probe_circle_uncompensated.csv"), "--json"});
  const auto with =
      pkm({"analyze", "circle", "--data", path("S/probe_circle_compensated.csv"), "--json"});
  ASSERT_EQ(without.code, 0) << without.err;
  ASSERT_EQ(with.code, 0) << with.err;
  const auto jw = nlohmann::json::parse(without.out);
  const auto jc = nlohmann::json::parse(with.out);
  EXPECT_LT(jc["roundness_mzc"].get<double>(), 0.5 * jw["roundness_mzc"].get<double>());
  EXPECT_NEAR(jc["radius"].get<double>(), 40.001 / 2.0, kTolProbeOffset);
}

TEST_F(AnalyzeCircleCli, Seed003SimulationIsByteIdenticalPerSeed) {
  ASSERT_EQ(pkm({"simulate", "seed003-probe-offset", "--out", path("a")}).code, 0);
  ASSERT_EQ(pkm({"simulate", "seed003-probe-offset", "--out", path("b"), "--seed", "1"}).code, 0);
  ASSERT_EQ(pkm({"simulate", "seed003-probe-offset", "--out", path("c"), "--seed", "2"}).code, 0);
  for (const char* f : {"probe_offset.csv",
                        "probe_circle_uncompensated.csv",
                        "probe_circle_compensated.csv",
                        "truth.json"}) {
    EXPECT_EQ(slurp(dir_ / "a" / f), slurp(dir_ / "b" / f)) << f;
    EXPECT_FALSE(slurp(dir_ / "a" / f).empty()) << f;
  }
  EXPECT_NE(slurp(dir_ / "a" / "probe_offset.csv"), slurp(dir_ / "c" / "probe_offset.csv"));
}

TEST_F(AnalyzeCircleCli, BadInputIsAUsageError) {
  expectUsageError(pkm({"analyze", "circle", "--data", write("a.csv", "x,y\n0,0\n1,0\n")}),
                   "at least");
  expectUsageError(pkm({"analyze", "circle", "--data", write("b.csv", "x,z\n0,0\n")}), "b.csv");
  expectUsageError(
      pkm({"analyze", "circle", "--data", write("c.csv", "x,y\n0,0\n1,1\n2,2\n3,3\n")}),
      "collinear");
  expectUsageError(pkm({"analyze", "circle", "--data", write("d.csv", "x,y\n0,0\nnan,1\n")}),
                   "d.csv:3");
  expectUsageError(
      pkm({"analyze",
           "probe-offset",
           "--data",
           write("e.csv", "spindle_deg,x,y\n0,1,0\n0,0,1\n0,-1,0\n0,0,-1\n0,0.7,0.7\n")}),
      "same spindle angle");
  expectUsageError(pkm({"analyze", "circular", "--data", write("f.csv", "x,y\n1,0\n")}),
                   "two files");
}

}  // namespace PKM_TEST_NS
