// io::gcodeRunJson / io::gcodeRunText: the members of the `gcode run --report` document (Exechon
// members only for an Exechon, a worst event only when one was evaluated), the table rows and
// the line of a violation.
#include "pkm/io/gcode_run_report.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

namespace pkm::io {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;

GcodeRunReport hexapodReport() {
  GcodeRunReport r;
  r.program = "upload.ngc";
  r.machine = "pkm-hx1200";
  r.machine_type = "hexapod";
  r.units = "mm";
  r.orientation = "vector";
  r.lines = 3;
  r.motions = 3;
  r.points = 40;
  r.tolerance_mm = 0.01;
  r.max_step_mm = 2.5;
  r.max_angle_step_deg = 0.5;
  r.max_joint_velocity = 200.0;
  r.max_joint_acceleration = 2000.0;
  r.rapid_rate_mm_per_min = 10000.0;
  r.cycle_time_s = 1.25;
  r.ok = false;
  GcodeCheckSummary stroke{"stroke", true, 2, "mm", {}, {}};
  stroke.worst = {3, {0, 0, -300, 0, 0, 0}, "strut 2", 710.5, 700.0, -10.5, "mm"};
  stroke.first = {3, {0, 0, -250, 0, 0, 0}, "strut 2", 700.25, 700.0, -0.25, "mm"};
  r.checks.push_back(stroke);
  r.checks.push_back({"reach", true, 0, "", {}, {}});  // never evaluated: margin +infinity
  r.checks.push_back({"interference", false, 0, "mm", {}, {}});
  return r;
}

TEST(GcodeRunReport, JsonHasTheDocumentedMembers) {
  const nlohmann::json j = nlohmann::json::parse(gcodeRunJson(hexapodReport()));
  EXPECT_EQ(j["program"], "upload.ngc");
  EXPECT_EQ(j["machine_type"], "hexapod");
  EXPECT_FALSE(j.contains("orientation"));
  EXPECT_FALSE(j.contains("max_wrist_velocity_deg_per_s"));
  EXPECT_EQ(j["points"], 40);
  EXPECT_FALSE(j["ok"].get<bool>());
  EXPECT_EQ(j["checks"]["stroke"]["violations"], 2);
  EXPECT_EQ(j["checks"]["stroke"]["worst"]["margin"], -10.5);
  EXPECT_EQ(j["checks"]["stroke"]["first_violation"]["line"], 3);
  EXPECT_EQ(j["checks"]["stroke"]["first_violation"]["position"][2], -250.0);
  EXPECT_FALSE(j["checks"]["reach"].contains("worst"));
  EXPECT_FALSE(j["checks"]["reach"].contains("first_violation"));
  EXPECT_FALSE(j["checks"]["interference"]["enabled"].get<bool>());
}

TEST(GcodeRunReport, ExechonMembersOnlyForAnExechon) {
  GcodeRunReport r = hexapodReport();
  r.machine_type = "exechon";
  r.orientation = "axes";
  r.max_wrist_velocity_deg_per_s = 180.0;
  const nlohmann::json j = nlohmann::json::parse(gcodeRunJson(r));
  EXPECT_EQ(j["orientation"], "axes");
  EXPECT_EQ(j["max_wrist_velocity_deg_per_s"], 180.0);
  EXPECT_THAT(gcodeRunText(r), HasSubstr("orientation: axes (A/C words are the wrist axes'"));
  EXPECT_THAT(gcodeRunText(r), HasSubstr("wrist velocity 180 deg/s"));
}

TEST(GcodeRunReport, TextHasOneRowPerCheckAndTheViolationLine) {
  GcodeRunReport r = hexapodReport();
  r.limits_from_machine_file = {"velocity", "acceleration"};
  r.dwell_time_s = 0.5;
  const std::string t = gcodeRunText(r);
  EXPECT_THAT(t, HasSubstr("gcode run: upload.ngc on pkm-hx1200 (3 lines, 3 motions, 40 points)"));
  EXPECT_THAT(t, HasSubstr("rapid 10000 mm/min (velocity, acceleration from the machine file)"));
  EXPECT_THAT(t, HasSubstr("cycle time: 1.250 s (dwells 0.500 s)"));
  EXPECT_THAT(
      t, HasSubstr("stroke              VIOLATED           2       -10.5 mm       3  strut 2"));
  EXPECT_THAT(t, HasSubstr("reach               ok                 0              -       -  \n"));
  EXPECT_THAT(t, HasSubstr("interference        n/a      \n"));
  EXPECT_THAT(t,
              HasSubstr("upload.ngc:3: stroke violated first at X0 Y0 Z-250 A0 B0 C0: strut 2 "
                        "value 700.25, limit 700, margin -0.25 mm\n"));
  EXPECT_THAT(t, ::testing::EndsWith("result: VIOLATIONS (exit code 1)\n"));
  r.ok = true;
  r.checks.resize(1);
  r.checks[0].violations = 0;
  EXPECT_THAT(gcodeRunText(r), ::testing::EndsWith("result: all checks pass\n"));
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::io
