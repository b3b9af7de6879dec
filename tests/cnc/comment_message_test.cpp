// Active comments: classification, parameter substitution and their run through the interpreter.
// Expected texts were read off LinuxCNC 2.9's rs274 on the same lines (MESSAGE(...) canonical
// calls, its standard output for PRINT, its error for ABORT).
#include "pkm/cnc/comment_message.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "pkm/cnc/gcode_error.hpp"
#include "pkm/cnc/interpreter.hpp"
#include "pkm/core/error.hpp"

namespace pkm::cnc {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;

class FakeParameters final : public ParameterSource {
 public:
  double numbered(int index) override { return index == 1 ? 2.5 : 0.0; }
  double named(const std::string& name) override { return names.at(name); }
  bool exists(const std::string& name) override { return names.count(name) > 0; }
  std::map<std::string, double> names{{"foo", 3.0}, {"_x", 2.0}};
};

TEST(CommentMessage, ClassifiesAsRs274Does) {
  std::string text;
  EXPECT_EQ(classifyComment(" msg, a", text), CommentKind::kMsg);
  EXPECT_EQ(text, " a");
  EXPECT_EQ(classifyComment("Msg,c", text), CommentKind::kMsg);
  EXPECT_EQ(text, "c");
  EXPECT_EQ(classifyComment("msg , b", text), CommentKind::kNone);  // blank before the comma
  EXPECT_EQ(classifyComment("DEBUG,x=#1", text), CommentKind::kDebug);
  EXPECT_EQ(text, "x=#1");
  EXPECT_EQ(classifyComment("print,p", text), CommentKind::kPrint);
  EXPECT_EQ(classifyComment("ABORT,d", text), CommentKind::kAbort);
  EXPECT_EQ(classifyComment("logopen,/tmp/p.txt", text), CommentKind::kLogOpen);
  EXPECT_EQ(classifyComment("logappend,p.txt", text), CommentKind::kLogAppend);
  EXPECT_EQ(classifyComment("LOGCLOSE", text), CommentKind::kLogClose);
  EXPECT_EQ(classifyComment("log,#1", text), CommentKind::kLog);
  EXPECT_EQ(classifyComment("plain words", text), CommentKind::kNone);
  EXPECT_EQ(classifyComment("message", text), CommentKind::kNone);
  EXPECT_THROW((void)classifyComment("py,print(1)", text), GcodeError);
  EXPECT_EQ(commentKeyword(CommentKind::kDebug), "debug");
  EXPECT_EQ(commentKeyword(CommentKind::kNone), "");
}

TEST(CommentMessage, SubstitutesParametersWithSixDecimals) {
  FakeParameters p;
  EXPECT_EQ(substituteParameters(" one #1 two #<foo> five [#1]", p),
            " one 2.500000 two 3.000000 five [2.500000]");
  EXPECT_EQ(substituteParameters("#1#<_x>", p), "2.5000002.000000");
  EXPECT_EQ(substituteParameters("f #<nope>", p), "f ######");
  EXPECT_EQ(substituteParameters("#<F o o>", p), "3.000000");  // case and blanks dropped
  EXPECT_EQ(substituteParameters("# alone, #99999 and #0", p), "# alone, ###### and ######");
  EXPECT_EQ(substituteParameters("open #<foo", p), "open #<foo");
}

TEST(CommentMessage, TheInterpreterSendsMessagesInOrderAndAborts) {
  const std::string program =
      "#1=2 #<foo>=3\n"
      "(debug, one #1 two #<foo>)\n"
      "(msg, m #1)\n"
      "(debug,x) (plain)\n"
      "#1=5 (debug,a #1)\n"
      "(debug,d) G0 X1 (print,e #1)\n"
      "G0 X2 ; (debug, g)\n"
      "M2\n";
  Interpreter interp;
  MoveCollector c;
  interp.run(Program::parse(program, "m.ngc"), c);
  ASSERT_EQ(c.messages.size(), 4u);
  EXPECT_EQ(c.messages[0].text, " one 2.000000 two 3.000000");
  EXPECT_EQ(c.messages[0].line, 2u);
  EXPECT_EQ(c.messages[1].text, " m #1");              // MSG is not substituted
  EXPECT_EQ(c.messages[2].text, "a 5.000000");         // after the line's own setting
  EXPECT_EQ(c.messages[3].kind, CommentKind::kPrint);  // the last comment of the line
  EXPECT_EQ(c.messages[3].text, "e 5.000000");
  EXPECT_EQ(c.moves.size(), 2u);

  Interpreter aborting;
  MoveCollector none;
  try {
    aborting.run(Program::parse("#1=2.5\nG0 X1\n(abort, stop #1 now)\nG0 X2\nM2\n", "a.ngc"), none);
    FAIL() << "no error";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("a.ngc:3: program aborted: stop 2.500000 now"));
  }
  EXPECT_EQ(none.moves.size(), 1u);
}

TEST(CommentMessage, EmbeddedPythonIsRefusedNamingTheLine) {
  for (const char* line : {";py,print(1)", "(py,x=1)", "G0 X1 ; py, x"}) {
    try {
      (void)Program::parse(std::string("G0 X0\n") + line + "\nM2\n", "p.ngc");
      FAIL() << line;
    } catch (const IoError& e) {
      EXPECT_THAT(e.what(), HasSubstr("p.ngc:2: embedded Python"));
    }
  }
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::cnc
