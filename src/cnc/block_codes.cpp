// The modal-group check of one block (LinuxCNC 2.9 G-code overview, "Modal Groups"): at most
// one code per group, the supported G and M codes, M9 not with M7/M8.
#include <fmt/format.h>

#include <cmath>

#include "interpreter_impl.hpp"
#include "pkm/cnc/gcode_error.hpp"

namespace pkm::cnc {

namespace {

void setOnce(int& slot, int code, const char* prefix) {
  if (slot >= 0)
    throw GcodeError(fmt::format("two {} codes from the same modal group: {}{} and {}{}",
                                 prefix,
                                 prefix,
                                 slot,
                                 prefix,
                                 code));
  slot = code;
}

void setOnceG(int& slot, int code) {
  if (slot >= 0)
    throw GcodeError(
        fmt::format("two G codes from the same modal group: {} and {}", gName(slot), gName(code)));
  slot = code;
}

/// Whether G code `g` (×10) is in the motion group (group 1, G80 included).
bool isMotion(int g) {
  switch (g) {
    case 0:
    case 10:
    case 20:
    case 30:
    case 330:
    case 331:
    case 382:
    case 383:
    case 384:
    case 385:
    case 800:
    case 810:
    case 820:
    case 830:
    case 730:
    case 740:
    case 840:
    case 850:
    case 860:
    case 870:
    case 880:
    case 890:
      return true;
    default:
      return false;
  }
}

/// The slot of `c` for the modal group of G code `g` (×10) other than motion; null when `g` is
/// not supported.
int* modalSlot(BlockCodes& c, int g) {
  switch (g) {
    case 40:
    case 100:
    case 280:
    case 281:
    case 300:
    case 301:
    case 530:
    case 520:
    case 920:
    case 921:
    case 922:
    case 923:
      return &c.non_modal;
    case 170:
    case 180:
    case 190:
      return &c.plane;
    case 900:
    case 910:
      return &c.distance;
    case 901:
    case 911:
      return &c.ijk;
    case 930:
    case 940:
    case 950:
      return &c.feed_mode;
    case 960:
    case 970:
      return &c.spindle_mode;
    case 200:
    case 210:
      return &c.units;
    case 400:
    case 410:
    case 411:
    case 420:
    case 421:
      return &c.cutter;
    case 430:
    case 431:
    case 490:
      return &c.tlo;
    case 980:
    case 990:
      return &c.retract;
    case 540:
    case 550:
    case 560:
    case 570:
    case 580:
    case 590:
    case 591:
    case 592:
    case 593:
      return &c.wcs;
    case 610:
    case 611:
    case 640:
      return &c.path;
    default:
      return nullptr;
  }
}

/// Adds G code `g` (×10) to `c`.
void classifyG(BlockCodes& c, int g) {
  if (isMotion(g)) {
    // rs274 accepts G80 together with another motion code, which wins (checked with rs274:
    // "G80 G0 X1" and "G0 G80 X1" both traverse).
    if (g == 800 && c.motion >= 0) return;
    if (c.motion == 800) c.motion = -1;
    setOnceG(c.motion, g);
    return;
  }
  if (int* slot = modalSlot(c, g)) {
    setOnceG(*slot, g);
    return;
  }
  throw GcodeError(fmt::format("unsupported G code {}", gName(g)));
}

/// Adds M code `m` to `c`.
void classifyM(BlockCodes& c, int m) {
  switch (m) {
    case 0:
    case 1:
    case 2:
    case 30:
      setOnce(c.m_stop, m, "M");
      break;
    case 6:
      setOnce(c.m_tool, m, "M");
      break;
    case 3:
    case 4:
    case 5:
      setOnce(c.m_spindle, m, "M");
      break;
    case 48:
    case 49:
      setOnce(c.m_override, m, "M");
      break;
    case 7:
      c.m_mist = true;
      break;
    case 8:
      c.m_flood = true;
      break;
    case 9:
      c.m_coolant_off = true;
      break;
    case 19:
      setOnce(c.m_orient, m, "M");
      break;
    case 50:
    case 51:
    case 52:
    case 53:
      setOnce(c.m_switch, m, "M");
      break;
    case 61:
      setOnce(c.m_set_tool, m, "M");
      break;
    case 70:
    case 71:
    case 72:
    case 73:
      setOnce(c.m_modes, m, "M");
      break;
    case 98:
    case 99:
      setOnce(c.m_fanuc, m, "M");
      break;
    case 62:
    case 63:
    case 64:
    case 65:
    case 66:
    case 67:
    case 68:
      setOnce(c.m_io, m, "M");
      break;
    default:
      if (m >= 100 && m <= 199)
        throw GcodeError(fmt::format(
            "user M code M{} (a program of the controller's USER_M_PATH) is not supported", m));
      throw GcodeError(fmt::format("unsupported M code M{}", m));
  }
}

}  // namespace

BlockCodes Interpreter::Impl::classify(const ResolvedBlock& rb) const {
  if (!options.remapped_codes.empty()) refuseRemapped(rb);
  BlockCodes c;
  for (int k = 0; k < rb.n_g; ++k) classifyG(c, rb.g[static_cast<std::size_t>(k)]);
  for (int k = 0; k < rb.n_m; ++k) classifyM(c, rb.m[static_cast<std::size_t>(k)]);
  if (c.m_coolant_off && (c.m_mist || c.m_flood))
    throw GcodeError("two M codes from the same modal group: M9 with M7/M8");
  return c;
}

void Interpreter::Impl::refuseRemapped(const ResolvedBlock& rb) const {
  const auto refuse = [this](const std::string& code, const std::string& shown) {
    const auto it = options.remapped_codes.find(code);
    if (it != options.remapped_codes.end())
      throw GcodeError(
          fmt::format("{} is remapped by the INI ({}); pkm does not run a remap's procedure",
                      shown,
                      it->second));
  };
  for (int k = 0; k < rb.n_g; ++k) {
    const std::string name = gName(rb.g[static_cast<std::size_t>(k)]);
    std::string lower = name;
    lower[0] = 'g';
    refuse(lower, name);
  }
  for (int k = 0; k < rb.n_m; ++k) {
    const int m = rb.m[static_cast<std::size_t>(k)];
    refuse(fmt::format("m{}", m), fmt::format("M{}", m));
  }
}

void Interpreter::Impl::checkIoWords(const ResolvedBlock& rb, const BlockCodes& c) const {
  if (c.m_set_tool >= 0 && !rb.hasWord('q'))
    throw GcodeError("M61 needs a Q word >= 0 (the tool number)");
  if (c.m_io < 0) return;
  const int m = c.m_io;
  if (m <= 65 && !rb.hasWord('p')) throw GcodeError(fmt::format("M{} needs a P word", m));
  if (m >= 67 && !rb.hasWord('e'))
    throw GcodeError(fmt::format("M{} needs an E word (the analog output)", m));
  if (m != 66) return;
  if (rb.hasWord('p') == rb.hasWord('e'))
    throw GcodeError("M66 needs either a P word (digital input) or an E word (analog input)");
  const double l = rb.hasWord('l') ? rb.word('l') : 0.0;
  if (l != 0.0 && rb.hasWord('e'))
    throw GcodeError("M66 with an analog input (E) can only return at once (L0)");
  if (l != 0.0 && !(rb.word('q') > 0.0))
    throw GcodeError("M66 with a wait mode (L1-L4) needs a timeout Q > 0");
  if (l < 0.0 || l > 4.0 || l != std::floor(l))
    throw GcodeError(fmt::format("M66 L{} is not a wait mode (0..4)", l));
}

}  // namespace pkm::cnc
