// cnc::ProgramFile: a regular file mapped, anything else read, the error of a missing file.
#include "pkm/cnc/program_file.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <utility>

#include "pkm/cnc/program.hpp"
#include "pkm/core/error.hpp"
#include "support/scratch_files.hpp"

namespace pkm::cnc {
namespace PKM_TEST_NS {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) { return test::scratchPath("cnc_program_file", name); }

TEST(ProgramFile, HoldsTheWholeTextOfARegularFile) {
  const fs::path p = scratch("part.ngc");
  std::string text;
  for (int k = 0; k < 5000; ++k)
    text += "N" + std::to_string(10 * k) + " G1 X" + std::to_string(k) + "\n";
  std::ofstream(p, std::ios::binary) << text;
  const ProgramFile file(p.string());
  EXPECT_EQ(file.text(), text);
  EXPECT_EQ(file.text(), Program::readFile(p.string()));
}

TEST(ProgramFile, StaysValidWhenMoved) {
  const fs::path p = scratch("moved.ngc");
  std::ofstream(p, std::ios::binary) << "G0 X1\nM2\n";
  ProgramFile a(p.string());
  ProgramFile b(std::move(a));
  EXPECT_EQ(b.text(), "G0 X1\nM2\n");
  const fs::path q = scratch("other.ngc");
  std::ofstream(q, std::ios::binary) << "G0 X2\n";
  ProgramFile c(q.string());
  c = std::move(b);
  EXPECT_EQ(c.text(), "G0 X1\nM2\n");
}

TEST(ProgramFile, EmptyFilesAndDevicesAreRead) {
  const fs::path p = scratch("empty.ngc");
  std::ofstream(p, std::ios::binary).close();
  EXPECT_TRUE(ProgramFile(p.string()).text().empty());
  EXPECT_TRUE(ProgramFile("/dev/null").text().empty());
}

TEST(ProgramFile, AMissingFileIsAnIoErrorNamingIt) {
  const std::string p = scratch("missing.ngc").string();
  try {
    (void)ProgramFile(p);
    FAIL() << "no error";
  } catch (const IoError& e) {
    EXPECT_EQ(std::string(e.what()), p + ": cannot open G-code file");
  }
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::cnc
