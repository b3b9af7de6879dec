// workflow::analyzeCircle / analyzeCircular / analyzeProbeOffset on points of known circles;
// upload-named errors; bad requests refused.
#include "pkm/workflow/analyze_circle.hpp"

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "pkm/core/error.hpp"

namespace pkm::workflow {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;

/// `n` points of the circle (cx, cy, r), header x,y.
std::string circle(double cx, double cy, double r, int n, const std::string& extra = "") {
  std::string t = "x,y" + std::string(extra.empty() ? "" : ",direction") + "\n";
  for (int k = 0; k < n; ++k) {
    const double a = 2.0 * std::numbers::pi * k / n;
    t += fmt::format("{},{}{}\n", cx + r * std::cos(a), cy + r * std::sin(a), extra);
  }
  return t;
}

TEST(AnalyzeCircleWorkflow, FitsTheCircleAndNamesTheContacts) {
  const io::CircleReport r = analyzeCircle({{{"ring upload", circle(1.0, 2.0, 5.0, 12)}}});
  EXPECT_NEAR(r.lsc.circle.center.x(), 1.0, 1e-9);
  EXPECT_NEAR(r.lsc.circle.center.y(), 2.0, 1e-9);
  EXPECT_NEAR(r.lsc.circle.radius, 5.0, 1e-9);
  EXPECT_NEAR(r.mzc.roundness, 0.0, 1e-9);
  ASSERT_EQ(r.sources.size(), 12u);
  EXPECT_EQ(r.sources[0].name, "ring upload");
  EXPECT_EQ(r.sources[0].line, 2u);
}

TEST(AnalyzeCircleWorkflow, OneCircleWhenOneIsAskedAndPointsFromMemory) {
  // An oval: the two circles differ, so each report shows which one it holds.
  std::string text = "x,y\n";
  std::vector<metrology::Point2> points;
  for (int k = 0; k < 40; ++k) {
    const double a = 2.0 * std::numbers::pi * k / 40;
    points.emplace_back(3.0 + 5.01 * std::cos(a), -1.0 + 4.99 * std::sin(a));
    text += fmt::format("{},{}\n", points.back().x(), points.back().y());
  }
  CircleRequest both{{{"oval.csv", text}}};
  const io::CircleReport all = analyzeCircle(both);
  CircleRequest lsc{{{"oval.csv", text}}};
  lsc.fit = "lsc";
  const io::CircleReport l = analyzeCircle(lsc);
  EXPECT_TRUE(l.has_lsc && !l.has_mzc);
  EXPECT_EQ(l.lsc.circle.radius, all.lsc.circle.radius);
  ASSERT_EQ(l.uncertainty.size(), 2u);  // radius and roundness_lsc
  EXPECT_EQ(l.uncertainty[1].quantity, "roundness_lsc");
  CircleRequest mzc{{{"oval.csv", text}}};
  mzc.fit = "mzc";
  mzc.budget = false;
  const io::CircleReport m = analyzeCircle(mzc);
  EXPECT_TRUE(!m.has_lsc && m.has_mzc);
  EXPECT_EQ(m.mzc.roundness, all.mzc.roundness);
  EXPECT_TRUE(m.uncertainty.empty());
  // The same points from memory: the same circles, the contacts named by row.
  CircleRequest mem;
  mem.points = points;
  mem.points_name = "xy";
  const io::CircleReport p = analyzeCircle(mem);
  EXPECT_EQ(p.lsc.circle.radius, all.lsc.circle.radius);
  EXPECT_EQ(p.mzc.roundness, all.mzc.roundness);
  ASSERT_FALSE(p.mzc.contacts.empty());
  const std::size_t i = p.mzc.contacts[0].index;
  EXPECT_EQ(p.sources[i].name, "xy");
  EXPECT_EQ(p.sources[i].line, i + 1);
  CircleRequest bad{{{"oval.csv", text}}};
  bad.fit = "lse";
  EXPECT_THROW((void)analyzeCircle(bad), InvalidArgument);
  bad.fit = "lsc";
  bad.points = points;
  EXPECT_THROW((void)analyzeCircle(bad), IoError);  // tables and points
}

TEST(AnalyzeCircleWorkflow, TheRingsCertificateInTheFileEntersTheBudget) {
  // "# ring form mm: 0.002" (Lee et al. 2019, Table 4) replaces the sources' typical 0.5 µm.
  const auto ring_form = [](const io::CircleReport& r) {
    for (const metrology::UncertaintyBudget& b : r.uncertainty)
      for (const metrology::UncertaintyContributor& c : b.contributors)
        if (c.name.find("ring form") != std::string::npos) return c.value;
    return -1.0;
  };
  const std::string points = circle(0.0, 0.0, 20.0, 36);
  const io::CircleReport plain = analyzeCircle({{{"ring.csv", points}}});
  EXPECT_DOUBLE_EQ(ring_form(plain), metrology::TouchProbe{}.ring_form_mm);
  const io::CircleReport cert = analyzeCircle({{{"ring.csv", "# ring form mm: 0.002\n" + points}}});
  EXPECT_DOUBLE_EQ(ring_form(cert), 0.002);
  try {
    (void)analyzeCircle({{{"ring.csv", "# ring form mm: -1\n" + points}}});
    FAIL() << "accepted a negative ring form";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("ring.csv"));
    EXPECT_THAT(e.what(), HasSubstr("ring form mm"));
  }
}

TEST(AnalyzeCircleWorkflow, CircularOfTwoPerfectRunsHasNoDeviation) {
  CircularRequest r;
  r.data = {{"cw", circle(0, 0, 50, 36)}, {"ccw", circle(0, 0, 50, 36)}};
  const io::CircularReport rep = analyzeCircular(r);
  EXPECT_EQ(rep.points_cw, 36u);
  EXPECT_EQ(rep.points_ccw, 36u);
  EXPECT_NEAR(rep.result.cw.circular_deviation, 0.0, 1e-9);
  EXPECT_NEAR(rep.result.hysteresis, 0.0, 1e-9);
}

TEST(AnalyzeCircleWorkflow, ABadDirectionIsLocatedInTheUpload) {
  CircularRequest r;
  r.data = {{"web.csv", "x,y,direction\n1,0,cw\n0,1,up\n"}};
  try {
    (void)analyzeCircular(r);
    FAIL() << "accepted direction 'up'";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("web.csv:3: direction must be cw or ccw"));
  }
}

TEST(AnalyzeCircleWorkflow, BadRequestsAreRefused) {
  EXPECT_THROW(CircleRequest{}.validate(), IoError);
  CircularRequest c;
  c.data = {{"a", ""}, {"b", ""}, {"c", ""}};
  EXPECT_THROW(c.validate(), IoError);
  c.data.resize(1);
  c.nominal_radius = -1.0;
  EXPECT_THROW(c.validate(), InvalidArgument);
  ProbeOffsetRequest p;
  p.data = c.data;
  p.ring_diameter = 0.0;
  EXPECT_THROW((void)analyzeProbeOffset(p), InvalidArgument);
}

TEST(AnalyzeCircleWorkflow, ProbeOffsetRecoversTheBallOffset) {
  // Ball centre b = s + R(ψ)·d on the circle of radius 20 about the origin; spindle angles ψ with
  // tool direction +z (ψ = +spindle angle).
  const Eigen::Vector2d d(0.03, -0.01);
  std::string t = "spindle_deg,x,y\n";
  for (int k = 0; k < 16; ++k) {
    const double psi = 2.0 * std::numbers::pi * (k % 4) / 4.0;
    const double a = 2.0 * std::numbers::pi * k / 16.0;
    const Eigen::Vector2d b(20.0 * std::cos(a), 20.0 * std::sin(a));
    const Eigen::Vector2d rd(std::cos(psi) * d.x() - std::sin(psi) * d.y(),
                             std::sin(psi) * d.x() + std::cos(psi) * d.y());
    const Eigen::Vector2d s = b - rd;
    t += fmt::format("{},{},{}\n", 90.0 * (k % 4), s.x(), s.y());
  }
  ProbeOffsetRequest r;
  r.data = {{"touches", t}};
  r.tool_plus_z = true;
  r.ring_diameter = 42.0;
  const io::ProbeOffsetReport rep = analyzeProbeOffset(r);
  EXPECT_EQ(rep.touches, 16u);
  EXPECT_NEAR(rep.fit.offset.x(), d.x(), 1e-9);
  EXPECT_NEAR(rep.fit.offset.y(), d.y(), 1e-9);
  EXPECT_NEAR(rep.fit.ball_path_radius, 20.0, 1e-9);
  ASSERT_TRUE(rep.effective_stylus_radius.has_value());
  EXPECT_NEAR(*rep.effective_stylus_radius, 1.0, 1e-9);
  EXPECT_FALSE(rep.paper.has_value());  // no labelled touches
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::workflow
