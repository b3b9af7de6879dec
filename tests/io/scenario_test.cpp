// Scenario files: the built-in scenarios parse and run; malformed scenarios give FILE:LINE errors;
// scenario.json and truth.json outputs.
#include "pkm/io/scenario.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>

#include "pkm/core/error.hpp"
#include "pkm/simulation/hybrid_virtual_machine.hpp"

namespace PKM_TEST_NS {

namespace io = pkm::io;
namespace sim = pkm::simulation;
using ::testing::HasSubstr;

const char* kMinimal = R"({
  "type": "simulation_scenario",
  "name": "mini",
  "seed": 5,
  "machine": {"kind": "cartesian", "errors": {"squareness_urad": {"xy": 50},
              "x": {"positions": [0, 100], "dx": [0, 0.002], "ey_urad": [0, 10]}}},
  "measurements": [
    {"name": "lin-x", "quantity": "linear", "from": [0, 0, 0], "to": [100, 0, 0], "targets": 5, "runs": 2},
    {"name": "diag", "quantity": "linear", "from": [0, 0, 0], "to": [30, 40, 0], "noise": "xl80-linear"},
    {"name": "pitch", "quantity": "angular", "from": [10, 0, 0], "to": [90, 0, 0], "lateral": [0, 1, 0],
     "noise": {"sigma": 0.05, "resolution": 0.01}}
  ]
})";

std::string messageOf(const std::string& text) {
  try {
    (void)io::parseScenarioJson(text, "s.json");
  } catch (const pkm::IoError& e) {
    return e.what();
  }
  return "no error";
}

TEST(Scenario, ParsesAMinimalCartesianScenario) {
  const io::Scenario s = io::parseScenarioJson(kMinimal, "s.json");
  EXPECT_EQ(s.campaign.name, "mini");
  EXPECT_EQ(s.seed, 5U);
  EXPECT_EQ(s.machine_kind, "cartesian");
  ASSERT_EQ(s.campaign.measurements.size(), 3U);
  const sim::LineSetup& lin = s.campaign.measurements[0];
  EXPECT_EQ(lin.cycle.first, 0.0);
  EXPECT_EQ(lin.cycle.last, 100.0);
  EXPECT_EQ(lin.cycle.runs, 2);
  const sim::LineSetup& diag = s.campaign.measurements[1];
  EXPECT_EQ(diag.cycle.last, 50.0);  // a diagonal is measured from 0 at "from"
  EXPECT_EQ(diag.noise.sigma_ppm, 0.25);
  const sim::LineSetup& pitch = s.campaign.measurements[2];
  EXPECT_EQ(pitch.cycle.first, 10.0);            // a single-axis line in the axis coordinate
  EXPECT_DOUBLE_EQ(pitch.noise.sigma, 0.05e-6);  // µrad in the file, rad in the model
  EXPECT_EQ(pitch.line.at(10.0)[0], 10.0);
}

TEST(Scenario, BuiltinsParseAndRun) {
  const std::vector<std::string> names = io::builtinScenarioNames();
  EXPECT_THAT(names, ::testing::Contains("seed000-parallelism"));
  EXPECT_THAT(names, ::testing::Contains("seed001-diagonals"));
  for (const std::string& name : names) {
    const io::Scenario s = io::loadScenario(name);
    EXPECT_EQ(s.source, "builtin:" + name);
    // Every built-in measures something: laser lines, dial gauges, a tracker or a touch probe.
    EXPECT_FALSE(sim::runCampaign(s.campaign, s.seed).empty() && s.campaign.constrained.empty() &&
                 s.campaign.trackers.empty() && s.campaign.probes.empty() &&
                 s.campaign.exechon_trackers.empty())
        << name;
  }
  const io::Scenario hybrid = io::loadScenario("seed000-parallelism");
  const auto* m = dynamic_cast<const sim::HybridVirtualMachine*>(hybrid.campaign.machine.get());
  ASSERT_NE(m, nullptr);
  EXPECT_DOUBLE_EQ(m->errors().squareness.sx_p, -14.74e-3);
  EXPECT_THROW((void)io::loadScenario("no-such-scenario"), pkm::IoError);
}

TEST(Scenario, ErrorsNameTheFileLineAndPointer) {
  std::string bad = kMinimal;
  bad.replace(bad.find("\"runs\": 2"), 9, "\"runs\": 0");
  EXPECT_THAT(messageOf(bad), HasSubstr("s.json:8: /measurements/0/runs"));
  bad = kMinimal;
  bad.replace(bad.find("\"targets\": 5"), 12, "\"target\": 5");
  EXPECT_THAT(messageOf(bad), HasSubstr("unknown key 'target'"));
  bad = kMinimal;
  bad.replace(bad.find("[100, 0, 0]"), 11, "[100, 0]");
  EXPECT_THAT(messageOf(bad), HasSubstr("s.json:8: /measurements/0/to: expected an array of 3"));
  bad = kMinimal;
  bad.replace(bad.find("\"cartesian\""), 11, "\"delta\"");
  EXPECT_THAT(messageOf(bad), HasSubstr("/machine/kind"));
  bad = kMinimal;
  bad.replace(bad.find("\"xl80-linear\""), 13, "\"xl81\"");
  EXPECT_THAT(messageOf(bad), HasSubstr("unknown instrument noise 'xl81'"));
  bad = kMinimal;
  bad.replace(bad.find("\"diag\""), 6, "\"lin-x\"");
  EXPECT_THAT(messageOf(bad), HasSubstr("two measurements are named 'lin-x'"));
  EXPECT_THAT(messageOf("{\"type\": \"simulation_scenario\",\n ]"),
              HasSubstr("s.json:2: invalid JSON"));
  EXPECT_THAT(messageOf("{\"type\": \"x\"}"), HasSubstr("/type"));
}

TEST(Scenario, ScenarioJsonWithSeedReproducesTheInputs) {
  const io::Scenario s = io::parseScenarioJson(kMinimal, "s.json");
  const std::string text = io::scenarioJsonWithSeed(s, 99);
  const io::Scenario again = io::parseScenarioJson(text, "again.json");
  EXPECT_EQ(again.seed, 99U);
  EXPECT_EQ(again.campaign.measurements.size(), 3U);
  EXPECT_LT(text.find("\"type\""), text.find("\"measurements\""));  // key order kept
}

TEST(Scenario, TruthJsonHoldsTheInjectedErrors) {
  const io::Scenario s = io::parseScenarioJson(kMinimal, "s.json");
  const nlohmann::json t = nlohmann::json::parse(io::truthJson(s, 5));
  EXPECT_EQ(t["schema"], "pkm.truth/1");
  EXPECT_EQ(t["seed"], 5);
  EXPECT_EQ(t["errors"]["squareness_urad"]["xy"], 50.0);
  EXPECT_EQ(t["errors"]["iso_squareness_urad"]["EC0Y"], 50.0);
  EXPECT_EQ(t["errors"]["x"]["dx"][1], 0.002);
  EXPECT_EQ(t["errors"]["x"]["ey_urad"][1], 10.0);
  const nlohmann::json h =
      nlohmann::json::parse(io::truthJson(io::loadScenario("seed000-parallelism"), 1));
  EXPECT_EQ(h["errors"]["squareness_urad"]["sxP"], -14740.0);
}

}  // namespace PKM_TEST_NS

namespace PKM_TEST_NS {

/// Least-squares slope of reading against target over every reading of a measurement.
double fittedSlope(const sim::MeasurementResult& r) {
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const auto& run : r.runs)
    for (const auto& x : run.readings) {
      n += 1;
      sx += x.target;
      sy += x.reading;
      sxx += x.target * x.target;
      sxy += x.target * x.reading;
    }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

TEST(Scenario, Seed004HexapodIsAboutTwelveMillimetresOffOver540) {
  const io::Scenario s = io::loadScenario("seed004-hexapod-calibration");
  EXPECT_EQ(s.machine_kind, "hexapod");
  ASSERT_EQ(s.campaign.constrained.size(), 1U);
  EXPECT_EQ(s.campaign.constrained[0].stations.size(), 24U);  // 72 constraints for 36 unknowns
  EXPECT_DOUBLE_EQ(s.campaign.constrained[0].stations[8][2],
                   10.0 * std::numbers::pi / 180.0);  // degrees in the file
  const auto lines = sim::runCampaign(s.campaign, s.seed);
  ASSERT_EQ(lines.size(), 1U);
  const auto& readings = lines[0].runs[0].readings;
  const double error =
      (readings[9].reading - readings[9].target) - (readings[0].reading - readings[0].target);
  constexpr double kPaperErrorMm = 12.0;  // seed 004 §5: more than 12 mm over a 540 mm move
  EXPECT_NEAR(error, kPaperErrorMm, 0.25 * kPaperErrorMm);
  for (const auto& r : sim::runConstrainedMotion(s.campaign, s.seed))
    for (const auto& st : r.stations) EXPECT_TRUE(st.converged) << st.station;
  const nlohmann::json t = nlohmann::json::parse(io::truthJson(s, 4));
  EXPECT_EQ(t["errors"]["length_offset"].size(), 6U);
  EXPECT_EQ(t["actuation"]["repeatability_sigma"], 0.002);
}

TEST(Scenario, Seed000StraightnessSlopesGiveTheParallelismErrors) {
  // Seed 000 §3: the same beam along Y2 and along the PKM's Y; the slope difference in the tool's
  // y is sxP (vertical) and szX2 − szP (horizontal), to first order. Against their own line
  // coordinates (+y2 moves the tool along −y) the two slopes add up to it.
  const io::Scenario s = io::loadScenario("seed000-parallelism");
  const auto results = sim::runCampaign(s.campaign, s.seed);
  const auto slope = [&](const std::string& name) {
    for (const auto& r : results)
      if (r.setup->name == name) return fittedSlope(r);
    ADD_FAILURE() << name;
    return 0.0;
  };
  // The Y2 straightness tables (a few µm over 350 mm) tilt the fitted lines by up to ~3e-5 rad.
  constexpr double kTolSlope = 5e-5;
  EXPECT_NEAR(slope("straightness-y2-v") + slope("straightness-py-v"), -14.74e-3, kTolSlope);
  EXPECT_NEAR(
      slope("straightness-y2-h") + slope("straightness-py-h"), -0.034e-3 + 2.85e-3, kTolSlope);
}

}  // namespace PKM_TEST_NS

namespace PKM_TEST_NS {

std::string withEnvironment(const std::string& environment) {
  std::string text = kMinimal;
  text.insert(text.find("\"machine\""), "\"environment\": " + environment + ",\n  ");
  return text;
}

TEST(Scenario, EnvironmentIsIdealByDefaultAPresetOrAnObject) {
  EXPECT_FALSE(io::parseScenarioJson(kMinimal, "s.json").campaign.environment.active());
  const io::Scenario r = io::parseScenarioJson(withEnvironment("\"realistic\""), "s.json");
  EXPECT_EQ(r.campaign.environment.name, "realistic");
  EXPECT_TRUE(r.campaign.environment.air.enabled);
  const io::Scenario c =
      io::parseScenarioJson(withEnvironment(R"({"preset": "realistic", "duration_h": 2,
        "air": {"temperature_c": {"change": 0.5}, "pressure_sensor": {"offset": 20},
                "dead_path_mm": 0}})"),
                            "s.json");
  const sim::Environment& e = c.campaign.environment;
  EXPECT_EQ(e.name, "custom");
  EXPECT_EQ(e.duration_h, 2.0);
  EXPECT_EQ(e.air.temperature_c.change, 0.5);
  EXPECT_EQ(e.air.temperature_c.start, 20.5);  // kept from the preset
  EXPECT_EQ(e.air.pressure_sensor.offset, 20.0);
  EXPECT_EQ(e.air.pressure_sensor.noise, 5.0);
  EXPECT_EQ(e.air.dead_path_mm, 0.0);
  const io::Scenario off =
      io::parseScenarioJson(withEnvironment(R"({"air": {"enabled": false}})"), "s.json");
  EXPECT_FALSE(off.campaign.environment.active());
  const io::Scenario t = io::parseScenarioJson(
      withEnvironment(R"({"thermal": {"machine_material": "cast_iron", "assumed_cte_per_k": 1.1e-5,
        "material_temperature_c": {"start": 22}, "warmup_drift_mm": [0, 0, -0.02],
        "strut_material": "aluminium", "strut_warmup_k": 3}})"),
      "s.json");
  const sim::ThermalEnvironment& th = t.campaign.environment.thermal;
  EXPECT_TRUE(th.enabled);
  EXPECT_FALSE(t.campaign.environment.air.enabled);
  EXPECT_EQ(th.machine_cte_per_k, 10.5e-6);
  EXPECT_EQ(th.assumed_cte_per_k, 1.1e-5);
  EXPECT_EQ(th.strut_cte_per_k, 23.1e-6);
  EXPECT_EQ(th.material_temperature_c.start, 22.0);
  EXPECT_EQ(th.warmup_drift_mm.z(), -0.02);
  EXPECT_EQ(th.strut_warmup_k, 3.0);
  const io::Scenario set = io::parseScenarioJson(
      withEnvironment(R"({"setup": {"beam_misalignment_urad": 500, "reflector_offset_mm": 2,
        "probe_lobing_um": 0.5, "probe_lobes": 4}})"),
      "s.json");
  const sim::SetupEnvironment& su = set.campaign.environment.setup;
  EXPECT_TRUE(su.enabled);
  EXPECT_DOUBLE_EQ(su.beam_misalignment_rad, 500e-6);
  EXPECT_EQ(su.reflector_offset_mm, 2.0);
  EXPECT_DOUBLE_EQ(su.probe_lobing_mm, 0.5e-3);
  EXPECT_EQ(su.probe_lobes, 4);
  const io::Scenario st = io::parseScenarioJson(
      withEnvironment(R"({"structure": {"correlated_sigma_um": 2, "correlation_s": 300,
        "white_sigma_um": 0.5}})"),
      "s.json");
  const sim::StructureEnvironment& str = st.campaign.environment.structure;
  EXPECT_TRUE(str.enabled);
  EXPECT_DOUBLE_EQ(str.correlated_sigma_mm, 2e-3);
  EXPECT_EQ(str.correlation_s, 300.0);
  EXPECT_DOUBLE_EQ(str.white_sigma_mm, 0.5e-3);
  const io::Scenario co =
      io::parseScenarioJson(withEnvironment(R"({"compliance": {"hexapod": {"platform_mass_kg": 80,
        "platform_com_mm": [0, 0, -50], "strut_stiffness_n_per_um": 120, "joint_clearance_um": 3},
        "exechon": {"head_mass_kg": 300, "leg_stiffness_n_per_um": 70},
        "cartesian": {"y": {"kind": "cantilever", "sag_um": 30, "length_mm": 800, "zero_mm": 200}},
        "x2": {"kind": "span", "sag_um": 8, "length_mm": 3000, "sense": -1}}})"),
                            "s.json");
  const sim::ComplianceEnvironment& com = co.campaign.environment.compliance;
  EXPECT_TRUE(com.enabled);
  EXPECT_EQ(com.hexapod.platform_mass_kg, 80.0);
  EXPECT_EQ(com.hexapod.platform_com_mm.z(), -50.0);
  EXPECT_EQ(com.hexapod.strut_stiffness_n_per_um, 120.0);
  EXPECT_DOUBLE_EQ(com.hexapod.joint_clearance_mm, 3e-3);
  EXPECT_EQ(com.exechon.head_mass_kg, 300.0);
  EXPECT_EQ(com.exechon.leg_stiffness_n_per_um, 70.0);
  EXPECT_EQ(com.cartesian[1].kind, sim::AxisSag::Kind::kCantilever);
  EXPECT_DOUBLE_EQ(com.cartesian[1].sag_mm, 30e-3);
  EXPECT_EQ(com.cartesian[1].length_mm, 800.0);
  EXPECT_EQ(com.cartesian[1].zero_mm, 200.0);
  EXPECT_EQ(com.cartesian[0].kind, sim::AxisSag::Kind::kNone);
  EXPECT_EQ(com.x2.kind, sim::AxisSag::Kind::kSpan);
  EXPECT_EQ(com.x2.sense, -1.0);
  const io::Scenario rigid = io::parseScenarioJson(
      withEnvironment(R"({"preset": "realistic", "compliance": {"enabled": false}})"), "s.json");
  EXPECT_FALSE(rigid.campaign.environment.compliance.enabled);
}

TEST(Scenario, EnvironmentErrorsNameTheLineAndPointer) {
  const auto message = [](const std::string& env) {
    try {
      (void)io::parseScenarioJson(withEnvironment(env), "s.json");
    } catch (const pkm::IoError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_THAT(message("\"lab\""), HasSubstr("s.json:5: /environment: unknown environment 'lab'"));
  EXPECT_THAT(message(R"({"air": {"dead_path_mm": -3}})"),
              HasSubstr("s.json:5: /environment/air: dead_path_mm must be >= 0"));
  EXPECT_THAT(message(R"({"air": {"humidity_sensor": {"noise": -1}}})"),
              HasSubstr("/environment/air/humidity_sensor/noise: must be >= 0"));
  EXPECT_THAT(message(R"({"air": {"wind": 1}})"), HasSubstr("unknown key 'wind'"));
  EXPECT_THAT(message(R"({"duration_h": 0})"), HasSubstr("duration_h must be > 0"));
  EXPECT_THAT(message(R"({"thermal": {"machine_material": "wood"}})"),
              HasSubstr("/environment/thermal/machine_material: unknown material 'wood'"));
  EXPECT_THAT(message(R"({"thermal": {"strut_material": "steel", "strut_cte_per_k": 1e-5}})"),
              HasSubstr("give either strut_material or strut_cte_per_k"));
  EXPECT_THAT(message(R"({"thermal": {"warmup_time_constant_h": 0}})"),
              HasSubstr("warmup_time_constant_h must be > 0"));
  EXPECT_THAT(message(R"({"setup": {"probe_lobes": 0}})"),
              HasSubstr("/environment/setup/probe_lobes: must be an integer in [1, 100]"));
  EXPECT_THAT(message(R"({"setup": {"reflector_offset_mm": -1}})"),
              HasSubstr("set-up errors must be finite and >= 0"));
  EXPECT_THAT(message(R"({"structure": {"correlation_s": 0}})"),
              HasSubstr("/environment/structure: structure correlation_s must be > 0"));
  EXPECT_THAT(message(R"({"compliance": {"x2": {"kind": "arch"}}})"),
              HasSubstr("/environment/compliance/x2/kind: must be \"none\", \"cantilever\""));
  EXPECT_THAT(message(R"({"compliance": {"hexapod": {"strut_stiffness_n_per_um": 0}}})"),
              HasSubstr("/environment/compliance/hexapod: strut_stiffness_n_per_um must be > 0"));
  EXPECT_THAT(message(R"({"compliance": {"cartesian": {"w": {}}}})"),
              HasSubstr("/environment/compliance/cartesian/w: unknown key 'w'"));
}

}  // namespace PKM_TEST_NS

namespace PKM_TEST_NS {

/// The built-in seed 004 scenario with `environment`.
std::string seed004With(const std::string& environment) {
  nlohmann::json j = nlohmann::json::parse(io::loadScenario("seed004-hexapod-calibration").text);
  j["environment"] = nlohmann::json::parse(environment);
  return j.dump();
}

TEST(Scenario, EnvironmentGeometryIsReadDrawnIntoTheMachineAndWrittenToTheTruth) {
  const io::Scenario s = io::parseScenarioJson(
      seed004With(R"({"geometry": {"lead_progressive_ppm": 50, "lead_wave_um": 5,
        "lead_wave_length_mm": 200, "lead_periodic_um": 2, "screw_lead_mm": 5,
        "joint_axis_offset_um": 10}})"),
      "s.json");
  const sim::GeometryEnvironment& g = s.campaign.environment.geometry;
  EXPECT_TRUE(g.enabled);
  EXPECT_DOUBLE_EQ(g.lead_progressive, 50e-6);
  EXPECT_DOUBLE_EQ(g.lead_wave_mm, 5e-3);
  EXPECT_EQ(g.lead_wave_length_mm, 200.0);
  EXPECT_DOUBLE_EQ(g.lead_periodic_mm, 2e-3);
  EXPECT_EQ(g.screw_lead_mm, 5.0);
  EXPECT_DOUBLE_EQ(g.joint_axis_offset_mm, 10e-3);
  const nlohmann::json t = nlohmann::json::parse(io::truthJson(s, s.seed));
  const nlohmann::json& u = t["unmodelled_geometry"];
  ASSERT_EQ(u["strut_lead"].size(), 6U);
  for (const nlohmann::json& lead : u["strut_lead"]) {
    EXPECT_LE(std::abs(lead["progressive_ppm"].get<double>()), 50.0);
    EXPECT_EQ(lead["wave_um"], 5.0);
    EXPECT_EQ(lead["lead_mm"], 5.0);
  }
  for (const nlohmann::json& joint : u["platform_joint"])
    EXPECT_LE(std::abs(joint["offset_um"].get<double>()), 10.0);
  // Off (ideal, or "enabled": false): the machine and the truth have none.
  const io::Scenario off =
      io::parseScenarioJson(seed004With(R"({"geometry": {"enabled": false}})"), "s.json");
  EXPECT_FALSE(nlohmann::json::parse(io::truthJson(off, off.seed)).contains("unmodelled_geometry"));
}

TEST(Scenario, EnvironmentGeometryErrorsNameThePointer) {
  const auto message = [](const std::string& env) {
    try {
      (void)io::parseScenarioJson(withEnvironment(env), "s.json");
    } catch (const pkm::IoError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_THAT(message(R"({"geometry": {"screw_lead_mm": 0}})"),
              HasSubstr("/environment/geometry: geometry lead_wave_length_mm (300) and "
                        "screw_lead_mm (0) must be > 0"));
  EXPECT_THAT(message(R"({"geometry": {"lead_wave_um": -1}})"),
              HasSubstr("geometry amplitudes and bounds must be finite and >= 0"));
  EXPECT_THAT(message(R"({"geometry": {"lead_um": 1}})"), HasSubstr("unknown key 'lead_um'"));
}

}  // namespace PKM_TEST_NS
