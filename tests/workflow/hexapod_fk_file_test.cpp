// workflow::solveHexapodFkFile: the rows of a file of readings solved in order and written in
// order (the same poses as the IK they came from), a bad line raised after the rows before it, a
// failing writer ending the run with its exception instead of a hang.
#include "pkm/workflow/hexapod_fk_file.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "pkm/core/error.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"
#include "support/scratch_files.hpp"

namespace pkm::workflow {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;

/// A pose read back from text with 17 significant digits: agreement of FK with the IK, mm.
constexpr double kTolRoundTrip = 1e-6;

/// Readings of `n` poses along a small circle at z 200 on `machine`, as a CSV file.
std::string readingsFile(const io::HexapodMachine& machine, int n, const std::string& tail = "") {
  kinematics::HexapodData data(machine.model);
  std::ostringstream s;
  s << "l0,l1,l2,l3,l4,l5\n";
  s.precision(17);
  for (int k = 0; k < n; ++k) {
    kinematics::PoseRpy p;
    p.position = {10.0 * std::cos(0.01 * k), 10.0 * std::sin(0.01 * k), 200.0};
    const kinematics::StrutVector q = kinematics::inverseKinematics(machine.model, data, p);
    for (int i = 0; i < 6; ++i) s << q[i] << (i < 5 ? "," : "\n");
  }
  const std::string path = test::scratchPath("workflow_hexapod_fk_file", "readings.csv").string();
  std::ofstream(path) << s.str() << tail;
  return path;
}

TEST(HexapodFkFile, RowsAreSolvedAndWrittenInOrder) {
  const io::HexapodMachine machine = io::loadHexapodMachine("hexapod-default");
  HexapodFkFileRequest r;
  r.lengths = readingsFile(machine, 3000);  // several chunks and pieces
  std::string out;
  const HexapodFkFileSummary s =
      solveHexapodFkFile(machine, r, [&out](std::string_view t) { out += t; });
  EXPECT_EQ(s.rows, 3000u);
  EXPECT_EQ(s.failed, 0u);
  std::istringstream lines(out);
  std::string line;
  std::getline(lines, line);
  EXPECT_EQ(line + "\n", kHexapodFkHeader);
  for (int k = 0; std::getline(lines, line); ++k) {
    double x = 0.0, y = 0.0;
    ASSERT_EQ(std::sscanf(line.c_str(), "%lf,%lf", &x, &y), 2) << line;
    EXPECT_NEAR(x, 10.0 * std::cos(0.01 * k), kTolRoundTrip) << k;
    EXPECT_NEAR(y, 10.0 * std::sin(0.01 * k), kTolRoundTrip) << k;
  }
}

TEST(HexapodFkFile, ABadLineIsRaisedAfterTheRowsBeforeIt) {
  const io::HexapodMachine machine = io::loadHexapodMachine("hexapod-default");
  HexapodFkFileRequest r;
  r.lengths = readingsFile(machine, 5, "1,2,3\n");
  std::string out;
  try {
    (void)solveHexapodFkFile(machine, r, [&out](std::string_view t) { out += t; });
    FAIL() << "a short line was accepted";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("readings.csv:7"));
  }
  EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 6);  // the header and five rows
}

TEST(HexapodFkFile, AFailingWriterEndsTheRun) {
  const io::HexapodMachine machine = io::loadHexapodMachine("hexapod-default");
  HexapodFkFileRequest r;
  r.lengths = readingsFile(machine, 40000);
  int calls = 0;
  EXPECT_THROW((void)solveHexapodFkFile(machine,
                                        r,
                                        [&calls](std::string_view) {
                                          if (++calls == 3) throw std::runtime_error("disk full");
                                        }),
               std::runtime_error);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::workflow
