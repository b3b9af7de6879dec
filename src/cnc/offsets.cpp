// Parameters that mirror the machine state (#5220, #5400-#5406, #5420-#5425, lengths in program
// units) and the offset codes: coordinate-system selection, G10 L2/L20, G92 family, tool length
// offsets G43/G43.1/G49 (LinuxCNC 2.9 G-code reference "G10 L2", "G10 L20", "G92", "G43").
#include <fmt/format.h>

#include <cmath>

#include "interpreter_impl.hpp"
#include "pkm/cnc/gcode_error.hpp"
#include "pkm/core/error.hpp"

namespace pkm::cnc {

double Interpreter::Impl::numbered(int index) {
  if (index >= 5420 && index <= 5425) {
    const auto i = static_cast<std::size_t>(index - 5420);
    return st.program(i) / st.axisScale(i);
  }
  if (index >= 5426 && index <= 5428) return 0.0;
  if (index == 5400) return st.tool_in_spindle;
  if (index >= 5401 && index <= 5406) {  // the table entry of the tool in the spindle (rs274)
    const auto i = static_cast<std::size_t>(index - 5401);
    // A tool not in the table (T0) leaves the last entry read, as rs274 does.
    if (const ToolEntry* t = options.tools.find(st.tool_in_spindle)) spindle_entry = t->offset;
    return spindle_entry[i] / st.axisScale(i);
  }
  const double v = params.get(index);
  return isLengthParameter(index) ? v / st.scale() : v;
}

void Interpreter::Impl::setNumbered(int index, double value) {
  if (index < 1 || index >= kParameterCount)
    throw GcodeError(fmt::format("parameter number {} out of range (1..5601)", index));
  // The machine's state (#5161 and above: homes, offsets, the tool) changes only through G10,
  // G92, G28.1...: a program that wrote it directly could not be flattened or rewritten line by
  // line. #5599, the (DEBUG, ...) switch, is no state of the machine.
  if (index >= 5161 && index != kDebugFlagParam)
    throw GcodeError(fmt::format("parameter #{} is read-only here (use G10, G92)", index));
  params.set(index, isLengthParameter(index) ? value * st.scale() : value);
}

void Interpreter::Impl::loadParameters() {
  if (options.initial_parameters.empty()) return;
  for (const auto& [n, v] : options.initial_parameters) {
    if (n < 1 || n >= kParameterCount)
      throw IoError(fmt::format("parameter number {} outside 1..5601", n));
    params.set(n, v);
  }
  const double system = params.get(kActiveSystemParam);
  selectSystem(system >= 1.0 && system <= 9.0 ? static_cast<int>(system) : 1);
  if (params.get(kG92Base - 1) == 1.0)
    for (std::size_t i = 0; i < 6; ++i) st.g92[i] = params.get(kG92Base + static_cast<int>(i));
}

void Interpreter::Impl::selectSystem(int n) {
  st.coordinate_system = n;
  params.set(kActiveSystemParam, n);
  const int base = coordinateSystemBase(n);
  for (std::size_t i = 0; i < 6; ++i) st.g5x[i] = params.get(base + static_cast<int>(i));
  st.rotation = params.get(base + kRotationIndex);
}

void Interpreter::Impl::setTlo(const ResolvedBlock& rb, int code) {
  st.tool_length_mode = code;
  if (code == 490) {
    st.tool_offset = {};
    return;
  }
  if (code == 431) {
    st.tool_offset = {};
    static constexpr std::array<char, 6> kAxes{'x', 'y', 'z', 'a', 'b', 'c'};
    for (std::size_t i = 0; i < 6; ++i)
      if (rb.hasWord(kAxes[i])) st.tool_offset[i] = rb.word(kAxes[i]) * st.axisScale(i);
    return;
  }
  int h = rb.hasWord('h') ? toInt(rb.word('h'), 'H') : st.tool_in_spindle;
  if (h < 0) throw GcodeError("negative H word");
  if (h == 0) h = st.tool_in_spindle;  // LinuxCNC: H0 is the spindle's entry (checked with rs274)
  if (h == 0) {
    st.tool_offset = {};
    return;
  }
  const ToolEntry* t = options.tools.find(h);
  if (t == nullptr) {
    missing_tool = true;
    throw GcodeError(fmt::format("tool {} (G43 H{}) is not in the tool table", h, h));
  }
  st.tool_offset = t->offset;
}

void Interpreter::Impl::doG10(const ResolvedBlock& rb) {
  if (!rb.hasWord('l')) throw GcodeError("G10 needs an L word");
  if (!rb.hasWord('p')) throw GcodeError("G10 needs a P word");
  const int l = toInt(rb.word('l'), 'L');
  if (l == 1 || l == 10 || l == 11) {
    doG10Tool(rb, l);
    return;
  }
  if (l != 2 && l != 20)
    throw GcodeError(fmt::format("G10 L{} is not supported (L1, L2, L10, L11, L20)", l));
  int p = toInt(rb.word('p'), 'P');
  if (p < 0 || p > 9) throw GcodeError(fmt::format("G10 P{} out of range (0..9)", p));
  if (p == 0) p = st.coordinate_system;
  const int base = coordinateSystemBase(p);
  if (rb.hasWord('r')) params.set(base + kRotationIndex, rb.word('r'));
  const double rotation = params.get(base + kRotationIndex);
  const Axes words = axisWords(rb);
  if (l == 20 && rotation != 0.0) {
    // The current point gets the given coordinates in system p, turned by p's rotation: its
    // origin moves along the turned axes (the other axes keep their program coordinates).
    MachineState in_p = st;
    for (std::size_t i = 0; i < 6; ++i) in_p.g5x[i] = params.get(base + static_cast<int>(i));
    in_p.rotation = rotation;
    Axes v = in_p.programPosition();
    for (std::size_t i = 0; i < 6; ++i)
      if (!std::isnan(words[i])) v[i] = words[i];
    in_p.g5x = {};
    const Axes without_origin = in_p.toMachine(v);  // R·(v + G92) + tool offset
    for (std::size_t i = 0; i < 6; ++i)
      params.set(base + static_cast<int>(i), st.machine[i] - without_origin[i]);
  } else {
    for (std::size_t i = 0; i < 6; ++i) {
      if (std::isnan(words[i])) continue;
      // L20: the current point gets coordinate v; LinuxCNC computes the new origin from the
      // program position and the *active* origin, without the G92 offset (checked with rs274).
      const double origin = l == 2 ? words[i] : st.program(i) + st.g5x[i] - words[i];
      params.set(base + static_cast<int>(i), origin);
    }
  }
  if (p == st.coordinate_system) selectSystem(p);
}

void Interpreter::Impl::doG92(const ResolvedBlock& rb, int code) {
  static constexpr std::array<char, 6> kAxes{'x', 'y', 'z', 'a', 'b', 'c'};
  switch (code) {
    case 920: {
      // The current point gets the given program coordinates: G92 = R⁻¹(machine − G5x − tool)
      // − v on each given axis.
      MachineState no_g92 = st;
      no_g92.g92 = {};
      const Axes p = no_g92.programPosition();
      for (std::size_t i = 0; i < 6; ++i) {
        if (!rb.hasWord(kAxes[i])) continue;
        st.g92[i] = p[i] - rb.word(kAxes[i]) * st.axisScale(i);
      }
      for (std::size_t i = 0; i < 6; ++i) params.set(kG92Base + static_cast<int>(i), st.g92[i]);
      params.set(kG92Base - 1, 1.0);
      break;
    }
    case 520:  // G52: a local offset in the G92 registers, set to the words themselves
      for (std::size_t i = 0; i < 6; ++i)
        if (rb.hasWord(kAxes[i])) st.g92[i] = rb.word(kAxes[i]) * st.axisScale(i);
      for (std::size_t i = 0; i < 6; ++i) params.set(kG92Base + static_cast<int>(i), st.g92[i]);
      params.set(kG92Base - 1, 1.0);
      break;
    case 921:
      st.g92 = {};
      for (int i = 0; i < 9; ++i) params.set(kG92Base + i, 0.0);
      params.set(kG92Base - 1, 0.0);
      break;
    case 922:
      st.g92 = {};
      params.set(kG92Base - 1, 0.0);
      break;
    case 923:
      for (std::size_t i = 0; i < 6; ++i) st.g92[i] = params.get(kG92Base + static_cast<int>(i));
      params.set(kG92Base - 1, 1.0);
      break;
    default:
      break;
  }
}

}  // namespace pkm::cnc
