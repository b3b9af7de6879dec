/// @file
/// @brief Modal state and offsets of the interpreter (LinuxCNC 2.9 "Modal Groups"), and the
/// coordinate chain machine = Rz(rotation)·(program + G92) + G5x + tool length offset, the
/// rotation (G10 L2 R of the active system) turning X and Y about the system's origin (lengths
/// in mm, angles in degrees).
#pragma once

#include <array>

#include "pkm/cnc/move.hpp"

namespace pkm::cnc {

/// Millimetres per inch (exact).
inline constexpr double kMmPerInch = 25.4;

/// Six axes X Y Z (mm) A B C (deg).
using Axes = std::array<double, 6>;

/// The interpreter's modal state. G-codes are stored times ten (G92.1 -> 921).
struct MachineState {
  bool inch = false;          ///< G20 (true) / G21
  Plane plane = Plane::kXY;   ///< G17 / G18 / G19
  bool incremental = false;   ///< G91 / G90
  bool ijk_absolute = false;  ///< G90.1 / G91.1
  bool inverse_time = false;  ///< G93 / G94
  bool feed_per_rev = false;  ///< G95 (F in length units per spindle revolution) / G94
  bool css = false;           ///< G96 (S is a surface speed) / G97 (S in rev/min)
  double css_max = 0.0;       ///< G96's D word: the most rev/min (0: none given)
  bool retract_to_r = true;   ///< G99 / G98 (rs274's start-up mode is G99)
  int motion = 800;           ///< active motion mode x10 (0, 10, 20, 30, 730, 740, 800..890)
  int coordinate_system = 1;  ///< 1 = G54 .. 9 = G59.3
  int path_mode = 640;        ///< G61 / G61.1 / G64, recorded only
  double feed = 0.0;          ///< feed rate, mm/min (units-per-minute mode)
  /// The F number as written (units-per-minute mode): the feed of a rotary-only move in deg/min,
  /// whatever G20/G21 said (LinuxCNC converts F's length rate only; angles have no inch).
  double angular_feed = 0.0;
  double spindle_speed = 0.0;     ///< S
  int spindle_direction = 0;      ///< M3 (+1, clockwise), M4 (-1), M5 (0; stopped at start-up)
  bool overrides_enabled = true;  ///< M48 (true) / M49: feed and speed overrides
  bool mist = false;              ///< M7 (on) / M9
  bool flood = false;             ///< M8 (on) / M9
  int tool_length_mode = 490;     ///< G43 (430) / G43.1 (431) / G49 (490)
  int selected_tool = 0;          ///< T
  int tool_in_spindle = 0;        ///< after M6
  Axes machine{};                 ///< current position, machine coordinates
  Axes g5x{};                     ///< active coordinate system offset
  Axes g92{};                     ///< G92 offset
  Axes tool_offset{};             ///< tool length offset (G43 / G43.1)
  double rotation = 0.0;          ///< XY rotation of the active system, deg (G10 L2 R)
  /// The machine position of program position `p` (the chain above).
  [[nodiscard]] Axes toMachine(const Axes& p) const;
  /// The program position of machine position `m` (the chain above, inverted).
  [[nodiscard]] Axes toProgram(const Axes& m) const;
  /// The program position now.
  [[nodiscard]] Axes programPosition() const { return toProgram(machine); }
  /// Program coordinate of axis `i` at the current position.
  [[nodiscard]] double program(std::size_t i) const { return programPosition()[i]; }
  /// The machine position after a move to the axis values `words` (program units converted to
  /// mm/deg; NaN for an axis without a word: it keeps its program coordinate), absolute or
  /// incremental as the state says.
  [[nodiscard]] Axes target(const Axes& words) const;
  /// The feed of a non-rapid move in mm/min: F, or under G95 F (mm/rev) times S (rev/min).
  [[nodiscard]] double feedPerMinute() const { return feed_per_rev ? feed * spindle_speed : feed; }
  /// mm per program length unit (1 or 25.4).
  [[nodiscard]] double scale() const { return inch ? kMmPerInch : 1.0; }
  /// mm (or deg) per program unit of axis `i`.
  [[nodiscard]] double axisScale(std::size_t i) const { return i < 3 ? scale() : 1.0; }
};

}  // namespace pkm::cnc
