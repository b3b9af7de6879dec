// The coordinate chain of the interpreter's state (cnc/modal_state.hpp): LinuxCNC's canon adds
// the G92 offset to a program position, turns X and Y by the active system's rotation, then adds
// the G5x origin and the tool length offset.
#include "pkm/cnc/modal_state.hpp"

#include <cmath>
#include <numbers>

namespace pkm::cnc {

Axes MachineState::toMachine(const Axes& p) const {
  Axes m;
  for (std::size_t i = 0; i < 6; ++i) m[i] = p[i] + g92[i];
  if (rotation != 0.0) {
    const double t = rotation * std::numbers::pi / 180.0;
    const double c = std::cos(t), s = std::sin(t);
    const double x = m[0], y = m[1];
    m[0] = c * x - s * y;
    m[1] = s * x + c * y;
  }
  for (std::size_t i = 0; i < 6; ++i) m[i] += g5x[i] + tool_offset[i];
  return m;
}

Axes MachineState::toProgram(const Axes& m) const {
  Axes p;
  for (std::size_t i = 0; i < 6; ++i) p[i] = m[i] - g5x[i] - tool_offset[i];
  if (rotation != 0.0) {
    const double t = rotation * std::numbers::pi / 180.0;
    const double c = std::cos(t), s = std::sin(t);
    const double x = p[0], y = p[1];
    p[0] = c * x + s * y;
    p[1] = -s * x + c * y;
  }
  for (std::size_t i = 0; i < 6; ++i) p[i] -= g92[i];
  return p;
}

Axes MachineState::target(const Axes& words) const {
  if (rotation == 0.0) {  // per axis, exact: an axis without a word stays where it is
    Axes to = machine;
    for (std::size_t i = 0; i < 6; ++i) {
      if (std::isnan(words[i])) continue;
      to[i] = incremental ? machine[i] + words[i] : words[i] + g5x[i] + g92[i] + tool_offset[i];
    }
    return to;
  }
  Axes p = programPosition();
  for (std::size_t i = 0; i < 6; ++i)
    if (!std::isnan(words[i])) p[i] = incremental ? p[i] + words[i] : words[i];
  return toMachine(p);
}

}  // namespace pkm::cnc
