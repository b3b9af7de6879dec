// libFuzzer harness for the controller compensation-table readers (docs/compensation.md):
// LinuxCNC COMP_FILE of types 0 and 1 (compensation::parseLinuxcncComp) and SINUMERIK EEC and
// CEC part programs (parseSiemensEec, parseSiemensCec). Any input parses or throws pkm::IoError /
// pkm::InvalidArgument. A table that parses is valid, is written back (writeLinuxcncComp,
// writeSiemensEec, writeSiemensCec) to a text that parses again (LinuxCNC: to the same numbers),
// and can be applied at its ends.
#include <cmath>
#include <string>

#include "fuzz_support.hpp"
#include "pkm/compensation/linuxcnc_comp.hpp"
#include "pkm/compensation/siemens_comp.hpp"

namespace comp = pkm::compensation;

namespace {

/// Halfway between a and b, without overflow.
double middle(double a, double b) { return 0.5 * a + 0.5 * b; }

void linuxcnc(const std::string& text, int type) {
  comp::LinuxcncCompFile f;
  if (!pkm::fuzz::accepts([&] { f = comp::parseLinuxcncComp(text, "fuzz.comp", type); })) return;
  pkm::fuzz::check(pkm::fuzz::accepts([&] { f.validate(); }), "a file that parses is valid");
  const comp::LinuxcncCompFile back =
      comp::parseLinuxcncComp(comp::writeLinuxcncComp(f), "b", type);
  pkm::fuzz::check(
      back.nominal == f.nominal && back.forward == f.forward && back.reverse == f.reverse,
      "a file written back parses to the same numbers");
  for (const int direction : {1, -1})
    for (const double x : {f.nominal.front(), middle(f.nominal.front(), f.nominal.back())})
      (void)comp::applyLinuxcncComp(f, x, direction);
}

/// A SINUMERIK EEC or CEC table: one that parses is valid, is written to a text that parses
/// again, and has finite values at its ends and middle.
template <typename Table, typename Parse, typename Write>
void siemens(const std::string& text, Parse parse, Write write) {
  Table t;
  if (!pkm::fuzz::accepts([&] { t = parse(text, "fuzz.spf"); })) return;
  pkm::fuzz::check(pkm::fuzz::accepts([&] { t.validate(); }),
                   "a Siemens table that parses is valid");
  std::string written;
  pkm::fuzz::check(pkm::fuzz::accepts([&] { written = write(t); }),
                   "a Siemens table that parses is written");
  pkm::fuzz::check(pkm::fuzz::accepts([&] { (void)parse(written, "back"); }),
                   "a Siemens table written back parses");
  for (const double x : {t.min, middle(t.min, t.max), t.max})
    pkm::fuzz::check(std::isfinite(t.valueAt(x)), "finite Siemens table values");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(pkm::fuzz::asText(data, size));
  linuxcnc(text, 0);
  linuxcnc(text, 1);
  siemens<comp::SiemensEecTable>(
      text,
      [](const std::string& t, const std::string& n) { return comp::parseSiemensEec(t, n); },
      [](const comp::SiemensEecTable& t) { return comp::writeSiemensEec(t); });
  siemens<comp::SiemensCecTable>(
      text,
      [](const std::string& t, const std::string& n) { return comp::parseSiemensCec(t, n); },
      [](const comp::SiemensCecTable& t) { return comp::writeSiemensCec(t); });
  return 0;
}
