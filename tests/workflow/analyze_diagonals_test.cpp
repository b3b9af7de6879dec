// workflow::analyzeDiagonals: body diagonals of a known box from a table, the notice when ISO 230-2
// statistics cannot be computed, upload-named errors, bad requests refused.
#include "pkm/workflow/analyze_diagonals.hpp"

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "pkm/core/error.hpp"

namespace pkm::workflow {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;

/// A body-diagonal table with the length error `error[d]` of each diagonal, growing linearly
/// from its start corner (one reading per position).
std::string bodyTable(double length, const std::array<double, 4>& error) {
  std::string t = "diagonal,position,deviation\n";
  const char* names[] = {"PPP", "NPP", "PNP", "NNP"};
  for (int d = 0; d < 4; ++d)
    for (int k = 0; k <= 4; ++k) {
      const double s = length * k / 4.0;
      t += fmt::format("{},{},{}\n", names[d], s, error[static_cast<std::size_t>(d)] * k / 4.0);
    }
  return t;
}

TEST(AnalyzeDiagonalsWorkflow, EqualLengthErrorsAreAScaleErrorWithoutSquareness) {
  DiagonalsRequest r;
  r.size = Eigen::Vector3d(300.0, 400.0, 1200.0);  // D = 1300
  const double e = 0.013;                          // ΔD/D = 1e-5 on every diagonal
  r.data = {{"upload", bodyTable(1300.0, {e, e, e, e})}};
  std::vector<std::string> notices;
  RunControl control;
  control.notice = [&](const std::string& n) { notices.push_back(n); };
  const io::DiagonalsReport rep = analyzeDiagonals(r, control);
  ASSERT_TRUE(rep.body.has_value());
  EXPECT_FALSE(rep.step.has_value());
  EXPECT_NEAR(rep.body->length, 1300.0, 1e-9);
  EXPECT_NEAR(rep.body->diagonals[0].length_error, e, 1e-12);
  EXPECT_NEAR(rep.body->solution.squareness_xy, 0.0, 1e-12);
  EXPECT_NEAR(rep.body->solution.squareness_xz, 0.0, 1e-12);
  EXPECT_NEAR(rep.body->solution.squareness_yz, 0.0, 1e-12);
  EXPECT_NEAR(rep.body->solution.scale, 1e-5, 1e-12);
  ASSERT_EQ(notices.size(), 1u);  // one reading per target: no ISO 230-2 statistics
  EXPECT_THAT(notices[0], HasSubstr("ISO 230-2"));
  EXPECT_FALSE(rep.body->diagonals[0].iso.has_value());
}

TEST(AnalyzeDiagonalsWorkflow, ABadDiagonalNameIsLocatedInTheUpload) {
  DiagonalsRequest r;
  r.size = Eigen::Vector3d(1.0, 1.0, 1.0);
  r.data = {{"browser upload", "diagonal,position,deviation\nPPP,0,0\nXYZ,1,0\n"}};
  try {
    (void)analyzeDiagonals(r);
    FAIL() << "accepted diagonal XYZ";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("browser upload:3: diagonal 'XYZ'"));
  }
}

TEST(AnalyzeDiagonalsWorkflow, BadRequestsAreRefused) {
  DiagonalsRequest r;
  EXPECT_THROW(r.validate(), IoError);  // no data
  r.data = {{"a", "diagonal,position,deviation\n"}};
  EXPECT_THROW(r.validate(), InvalidArgument);  // zero box
  r.size = Eigen::Vector3d(1.0, 2.0, 3.0);
  r.compare = r.data;
  EXPECT_THROW(r.validate(), InvalidArgument);  // comparisons need step or shifted
  r.method = io::DiagonalMethod::kStep;
  EXPECT_NO_THROW(r.validate());
}

TEST(AnalyzeDiagonalsWorkflow, StepSubStepsOutOfOrderAreLocated) {
  DiagonalsRequest r;
  r.method = io::DiagonalMethod::kStep;
  r.size = Eigen::Vector3d(1.0, 1.0, 1.0);
  r.data = {{"steps", "diagonal,position,sub_step,deviation\nPPP,0.5,1,0\nPPP,0.5,3,0\n"}};
  try {
    (void)analyzeDiagonals(r);
    FAIL() << "accepted sub-step 3 after 1";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("steps:3: sub-steps of a step must come in the order 1, 2, 3"));
  }
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::workflow
