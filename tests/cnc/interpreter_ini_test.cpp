// The interpreter settings of a LinuxCNC INI and its parameter file, and their effect on a run.
#include "pkm/cnc/interpreter_ini.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "pkm/cnc/interpreter.hpp"
#include "pkm/core/error.hpp"

namespace pkm::cnc {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;

constexpr const char* kIni =
    "[EMC]\n"
    "MACHINE = test\n"
    "[TRAJ]\n"
    "LINEAR_UNITS = mm\n"
    "; a comment\n"
    "[RS274NGC]\n"
    "PARAMETER_FILE = sim.var\n"
    "RS274NGC_STARTUP_CODE = G17 G21 G90 G55\n"
    "SUBROUTINE_PATH = subs:/abs/lib\n"
    "CENTER_ARC_RADIUS_TOLERANCE_MM = 0.002\n"
    "[SETUP]\n"
    "XPOS = 3.145\n"
    "YPOS = 2.718\n"
    "name = 7\n"
    "TEXT = hello\n";

TEST(InterpreterIni, ReadsTheRs274ngcSection) {
  const Rs274ngcIni r = readRs274ngcIni(kIni, "/cfg/machine.ini");
  EXPECT_EQ(r.startup_code, "G17 G21 G90 G55");
  EXPECT_EQ(r.startup_source, "/cfg/machine.ini:8");
  EXPECT_EQ(r.parameter_file, "/cfg/sim.var");
  ASSERT_EQ(r.subroutine_path.size(), 2u);
  EXPECT_EQ(r.subroutine_path[0], "/cfg/subs");
  EXPECT_EQ(r.subroutine_path[1], "/abs/lib");
  EXPECT_DOUBLE_EQ(r.arc.centre_mm, 0.002);
  EXPECT_DOUBLE_EQ(r.values.at("setup]xpos"), 3.145);
  EXPECT_EQ(r.values.count("setup]name"), 0u);  // LinuxCNC upper-cases the name it looks up
  EXPECT_EQ(r.values.count("setup]text"), 0u);  // not a number
  EXPECT_FALSE(r.inch_machine);
}

TEST(InterpreterIni, RefusesWhatItCannotHonour) {
  const Rs274ngcIni remap =
      readRs274ngcIni("[RS274NGC]\nREMAP=M6 modalgroup=6 ngc=change\n", "m.ini");
  ASSERT_EQ(remap.remapped.count("m6"), 1u);
  InterpreterOptions o;
  o.remapped_codes = remap.remapped;
  MoveCollector c;
  EXPECT_THAT(
      [&] { Interpreter(o).run(Program::parse("G0 X1\nT1 M6\nM2\n", "r.ngc"), c); },
      ::testing::ThrowsMessage<IoError>(HasSubstr("r.ngc:2: M6 is remapped by the INI (m.ini:2)")));
  EXPECT_THAT(
      [] { (void)readRs274ngcIni("[RS274NGC]\nCENTER_ARC_RADIUS_TOLERANCE_MM = 0.5\n", "m.ini"); },
      ::testing::ThrowsMessage<IoError>(HasSubstr("m.ini:2: CENTER_ARC_RADIUS_TOLERANCE_MM")));
  EXPECT_THAT([] { (void)readRs274ngcIni("[RS274NGC\n", "m.ini"); },
              ::testing::ThrowsMessage<IoError>(HasSubstr("m.ini:1: unterminated section")));
  const Rs274ngcIni off = readRs274ngcIni("[RS274NGC]\nINI_VARS = 0\n[A]\nB = 1\n", "m.ini");
  EXPECT_TRUE(off.values.empty());
}

TEST(InterpreterIni, ParameterFileSetsOffsetsAtStartUp) {
  InterpreterOptions o;
  readParameterFile("5220 2\n5241 10.5\n5242 -4\n\n5211 1\n5210 1\n31 7\n", "sim.var", false, o);
  EXPECT_DOUBLE_EQ(o.initial_parameters.at(5241), 10.5);
  Interpreter interp(o);
  EXPECT_EQ(interp.state().coordinate_system, 2);  // #5220: G55
  EXPECT_DOUBLE_EQ(interp.state().g5x[0], 10.5);
  EXPECT_DOUBLE_EQ(interp.state().g92[0], 1.0);  // #5210 = 1: the G92 offset applies
  MoveCollector c;
  interp.run(Program::parse("G0 X#31\nM2\n", "p.ngc"), c);
  ASSERT_EQ(c.moves.size(), 1u);
  EXPECT_DOUBLE_EQ(c.moves[0].end[0], 7.0 + 10.5 + 1.0);

  InterpreterOptions inch;
  readParameterFile("5241 1\n", "sim.var", true, inch);
  EXPECT_DOUBLE_EQ(inch.initial_parameters.at(5241), 25.4);
  EXPECT_THAT([&] { readParameterFile("5241\n", "bad.var", false, inch); },
              ::testing::ThrowsMessage<IoError>(HasSubstr("bad.var:1: expected 'NUMBER VALUE'")));
  EXPECT_THAT([&] { readParameterFile("1\n9999 1\n", "bad.var", false, inch); },
              ::testing::ThrowsMessage<IoError>(HasSubstr("bad.var:1")));
  EXPECT_THAT([&] { readParameterFile("9999 1\n", "bad.var", false, inch); },
              ::testing::ThrowsMessage<IoError>(HasSubstr("bad.var:1: parameter number 9999")));
}

TEST(InterpreterIni, IniValuesAreReadOnlyParameters) {
  InterpreterOptions o;
  o.ini_values = readRs274ngcIni(kIni, "m.ini").values;
  o.require_program_end = true;
  Interpreter interp(o);
  MoveCollector c;
  interp.run(Program::parse("G0 X#<_ini[setup]xpos> Y#<_InI[SeTuP]ypos>\n"
                            "(debug, #<_ini[setup]xpos> #<_ini[nosuch]x>)\n"
                            "G0 Z[EXISTS[#<_ini[setup]xpos>] + EXISTS[#<_ini[setup]nope>]]\nM2\n",
                            "i.ngc"),
             c);
  ASSERT_EQ(c.moves.size(), 2u);
  EXPECT_DOUBLE_EQ(c.moves[0].end[0], 3.145);
  EXPECT_DOUBLE_EQ(c.moves[0].end[1], 2.718);
  EXPECT_DOUBLE_EQ(c.moves[1].end[2], 1.0);
  ASSERT_EQ(c.messages.size(), 1u);
  EXPECT_EQ(c.messages[0].text, " 3.145000 ######");
  Interpreter again(o);
  EXPECT_THAT([&] { again.run(Program::parse("#<_ini[setup]xpos> = 1\nM2\n", "w.ngc"), c); },
              ::testing::ThrowsMessage<IoError>(HasSubstr("w.ngc:1: cannot assign to read-only")));
  EXPECT_THAT([&] { again.run(Program::parse("G0 X#<_ini[setup]nope>\nM2\n", "u.ngc"), c); },
              ::testing::ThrowsMessage<IoError>(HasSubstr("u.ngc:1: named parameter")));
}

TEST(InterpreterIni, SubFilesComeFromTheSubroutinePath) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "pkm_sub_files_test";
  fs::create_directories(dir);
  std::ofstream(dir / "corner.ngc") << "o<corner> sub\nG0 X#1 Y#2\no<inner> call [#1]\n"
                                       "o<corner> endsub [#1 + #2]\nM2\n";
  std::ofstream(dir / "inner.ngc") << "(the sub of a sub file, also from the path)\n"
                                      "o<inner> sub\nG0 Z#1\no<inner> endsub\n";
  std::ofstream(dir / "broken.ngc") << "o<broken> sub\nG1 X1 F0\no<broken> endsub\n";
  InterpreterOptions o;
  o.subroutine_path = {dir.string()};
  o.search_working_folder = false;
  o.require_program_end = true;
  MoveCollector c;
  Interpreter(o).run(
      Program::parse("o<corner> call [3] [4]\nG0 X#<_value>\n#1 = 7\nG0 Y#1\nM2\n", "m.ngc"), c);
  ASSERT_EQ(c.moves.size(), 4u);
  EXPECT_DOUBLE_EQ(c.moves[0].end[0], 3.0);
  EXPECT_DOUBLE_EQ(c.moves[1].end[2], 3.0);  // o<inner> from inner.ngc
  EXPECT_DOUBLE_EQ(c.moves[2].end[0], 7.0);  // the value endsub returned
  EXPECT_DOUBLE_EQ(c.moves[3].end[1], 7.0);  // #1 of the main program untouched by the call
  EXPECT_THAT([&] { Interpreter(o).run(Program::parse("o<nope> call\nM2\n", "m.ngc"), c); },
              ::testing::ThrowsMessage<IoError>(HasSubstr("m.ngc:1: call to undefined")));
  EXPECT_THAT([&] { Interpreter(o).run(Program::parse("o<broken> call\nM2\n", "m.ngc"), c); },
              ::testing::ThrowsMessage<IoError>(HasSubstr("broken.ngc:2: cannot do G1")));
  fs::remove_all(dir);
}

TEST(InterpreterIni, ProgramEndIsRequiredWhenAsked) {
  InterpreterOptions o;
  o.require_program_end = true;
  MoveCollector c;
  EXPECT_THAT([&] { Interpreter(o).run(Program::parse("G0 X1\nG0 X2\n", "e.ngc"), c); },
              ::testing::ThrowsMessage<IoError>(HasSubstr("e.ngc:2: the file ended with no")));
  EXPECT_NO_THROW(Interpreter(o).run(Program::parse("%\nG0 X1\n%\n", "p.ngc"), c));
  EXPECT_NO_THROW(Interpreter(o).run(Program::parse("G0 X1\nM30\n", "m.ngc"), c));
  o.require_program_end = false;
  EXPECT_NO_THROW(Interpreter(o).run(Program::parse("G0 X1\n", "s.ngc"), c));
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::cnc
