// io::describeHexapodMachine on a built-in machine: the header lines, one row per strut and the
// checks at home.
#include "pkm/io/machine_description.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sstream>

#include "pkm/io/machine_loader.hpp"

namespace pkm::io {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;
using ::testing::StartsWith;

TEST(MachineDescription, DescribesTheDefaultHexapod) {
  const HexapodMachine m = loadHexapodMachine("hexapod-default");
  const std::string text = describeHexapodMachine(m);
  EXPECT_THAT(text, StartsWith("machine      " + m.model.name + " (builtin:hexapod-default)\n"));
  EXPECT_THAT(text, HasSubstr("units        mm (angles in degrees)\n"));
  EXPECT_THAT(text, HasSubstr("at home      status ok, condition number"));
  std::istringstream lines(text);
  std::string line;
  int struts = 0;
  while (std::getline(lines, line))
    if (line.size() > 5 && line.find_first_not_of(' ') == 4 && std::isdigit(line[4]) != 0) ++struts;
  EXPECT_EQ(struts, 6);
  EXPECT_EQ(text.back(), '\n');
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::io
