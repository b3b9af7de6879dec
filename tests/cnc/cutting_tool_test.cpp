// The tool's solid and its lowest point on a vertical line, against closed forms and a brute-force
// search over points of the solid.
#include "pkm/cnc/cutting_tool.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "pkm/core/error.hpp"

namespace pkm::cnc {
namespace PKM_TEST_NS {

/// Agreement of the closed form with itself across evaluations (rounding only), mm.
constexpr double kTolClosedForm = 1e-9;
/// The brute-force search's resolution: a point found inside lies at most this far above the
/// true lowest point (the search steps 0.001 mm in z).
constexpr double kTolSearch = 2e-3;

bool insideCylinder(const SolidCylinder& c, const std::array<double, 3>& p) {
  const std::array<double, 3> d{p[0] - c.from[0], p[1] - c.from[1], p[2] - c.from[2]};
  const double s = d[0] * c.axis[0] + d[1] * c.axis[1] + d[2] * c.axis[2];
  if (s < 0.0 || s > c.length) return false;
  const double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2] - s * s;
  return r2 <= c.radius * c.radius;
}

TEST(CuttingTool, VerticalFlatAndBallEndsHaveTheirClosedForms) {
  CuttingTool flat;
  flat.diameter = 10.0;
  flat.length = 40.0;
  const ToolSolid f = toolSolid(flat, {{1.0, 2.0, 3.0}, {0.0, 0.0, 1.0}});
  EXPECT_NEAR(f.cutterZ(1.0, 2.0), 3.0, kTolClosedForm);
  EXPECT_NEAR(f.cutterZ(5.9, 2.0), 3.0, kTolClosedForm);
  EXPECT_EQ(f.cutterZ(6.1, 2.0), std::numeric_limits<double>::infinity());
  EXPECT_NEAR(f.holderZ(1.0, 2.0), 43.0, kTolClosedForm);
  EXPECT_NEAR(f.holderZ(20.0, 2.0), 43.0, kTolClosedForm);  // the 40 mm holder is wider
  EXPECT_NEAR(f.bottom(), 3.0, kTolClosedForm);
  CuttingTool ball = flat;
  ball.end = ToolEnd::kBall;
  const ToolSolid b = toolSolid(ball, {{0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}});
  EXPECT_NEAR(b.cutterZ(0.0, 0.0), 0.0, kTolClosedForm);
  EXPECT_NEAR(b.cutterZ(3.0, 4.0), 5.0 - 0.0, kTolClosedForm);  // on the ball's equator
  EXPECT_NEAR(b.cutterZ(3.0, 0.0), 5.0 - 4.0, kTolClosedForm);
  const auto box = b.footprint(false);
  EXPECT_NEAR(box[0], -5.0, kTolClosedForm);
  EXPECT_NEAR(box[3], 5.0, kTolClosedForm);
}

TEST(CuttingTool, TiltedSolidsMatchABruteForceSearch) {
  std::mt19937 rng(41);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 15; ++trial) {
    std::array<double, 3> axis{0.6 * u(rng), 0.6 * u(rng), 1.0};
    const double n = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + 1.0);
    for (double& a : axis) a /= n;
    const SolidCylinder c{{u(rng), u(rng), u(rng)}, axis, 20.0, 3.0};
    for (int k = 0; k < 10; ++k) {
      const double x = c.from[0] + 6.0 * u(rng), y = c.from[1] + 6.0 * u(rng);
      const double z = lowestZ(c, x, y);
      double found = std::numeric_limits<double>::infinity();
      for (double zz = -10.0; zz <= 30.0; zz += 0.001)
        if (insideCylinder(c, {x, y, zz})) {
          found = zz;
          break;
        }
      if (std::isinf(found)) {
        EXPECT_TRUE(std::isinf(z) || !insideCylinder(c, {x, y, z + kTolSearch})) << trial;
        continue;
      }
      EXPECT_NEAR(z, found, kTolSearch) << "trial " << trial << " x " << x << " y " << y;
    }
  }
}

TEST(CuttingTool, AHorizontalToolIsCutAtItsSide) {
  const SolidCylinder c{{0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, 10.0, 2.0};
  EXPECT_NEAR(lowestZ(c, 5.0, 0.0), -2.0, kTolClosedForm);
  EXPECT_NEAR(lowestZ(c, 5.0, 1.2), -1.6, kTolClosedForm);
  EXPECT_EQ(lowestZ(c, 11.0, 0.0), std::numeric_limits<double>::infinity());
  EXPECT_EQ(lowestZ(c, 5.0, 2.5), std::numeric_limits<double>::infinity());
}

TEST(CuttingTool, TheTableCommentGivesTheEnd) {
  EXPECT_EQ(toolEndOf("6 mm Ball-end mill"), ToolEnd::kBall);
  EXPECT_EQ(toolEndOf("BALLNOSE"), ToolEnd::kBall);
  EXPECT_EQ(toolEndOf("8.5 mm drill"), ToolEnd::kFlat);
  ToolEntry e;
  e.number = 3;
  e.diameter = 6.0;
  e.offset[2] = 50.0;
  e.comment = "ball";
  const CuttingTool t = cuttingToolOf(e, CuttingTool{});
  EXPECT_EQ(t.end, ToolEnd::kBall);
  EXPECT_EQ(t.number, 3);
  e.diameter = 0.0;
  EXPECT_THROW((void)cuttingToolOf(e, CuttingTool{}), InvalidArgument);
  CuttingTool bad;
  bad.holder_length = std::nan("");
  EXPECT_THROW(bad.validate(), InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::cnc
