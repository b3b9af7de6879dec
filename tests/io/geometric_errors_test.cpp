// Tests of the geometric-errors JSON reader and writer (pkm/io/geometric_errors.hpp): the shipped
// seed-000 file, the write -> parse round trip, defaults and out-of-range policies. The
// "FILE:LINE: /pointer:" errors are in geometric_errors_json_errors_test.cpp.
#include "pkm/io/geometric_errors.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "io/geometric_errors_sample.hpp"
#include "pkm/core/error.hpp"
#include "support/tolerances.hpp"

namespace PKM_TEST_NS {

namespace kin = pkm::kinematics;
namespace geo = pkm::geometry;
using pkm::io::parseGeometricErrorsJson;
using pkm::io::readGeometricErrorsJson;
using pkm::io::writeGeometricErrorsJson;
using pkm::test::kTolExact;
using pkm::test::errors_json::kSource;
using pkm::test::errors_json::text;

/// Relative tolerance of a value written and read back (rotations pass through µrad: one division
/// and one multiplication, a few ulp).
constexpr double kTolRoundTripRelative = 1e-15;
/// Microradians in a radian: the file's rotation unit.
constexpr double kUrad = 1e-6;

const std::string kSeedFile = std::string(PKM_SOURCE_DIR) + "/data/errors/mxt700s-seed000.json";

void expectNearRelative(double a, double b, double rel) {
  EXPECT_NEAR(a, b, rel * std::max(std::abs(a), std::abs(b))) << a << " vs " << b;
}

void expectSameMatrix(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  ASSERT_EQ(a.rows(), b.rows());
  ASSERT_EQ(a.cols(), b.cols());
  for (Eigen::Index i = 0; i < a.rows(); ++i)
    for (Eigen::Index j = 0; j < a.cols(); ++j) {
      SCOPED_TRACE(testing::Message() << "row " << i << " column " << j);
      expectNearRelative(a(i, j), b(i, j), kTolRoundTripRelative);
    }
}

void expectSameTable(const std::optional<geo::ErrorTable1d>& a,
                     const std::optional<geo::ErrorTable1d>& b) {
  ASSERT_EQ(a.has_value(), b.has_value());
  if (!a) return;
  EXPECT_EQ(a->positions(), b->positions());
  EXPECT_EQ(a->outOfRange(), b->outOfRange());
  expectSameMatrix(a->values(), b->values());
}

void expectSameErrors(const kin::GeometricErrors& a, const kin::GeometricErrors& b) {
  expectNearRelative(a.squareness.sz_x2, b.squareness.sz_x2, kTolRoundTripRelative);
  expectNearRelative(a.squareness.sx_p, b.squareness.sx_p, kTolRoundTripRelative);
  expectNearRelative(a.squareness.sy_p, b.squareness.sy_p, kTolRoundTripRelative);
  expectNearRelative(a.squareness.sz_p, b.squareness.sz_p, kTolRoundTripRelative);
  {
    SCOPED_TRACE("x2");
    expectSameTable(a.x2, b.x2);
  }
  {
    SCOPED_TRACE("y2");
    expectSameTable(a.y2, b.y2);
  }
  ASSERT_EQ(a.pkm.has_value(), b.pkm.has_value());
  if (a.pkm) {
    SCOPED_TRACE("pkm");
    for (int k = 0; k < 3; ++k) EXPECT_EQ(a.pkm->axis(k), b.pkm->axis(k)) << k;
    EXPECT_EQ(a.pkm->outOfRange(), b.pkm->outOfRange());
    expectSameMatrix(a.pkm->values(), b.pkm->values());
  }
}

// ---------------------------------------------------------------------------------------------
// The shipped file

TEST(GeometricErrorsJson, ReadsSeedFile) {
  const kin::GeometricErrors e = readGeometricErrorsJson(kSeedFile);
  // Squareness: µrad in the file, rad in the model (seed 000: -0.034, -14.74, 4.35, -2.85 mrad).
  EXPECT_DOUBLE_EQ(e.squareness.sz_x2, -34e-6);
  EXPECT_DOUBLE_EQ(e.squareness.sx_p, -14740e-6);
  EXPECT_DOUBLE_EQ(e.squareness.sy_p, 4350e-6);
  EXPECT_DOUBLE_EQ(e.squareness.sz_p, -2850e-6);

  ASSERT_TRUE(e.x2.has_value());
  EXPECT_EQ(e.x2->outOfRange(), geo::OutOfRange::kClamp);
  EXPECT_EQ(e.x2->positions(), (std::vector<double>{0, 125, 250, 375, 500, 625, 750, 875}));
  ASSERT_EQ(e.x2->components(), 6);
  EXPECT_EQ(e.x2->values()(3, geo::kDx), -0.033429);
  EXPECT_EQ(e.x2->values()(7, geo::kDx), -0.078);  // seed 000 Table 2: EXX -0.078 mm
  EXPECT_EQ(e.x2->values()(4, geo::kDy), 0.0039);
  EXPECT_EQ(e.x2->values()(7, geo::kDz), -0.012);
  EXPECT_DOUBLE_EQ(e.x2->values()(7, geo::kEy), -69.0 * kUrad);  // EBX -0.069 mrad
  EXPECT_DOUBLE_EQ(e.x2->values()(1, geo::kEy), -9.857143 * kUrad);
  // Columns left out of the file are zero.
  EXPECT_TRUE(e.x2->values().col(geo::kEx).isZero(0.0));
  EXPECT_TRUE(e.x2->values().col(geo::kEz).isZero(0.0));

  ASSERT_TRUE(e.y2.has_value());
  EXPECT_EQ(e.y2->positions().size(), 8u);
  EXPECT_EQ(e.y2->positions().back(), 350.0);
  EXPECT_EQ(e.y2->values()(7, geo::kDy), 0.01);  // EYY 0.010 mm
  EXPECT_EQ(e.y2->values()(3, geo::kDx), 0.002925);
  EXPECT_EQ(e.y2->values()(7, geo::kDz), -0.002);
  EXPECT_TRUE(e.y2->values().rightCols(3).isZero(0.0));

  ASSERT_TRUE(e.pkm.has_value());
  EXPECT_EQ(e.pkm->axis(0), std::vector<double>{0});
  EXPECT_EQ(e.pkm->axis(1), std::vector<double>{0});
  EXPECT_EQ(e.pkm->axis(2), (std::vector<double>{0, 30, 60, 90, 120, 150, 180, 210}));
  ASSERT_EQ(e.pkm->values().rows(), 8);
  EXPECT_EQ(e.pkm->values()(7, geo::kDz), 0.805);  // EZZ 0.805 mm
  // Between nodes the grid interpolates; outside it holds the end value (clamp) on every axis.
  EXPECT_NEAR(e.pkm->evaluate({0, 0, 105})[geo::kDz], 0.4025, kTolExact);
  EXPECT_EQ(e.pkm->evaluate({300, -50, 500})[geo::kDz], 0.805);
  EXPECT_EQ(e.x2->evaluate(4000)[geo::kDx], -0.078);
  EXPECT_EQ(e.x2->evaluate(-10)[geo::kDy], 0.0);
}

// ---------------------------------------------------------------------------------------------
// Round trip

TEST(GeometricErrorsJson, RoundTripOfSeedFile) {
  const kin::GeometricErrors e = readGeometricErrorsJson(kSeedFile);
  const std::string json = writeGeometricErrorsJson(e);
  const kin::GeometricErrors back = parseGeometricErrorsJson(json, "round-trip.json");
  expectSameErrors(e, back);
  EXPECT_EQ(writeGeometricErrorsJson(back), json);  // a fixed point
}

TEST(GeometricErrorsJson, RoundTripOfRandomErrors) {
  std::mt19937 rng(pkm::test::kSeed);
  std::uniform_real_distribution<double> length(-0.1, 0.1), angle(-1e-3, 1e-3);
  const auto motion = [&] {
    Eigen::MatrixXd m(1, 6);
    m << length(rng), length(rng), length(rng), angle(rng), angle(rng), angle(rng);
    return m;
  };
  const auto rows = [&](std::size_t n) {
    Eigen::MatrixXd v(static_cast<Eigen::Index>(n), 6);
    for (Eigen::Index i = 0; i < v.rows(); ++i) v.row(i) = motion();
    return v;
  };
  kin::GeometricErrors e;
  e.squareness = {angle(rng), angle(rng), angle(rng), angle(rng)};
  e.x2.emplace(std::vector<double>{-1.5, 0, 1.0 / 3.0, 875.125}, rows(4), geo::OutOfRange::kThrow);
  e.y2.emplace(std::vector<double>{7}, rows(1), geo::OutOfRange::kClamp);
  e.pkm.emplace(std::array<std::vector<double>, 3>{std::vector<double>{-300, 0.1, 300},
                                                   std::vector<double>{-1e-3, 1e-3},
                                                   std::vector<double>{0, 10, 20, 1e4}},
                rows(3 * 2 * 4),
                geo::OutOfRange::kThrow);
  const kin::GeometricErrors back =
      parseGeometricErrorsJson(writeGeometricErrorsJson(e), "random.json");
  expectSameErrors(e, back);
}

TEST(GeometricErrorsJson, EmptyErrorsRoundTrip) {
  const kin::GeometricErrors e;
  const std::string json = writeGeometricErrorsJson(e);
  const kin::GeometricErrors back = parseGeometricErrorsJson(json, "empty.json");
  EXPECT_FALSE(back.x2.has_value());
  EXPECT_FALSE(back.y2.has_value());
  EXPECT_FALSE(back.pkm.has_value());
  EXPECT_EQ(back.squareness.sz_x2, 0.0);
  EXPECT_EQ(back.squareness.sz_p, 0.0);
}

// ---------------------------------------------------------------------------------------------
// Defaults and out-of-range policies

TEST(GeometricErrorsJson, TemplateValuesAndAbsentColumnsReadAsZero) {
  const kin::GeometricErrors e = parseGeometricErrorsJson(text(), kSource);
  EXPECT_DOUBLE_EQ(e.squareness.sz_x2, -34 * kUrad);
  EXPECT_DOUBLE_EQ(e.squareness.sx_p, 10 * kUrad);
  EXPECT_EQ(e.squareness.sy_p, 0.0);  // absent squareness: zero
  EXPECT_EQ(e.squareness.sz_p, 0.0);
  ASSERT_TRUE(e.x2 && e.y2 && e.pkm);
  // x2 gives dx and ey only.
  const Eigen::VectorXd x2 = e.x2->evaluate(150);
  EXPECT_NEAR(x2[geo::kDx], 0.02, kTolExact);
  EXPECT_NEAR(x2[geo::kEy], -7.5 * kUrad, kTolExact);
  for (int c : {geo::kDy, geo::kDz, geo::kEx, geo::kEz}) EXPECT_EQ(x2[c], 0.0) << c;
  // y2 gives dy only; the default policy is clamp.
  EXPECT_EQ(e.y2->outOfRange(), geo::OutOfRange::kClamp);
  EXPECT_EQ(e.y2->evaluate(1000)[geo::kDy], 0.002);
  EXPECT_EQ(e.y2->values().col(geo::kDx).norm(), 0.0);
  // pkm: node (i, j, k) is row i + nx·(j + ny·k), x fastest.
  EXPECT_EQ(e.pkm->evaluate({100, 0, 0})[geo::kDz], 0.1);
  EXPECT_EQ(e.pkm->evaluate({-100, 0, 10})[geo::kDz], 0.2);
  EXPECT_NEAR(e.pkm->evaluate({0, 0, 5})[geo::kDz], 0.175, kTolExact);
  EXPECT_EQ(e.pkm->evaluate({0, 0, 5})[geo::kDx], 0.0);
}

TEST(GeometricErrorsJson, AbsentSectionsAreZero) {
  const kin::GeometricErrors e =
      parseGeometricErrorsJson("{\"type\": \"hybrid_geometric_errors\"}", kSource);
  EXPECT_FALSE(e.x2 || e.y2 || e.pkm);
  EXPECT_EQ(e.squareness.sz_x2, 0.0);
  const kin::HybridErrorValues v = kin::evaluateHybridErrors(e, {123, 45, {1, 2, 3}});
  EXPECT_TRUE(v.x2.isZero(0.0));
  EXPECT_TRUE(v.y2.isZero(0.0));
  EXPECT_TRUE(v.pkm.isZero(0.0));
}

TEST(GeometricErrorsJson, ErrorPolicyThrowsOutsideTheTable) {
  const kin::GeometricErrors e =
      parseGeometricErrorsJson(text({{6, "  \"x2\": {\"out_of_range\": \"error\","}}), kSource);
  ASSERT_TRUE(e.x2.has_value());
  EXPECT_EQ(e.x2->outOfRange(), geo::OutOfRange::kThrow);
  EXPECT_NEAR(e.x2->evaluate(200)[geo::kDx], 0.03, kTolExact);  // the end node itself is inside
  EXPECT_THROW((void)e.x2->evaluate(200.5), pkm::InvalidArgument);
  EXPECT_THROW((void)e.x2->evaluate(-1), pkm::InvalidArgument);
  // Through the machine's error evaluation too.
  EXPECT_NO_THROW((void)kin::evaluateHybridErrors(e, {100, 0, {0, 0, 0}}));
  EXPECT_THROW((void)kin::evaluateHybridErrors(e, {250, 0, {0, 0, 0}}), pkm::InvalidArgument);
  // The same table with "clamp" holds the end value.
  const kin::GeometricErrors c = parseGeometricErrorsJson(text(), kSource);
  EXPECT_EQ(c.x2->evaluate(250)[geo::kDx], c.x2->values()(2, geo::kDx));
  EXPECT_EQ(c.x2->evaluate(-50)[geo::kEy], 0.0);
  EXPECT_EQ(kin::evaluateHybridErrors(c, {250, 0, {0, 0, 0}}).x2[geo::kDx], 0.03);
}

TEST(GeometricErrorsJson, ErrorPolicyOnTheGrid) {
  const kin::GeometricErrors e =
      parseGeometricErrorsJson(text({{12, "  \"pkm\": {\"out_of_range\": \"error\","}}), kSource);
  ASSERT_TRUE(e.pkm.has_value());
  EXPECT_EQ(e.pkm->outOfRange(), geo::OutOfRange::kThrow);
  EXPECT_NO_THROW((void)e.pkm->evaluate({0, 0, 5}));
  EXPECT_THROW((void)e.pkm->evaluate({0, 0, 11}), pkm::InvalidArgument);
  EXPECT_THROW((void)e.pkm->evaluate({0, 1, 5}), pkm::InvalidArgument);  // y has one node: 0
}

}  // namespace PKM_TEST_NS
