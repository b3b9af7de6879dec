// libFuzzer harness for io::parseGeometricErrorsJson (the geometric errors of a hybrid machine,
// docs/formats.md "Geometric errors"): any input parses or throws pkm::IoError; no allocation
// beyond what the text holds. Errors that parse are written back (io::writeGeometricErrorsJson)
// to a file that parses again with the same tables' positions and grid axes.
#include <string>

#include "fuzz_support.hpp"
#include "pkm/io/geometric_errors.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(pkm::fuzz::asText(data, size));
  pkm::kinematics::GeometricErrors e;
  if (!pkm::fuzz::accepts([&] { e = pkm::io::parseGeometricErrorsJson(text, "fuzz.json"); }))
    return 0;
  const std::string written = pkm::io::writeGeometricErrorsJson(e);
  pkm::kinematics::GeometricErrors back;
  pkm::fuzz::check(
      pkm::fuzz::accepts([&] { back = pkm::io::parseGeometricErrorsJson(written, "back"); }),
      "errors written back parse");
  pkm::fuzz::check(back.unit == e.unit, "same unit");
  pkm::fuzz::check(back.x2.has_value() == e.x2.has_value() &&
                       back.y2.has_value() == e.y2.has_value() &&
                       back.pkm.has_value() == e.pkm.has_value(),
                   "same tables");
  if (e.x2) pkm::fuzz::check(back.x2->positions() == e.x2->positions(), "same X2 positions");
  if (e.y2) pkm::fuzz::check(back.y2->positions() == e.y2->positions(), "same Y2 positions");
  if (e.pkm)
    for (int a = 0; a < 3; ++a)
      pkm::fuzz::check(back.pkm->axis(a) == e.pkm->axis(a), "same grid axes");
  return 0;
}
