// libFuzzer harness for the calibration input readers (io/calibration_files.hpp,
// io/exechon_tracker_files.hpp): hexapod tracker pose and point files, distance files,
// constrained-motion (dial gauge) files, Exechon and hybrid tracker files, and the metadata vector
// lists they hold. Any input reads or throws pkm::IoError / pkm::InvalidArgument. An input may
// carry a second file after a line "%%next" (added to the same calibration input: files that
// disagree must be refused with an error, not accepted).
#include <string>

#include "fuzz_support.hpp"
#include "pkm/io/calibration_files.hpp"
#include "pkm/io/exechon_tracker_files.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text = pkm::fuzz::asText(data, size);
  const pkm::fuzz::Split parts = pkm::fuzz::splitAt(text, "%%next");
  const pkm::io::NamedText first{"a.csv", parts.first}, second{"b.csv", parts.second};
  pkm::fuzz::accepts([&] {
    pkm::io::CalibrationInput input;
    pkm::io::addCalibrationFile(first, input);
    if (parts.found) pkm::io::addCalibrationFile(second, input);
  });
  pkm::fuzz::accepts([&] {
    pkm::io::ExechonCalibrationInput input;
    pkm::io::addExechonCalibrationFile(first, input);
    if (parts.found) pkm::io::addExechonCalibrationFile(second, input);
  });
  pkm::fuzz::accepts([&] {
    int skipped = 0;
    (void)pkm::io::readConstrainedMotionCsv(first, &skipped);
    pkm::fuzz::check(skipped >= 0, "skipped >= 0");
  });
  pkm::fuzz::accepts([&] {
    for (const auto& v : pkm::io::parseVectorList(std::string(text), "fuzz", "key"))
      pkm::fuzz::check(v.allFinite(), "finite vectors");
  });
  return 0;
}
