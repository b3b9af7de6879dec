// libFuzzer harness for the readers of `pkm analyze` as the workflows run them, analysis included
// (workflow/analyze_positioning.hpp, analyze_diagonals.hpp, analyze_circle.hpp; docs/analysis.md):
// ISO 230-2, straightness, parallelism, face-diagonal squareness, body, step and shifted
// diagonals, circle, circular test and probe offset. The input is one measurement file, or two
// separated by a line "%%next" (parallelism: reference and axis; circular: CW and CCW; the
// others: both files). Any input analyses or throws pkm::IoError / pkm::InvalidArgument.
#include <string>
#include <vector>

#include "fuzz_support.hpp"
#include "pkm/workflow/analyze_circle.hpp"
#include "pkm/workflow/analyze_diagonals.hpp"
#include "pkm/workflow/analyze_positioning.hpp"

namespace wf = pkm::workflow;

namespace {

using Files = std::vector<pkm::io::NamedText>;

/// ISO 230-2, straightness, parallelism (with a second file) and squareness.
void analyseLines(const Files& all, bool two) {
  pkm::fuzz::accepts([&] {
    wf::Iso230_2Request r;
    r.data = all;
    (void)wf::analyzeIso230_2(r);
  });
  pkm::fuzz::accepts([&] {
    wf::StraightnessRequest r;
    r.data = all;
    r.reference = pkm::metrology::StraightnessReference::kMinimumZone;
    (void)wf::analyzeStraightness(r);
  });
  if (two) {
    pkm::fuzz::accepts([&] {
      wf::ParallelismRequest r;
      r.reference = {all.front()};
      r.axis = {all.back()};
      r.szX2 = 1e-5;
      (void)wf::analyzeParallelism(r);
    });
  }
  pkm::fuzz::accepts([&] {
    wf::SquarenessRequest r;
    r.data = all;
    r.fit_scale = two;
    (void)wf::analyzeSquareness(r);
  });
}

/// Body, step and shifted diagonals (step and shifted compared with a second file).
void analyseDiagonals(const Files& all, bool two) {
  for (const auto method : {pkm::io::DiagonalMethod::kBody,
                            pkm::io::DiagonalMethod::kStep,
                            pkm::io::DiagonalMethod::kShifted}) {
    pkm::fuzz::accepts([&] {
      wf::DiagonalsRequest r;
      r.data = {all.front()};
      if (two && method != pkm::io::DiagonalMethod::kBody) r.compare = {all.back()};
      r.method = method;
      r.size = {400.0, 300.0, 200.0};
      (void)wf::analyzeDiagonals(r);
    });
  }
}

/// Circle, circular test and probe offset.
void analyseCircles(const Files& all) {
  pkm::fuzz::accepts([&] {
    wf::CircleRequest r;
    r.data = all;
    (void)wf::analyzeCircle(r);
  });
  pkm::fuzz::accepts([&] {
    wf::CircularRequest r;
    r.data = all;
    r.nominal_radius = 50.0;
    (void)wf::analyzeCircular(r);
  });
  pkm::fuzz::accepts([&] {
    wf::ProbeOffsetRequest r;
    r.data = all;
    r.ring_diameter = 50.0;
    (void)wf::analyzeProbeOffset(r);
  });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const pkm::fuzz::Split parts = pkm::fuzz::splitAt(pkm::fuzz::asText(data, size), "%%next");
  Files all{{"a.csv", parts.first}};
  if (parts.found) all.push_back({"b.csv", parts.second});
  analyseLines(all, parts.found);
  analyseDiagonals(all, parts.found);
  analyseCircles(all);
  return 0;
}
