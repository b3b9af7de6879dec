// workflow::runDemo: both round trips pass on the default machines, the Exechon part only on the
// default machine, progress stages and cancellation, bad requests refused.
#include "pkm/workflow/demo.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "pkm/core/error.hpp"

namespace pkm::workflow {
namespace PKM_TEST_NS {

TEST(DemoWorkflow, TheRoundTripsReturnEveryPose) {
  DemoRequest q;
  q.points = 200;
  std::vector<std::string> stages;
  RunControl control;
  control.progress = [&](const ProgressEvent& e) { stages.push_back(e.stage); };
  const DemoResult r = runDemo(q, control);
  EXPECT_TRUE(r.pass());
  EXPECT_EQ(r.hexapod.points, 200);
  EXPECT_EQ(r.hexapod.converged, 200);
  EXPECT_LT(r.hexapod.max_position_error, 1e-6);
  EXPECT_THAT(r.hexapod.description, ::testing::HasSubstr("machine "));
  ASSERT_TRUE(r.exechon.has_value());
  EXPECT_TRUE(r.exechon->path_solved);
  EXPECT_EQ(r.exechon->converged, 200);
  EXPECT_EQ(r.exechon->drm_status, "ok");
  EXPECT_EQ(r.exechon->volumetric_points, 9 * 5 * 5);
  EXPECT_EQ(stages, (std::vector<std::string>{"hexapod", "exechon"}));
}

TEST(DemoWorkflow, AnotherMachineHasNoExechonPart) {
  DemoRequest q;
  q.machine = "hexapod-default";
  q.points = 50;
  const DemoResult r = runDemo(q);
  EXPECT_FALSE(r.exechon.has_value());
  EXPECT_TRUE(r.pass());
}

TEST(DemoWorkflow, StopsWhenCancelled) {
  CancellationToken token;
  token.cancel();
  RunControl control;
  control.cancel = &token;
  DemoRequest q;
  q.points = 50;
  EXPECT_THROW((void)runDemo(q, control), Cancelled);
}

TEST(DemoWorkflow, RefusesABadRequest) {
  DemoRequest q;
  q.points = 1;
  EXPECT_THROW(q.validate(), InvalidArgument);
  q.points = 10;
  q.machine = "no-such-machine";
  EXPECT_THROW((void)runDemo(q), IoError);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::workflow
