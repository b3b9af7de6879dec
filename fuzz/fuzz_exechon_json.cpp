// libFuzzer harness for io::parseExechonJson (Exechon and hybrid machine files,
// docs/machine-format.md): any input parses or throws pkm::IoError. A machine that parses is
// written back (io::writeExechonJson) to a file that parses again with the same unit, legs and
// hybrid axes.
#include <string>

#include "fuzz_support.hpp"
#include "pkm/io/exechon_machine.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(pkm::fuzz::asText(data, size));
  pkm::io::ExechonMachine m;
  if (!pkm::fuzz::accepts([&] { m = pkm::io::parseExechonJson(text, "fuzz.json"); })) return 0;
  const std::string written = pkm::io::writeExechonJson(m);
  pkm::io::ExechonMachine back;
  pkm::fuzz::check(pkm::fuzz::accepts([&] { back = pkm::io::parseExechonJson(written, "back"); }),
                   "a machine written back parses");
  pkm::fuzz::check(back.model.unit == m.model.unit, "same unit");
  pkm::fuzz::check(back.hybrid.has_value() == m.hybrid.has_value(), "same hybrid axes");
  for (std::size_t i = 0; i < m.model.legs.size(); ++i)
    pkm::fuzz::check(back.model.legs[i].length_offset == m.model.legs[i].length_offset,
                     "same leg length offsets");
  return 0;
}
