// The height-field stock: its cells, outline, volume and limits.
#include "pkm/cnc/height_field.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "pkm/core/error.hpp"

namespace pkm::cnc {
namespace PKM_TEST_NS {

/// Volume sums over float heights: rounding of the stored heights, mm³.
constexpr double kTolVolume = 1e-6;
/// A cylinder's outline on 0.1 mm cells: the area of a ring one cell wide about its edge, relative.
constexpr double kTolOutline = 0.01;

StockShape box(double x0, double y0, double x1, double y1, double z0, double z1) {
  StockShape s;
  s.min = {x0, y0};
  s.max = {x1, y1};
  s.bottom = z0;
  s.top = z1;
  return s;
}

TEST(HeightField, ABoxHoldsItsVolumeAndCellCentres) {
  HeightField f(box(-10.0, 0.0, 10.0, 5.0, -2.0, 3.0), 0.5);
  EXPECT_EQ(f.nx(), 40u);
  EXPECT_EQ(f.ny(), 10u);
  EXPECT_DOUBLE_EQ(f.cx(0), -9.75);
  EXPECT_DOUBLE_EQ(f.cy(9), 4.75);
  EXPECT_NEAR(f.volume(), 20.0 * 5.0 * 5.0, kTolVolume);
  EXPECT_NEAR(f.lower(0, 1.0), 2.0, kTolVolume);
  EXPECT_NEAR(f.lower(0, 2.0), 0.0, kTolVolume);    // never raised
  EXPECT_NEAR(f.lower(1, -50.0), 5.0, kTolVolume);  // never below the bottom
  EXPECT_FLOAT_EQ(f.height(1), -2.0f);
  const auto cols = f.columns(-9.0, -8.0);
  EXPECT_LE(cols[0], 1);
  EXPECT_GE(cols[1], 3);
  const auto none = f.columns(20.0, 30.0);
  EXPECT_GT(none[0], none[1]);
  const auto all = f.rows(-std::numeric_limits<double>::infinity(), 1e300);
  EXPECT_EQ(all[0], 0);
  EXPECT_EQ(all[1], 9);
}

TEST(HeightField, ACylinderHasMaterialInsideItsOutlineOnly) {
  StockShape s;
  s.kind = StockShape::Kind::kCylinder;
  s.centre = {5.0, 5.0};
  s.radius = 10.0;
  s.bottom = 0.0;
  s.top = 10.0;
  HeightField f(s, 0.1);
  EXPECT_NEAR(f.volume(), std::numbers::pi * 100.0 * 10.0, kTolOutline * f.volume());
  EXPECT_FALSE(f.inside(0));  // the box's corner
  EXPECT_TRUE(f.inside(f.ny() / 2 * f.nx() + f.nx() / 2));
}

TEST(HeightField, BadStockIsRefused) {
  EXPECT_THROW(HeightField(box(0, 0, 0, 5, 0, 1), 1.0), InvalidArgument);
  EXPECT_THROW(HeightField(box(0, 0, 5, 5, 1, 1), 1.0), InvalidArgument);
  EXPECT_THROW(HeightField(box(0, 0, 5, 5, 0, 1), 0.0), InvalidArgument);
  EXPECT_THROW(HeightField(box(0, 0, 5, 5, 0, std::nan("")), 1.0), InvalidArgument);
  EXPECT_THROW(HeightField(box(0, 0, 1e4, 1e4, 0, 1), 0.001), InvalidArgument);  // 1e14 cells
  StockShape c;
  c.kind = StockShape::Kind::kCylinder;
  c.top = 1.0;
  EXPECT_THROW(HeightField(c, 1.0), InvalidArgument);  // radius 0
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::cnc
