// G38.2-G38.5 straight probing (LinuxCNC 2.9 G-code reference, "G38.n Straight Probe") as
// LinuxCNC's standalone rs274 simulates it: the probe never touches; where it leaves the tool
// and the probe parameters were read off rs274 (tests/cnc/corpus/probe_io.ngc).
#include <array>
#include <cmath>

#include "interpreter_impl.hpp"
#include "pkm/cnc/gcode_error.hpp"

namespace pkm::cnc {

namespace {
constexpr double kProbeSamePoint = 1e-9;   // mm: rs274 refuses a probe move to where it is
constexpr double kProbeBackOffMm = 0.254;  // rs274's simulated probe stops 0.01 in short
constexpr int kProbeResult = 5061;         // #5061-#5066: the probe position, X..C
constexpr int kProbeSuccess = 5070;        // #5070: 1 when the probe tripped
}  // namespace

void Interpreter::Impl::probe(const ResolvedBlock& rb, int code, MoveSink& sink) {
  if (st.inverse_time || st.feed <= 0.0) throw GcodeError("cannot probe with zero feed rate");
  const Axes to = st.target(axisWords(rb));
  double length = 0.0;
  for (std::size_t i = 0; i < 6; ++i) length = std::hypot(length, to[i] - st.machine[i]);
  // Only the probes that fail without contact (G38.2, G38.4) refuse a move to where they are.
  if (length < kProbeSamePoint && (code == 382 || code == 384))
    throw GcodeError("start point too close to probe point");
  const Axes from = st.machine;
  emitLine(rb.line, false, to, 0.0, sink);
  // A simulated probe never touches: the probe position (#5061-#5066, program coordinates) is
  // the end, #5070 is 0, and the tool stops 0.254 mm (0.01 in) short of the end along the XYZ
  // direction of the move, where rs274's simulated probe leaves it.
  for (std::size_t i = 0; i < 6; ++i) params.set(kProbeResult + static_cast<int>(i), st.program(i));
  params.set(kProbeSuccess, 0.0);
  const std::array<double, 3> d{to[0] - from[0], to[1] - from[1], to[2] - from[2]};
  const double n = std::hypot(d[0], d[1], d[2]);
  if (n > 0.0)
    for (std::size_t i = 0; i < 3; ++i) st.machine[i] -= kProbeBackOffMm * d[i] / n;
}

}  // namespace pkm::cnc
