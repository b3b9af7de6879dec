// The link to a running LinuxCNC (pkm/live/linuxcnc_link.hpp) with stand-in readers: records
// kept, an error after them, a reader that stops writing (stale), one that ends, one that will
// not end (stopped within seconds), one that cannot start; and the embedded reader itself on a
// host where no LinuxCNC runs.
#include "pkm/live/linuxcnc_link.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "pkm/core/error.hpp"
#include "support/linuxcnc_record.hpp"

namespace pkm::live {
namespace PKM_TEST_NS {

using namespace std::chrono_literals;
using pkm::test::linuxcncRecord;
using ::testing::HasSubstr;

/// A reader that writes `lines`, then waits for its input to close (as the real one does).
LinkOptions writes(const std::vector<std::string>& lines,
                   const std::string& then = "cat >/dev/null") {
  std::string script;
  for (std::size_t i = 0; i < lines.size(); ++i)
    script += "printf '%s\\n' \"$" + std::to_string(i + 1) + "\"; ";
  script += then;
  LinkOptions o;
  o.command = {"/bin/sh", "-c", script, "reader"};
  o.command.insert(o.command.end(), lines.begin(), lines.end());
  return o;
}

TEST(LinuxcncLink, KeepsTheLatestRecord) {
  LinuxcncLink link(
      writes({linuxcncRecord(1).dump(), linuxcncRecord(2, {1, 2, 21, 0, 0, 0}).dump()}));
  const LinkSnapshot s = link.waitForRecord(1, 10s);
  ASSERT_TRUE(s.status.has_value()) << s.reason;
  EXPECT_TRUE(s.connected) << s.reason;
  EXPECT_EQ(s.status->sequence, 2);
  EXPECT_EQ(s.status->pose_commanded[2], 21.0);
  EXPECT_EQ(s.records, 2);
  EXPECT_EQ(s.reason, "");
}

TEST(LinuxcncLink, AnErrorAfterRecordsDisconnectsButKeepsTheLastRecord) {
  LinuxcncLink link(writes({linuxcncRecord(1).dump(), R"({"error": "LinuxCNC is not running"})"}));
  (void)link.waitForRecord(0, 10s);
  LinkSnapshot s = link.snapshot();
  for (int i = 0; i < 200 && s.reason.empty(); ++i) {
    std::this_thread::sleep_for(10ms);
    s = link.snapshot();
  }
  EXPECT_FALSE(s.connected);
  EXPECT_EQ(s.reason, "LinuxCNC is not running");
  ASSERT_TRUE(s.status.has_value());
  EXPECT_EQ(s.status->sequence, 1);
}

TEST(LinuxcncLink, RecordsThatStopArrivingMakeItStale) {
  LinkOptions o = writes({linuxcncRecord(1).dump()});
  o.stale_after_s = 0.2;
  LinuxcncLink link(o);
  ASSERT_TRUE(link.waitForRecord(0, 10s).connected);
  std::this_thread::sleep_for(400ms);
  const LinkSnapshot s = link.snapshot();
  EXPECT_FALSE(s.connected);
  EXPECT_THAT(s.reason, HasSubstr("no record from LinuxCNC for"));
  EXPECT_GT(s.age_s, 0.2);
}

TEST(LinuxcncLink, AReaderThatEndsIsReported) {
  LinuxcncLink link(writes({linuxcncRecord(1).dump()}, "exit 0"));
  (void)link.waitForRecord(1, 10s);  // returns when the reader has ended
  EXPECT_FALSE(link.snapshot().connected);
  EXPECT_THAT(link.snapshot().reason, HasSubstr("ended unexpectedly"));
}

TEST(LinuxcncLink, AFatalLineIsTheReason) {
  LinuxcncLink link(
      writes({R"({"fatal": "python3 cannot import the linuxcnc module"})"}, "exit 3"));
  (void)link.waitForRecord(0, 10s);
  EXPECT_FALSE(link.snapshot().connected);
  EXPECT_THAT(link.snapshot().reason, HasSubstr("cannot import the linuxcnc module"));
}

TEST(LinuxcncLink, MalformedLinesAreReasonsNotCrashes) {
  LinuxcncLink link(writes({"Traceback (most recent call last):"}));
  LinkSnapshot s = link.snapshot();
  for (int i = 0; i < 500 && s.reason.find("reader line") == std::string::npos; ++i) {
    std::this_thread::sleep_for(10ms);
    s = link.snapshot();
  }
  EXPECT_FALSE(s.connected);
  EXPECT_THAT(s.reason, HasSubstr("reader line: not a JSON object"));
}

TEST(LinuxcncLink, AReaderThatIgnoresItsEndIsStoppedWithinSeconds) {
  const auto start = std::chrono::steady_clock::now();
  {
    LinuxcncLink link(
        writes({linuxcncRecord(1).dump()}, "trap '' TERM; while :; do sleep 0.05; done"));
    ASSERT_TRUE(link.waitForRecord(0, 10s).connected);
  }
  EXPECT_LT(std::chrono::steady_clock::now() - start, 5s);
}

TEST(LinuxcncLink, AReaderThatCannotStartThrows) {
  LinkOptions o;
  o.command = {"/nonexistent/pkm-reader"};
  EXPECT_THROW(LinuxcncLink{o}, IoError);
}

TEST(LinuxcncLink, OptionsAreChecked) {
  LinkOptions o;
  o.rate_hz = 0.5;
  EXPECT_THROW(o.validate(), InvalidArgument);
  o.rate_hz = 25;
  o.stale_after_s = 0;
  EXPECT_THROW(o.validate(), InvalidArgument);
}

TEST(LinuxcncLink, TheEmbeddedReaderSaysWhyWithoutARunningLinuxcnc) {
  EXPECT_THAT(readerProgram(), HasSubstr("import linuxcnc"));
  LinuxcncLink link;  // /usr/bin/python3 with the reader; the LinuxCNC tests run alone
  LinkSnapshot s = link.snapshot();
  for (int i = 0; i < 1000 && s.reason.rfind("waiting", 0) == 0; ++i) {
    std::this_thread::sleep_for(10ms);
    s = link.snapshot();
  }
  EXPECT_FALSE(s.connected);
  EXPECT_THAT(s.reason, ::testing::AnyOf(HasSubstr("not running"), HasSubstr("linuxcnc module")));
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::live
