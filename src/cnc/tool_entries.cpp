// G10 L1, L10 and L11: the tool table entries a program sets (LinuxCNC 2.9 G-code reference,
// "G10 L1 Set Tool Table", "G10 L10 Set Tool Table", "G10 L11 Set Tool Table"); which axes move
// under a rotated system was read off rs274 (LinuxCNC's tests/interp/g10).
#include <fmt/format.h>

#include <cmath>

#include "interpreter_impl.hpp"
#include "pkm/cnc/gcode_error.hpp"

namespace pkm::cnc {

namespace {
constexpr int kFixtureSystem = 9;  // G59.3: the touch-off fixture of G10 L11
}  // namespace

void Interpreter::Impl::doG10Tool(const ResolvedBlock& rb, int l) {
  const int tool = toInt(rb.word('p'), 'P');
  if (tool < 1) throw GcodeError(fmt::format("G10 L{} P{}: P must be a tool number >= 1", l, tool));
  const auto it = options.tools.tools.find(tool);
  if (it == options.tools.tools.end()) {
    missing_tool = true;
    throw GcodeError(fmt::format("G10 L{}: tool {} is not in the tool table", l, tool));
  }
  ToolEntry& entry = it->second;
  if (rb.hasWord('r')) entry.diameter = 2.0 * rb.word('r') * st.scale();
  const Axes words = axisWords(rb);
  if (l == 1) {
    for (std::size_t i = 0; i < 6; ++i)
      if (!std::isnan(words[i])) entry.offset[i] = words[i];
    return;
  }
  // L10: the entry that gives the current point the given coordinates once G43 applies it; L11
  // the same in the fixture's system G59.3 without G92. Axes without a word keep the program
  // coordinate they have with the tool's present entry (so, unrotated, their entry).
  MachineState s = st;
  if (l == 11) {
    const int base = coordinateSystemBase(kFixtureSystem);
    for (std::size_t i = 0; i < 6; ++i) s.g5x[i] = params.get(base + static_cast<int>(i));
    s.rotation = params.get(base + kRotationIndex);
    s.g92 = {};
  }
  s.tool_offset = entry.offset;
  Axes v = s.programPosition();
  for (std::size_t i = 0; i < 6; ++i)
    if (!std::isnan(words[i])) v[i] = words[i];
  s.tool_offset = {};
  const Axes without_tool = s.toMachine(v);
  for (std::size_t i = 0; i < 6; ++i) entry.offset[i] = st.machine[i] - without_tool[i];
}

}  // namespace pkm::cnc
