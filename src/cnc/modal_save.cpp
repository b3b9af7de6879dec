// M70-M73: saving and restoring the modal state per call level (LinuxCNC 2.9 M-code reference,
// "M70 Save Modal State" ... "M73 Save and Autorestore Modal State"). The motion mode is not part
// of it; units are restored first, so that the feed is read in the restored unit.
#include <fmt/format.h>

#include "interpreter_impl.hpp"
#include "pkm/cnc/gcode_error.hpp"

namespace pkm::cnc {

void Interpreter::Impl::modalState(int m) {
  const std::size_t level = params.callDepth();
  if (saved_modes.size() <= level) saved_modes.resize(level + 1);
  SavedModes& slot = saved_modes[level];
  switch (m) {
    case 70:
    case 73:
      slot.state = st;
      slot.autorestore = m == 73;
      return;
    case 71:
      slot = SavedModes{};
      return;
    default:  // 72
      if (!slot.state)
        throw GcodeError("M72: no modal state was saved (M70, M73) at this call level");
      restoreModes(*slot.state);
  }
}

void Interpreter::Impl::restoreModes(const MachineState& s) {
  st.inch = s.inch;
  st.plane = s.plane;
  st.incremental = s.incremental;
  st.ijk_absolute = s.ijk_absolute;
  st.inverse_time = s.inverse_time;
  st.retract_to_r = s.retract_to_r;
  st.path_mode = s.path_mode;
  st.feed = s.feed;
  st.angular_feed = s.angular_feed;
  st.spindle_speed = s.spindle_speed;
  st.spindle_direction = s.spindle_direction;
  st.mist = s.mist;
  st.flood = s.flood;
  st.overrides_enabled = s.overrides_enabled;
  st.tool_length_mode = s.tool_length_mode;
  st.tool_offset = s.tool_offset;
  if (s.coordinate_system != st.coordinate_system) selectSystem(s.coordinate_system);
}

void Interpreter::Impl::leaveCallLevel() {
  const std::size_t level = params.callDepth();
  if (level >= saved_modes.size()) return;
  const SavedModes slot = saved_modes[level];
  saved_modes.resize(level);  // the sub's saved state goes with it
  if (slot.autorestore && slot.state) restoreModes(*slot.state);
}

}  // namespace pkm::cnc
