/// @file
/// @brief Cutter radius compensation (G41/G42, G41.1/G42.1, G40) as LinuxCNC 2.9 performs it:
/// the tool centre runs one tool radius to the left or right of the programmed path in the XY
/// (G17) or XZ (G18) plane. The first move after G41/G42 is the entry move (its end is offset
/// perpendicular to it); a convex corner gets an arc of the tool radius about the programmed
/// corner; at a concave corner the move into it is shortened to where the offset paths meet
/// (line–line, arc–line, line–arc, arc–arc); a move that the shortening would reverse is a
/// gouging error. G40 leaves the tool where it is, and the next move (the exit move) goes from
/// there to its programmed point. Sources: LinuxCNC 2.9 User Manual, "Cutter Compensation" and
/// the G40–G42.1 reference; behaviour checked move by move against LinuxCNC's rs274
/// (docs/gcode.md). Positions are machine coordinates (mm, deg).
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "pkm/cnc/modal_state.hpp"
#include "pkm/cnc/move.hpp"

namespace pkm::cnc {

/// Side of the programmed path the tool runs on, looking along the motion: G41 left, G42 right.
enum class CompSide { kOff, kLeft, kRight };

/// Cutter compensation of a stream of programmed moves. Because a move's compensated end
/// depends on the next move (the corner), the last move is held back until the next XY (XZ)
/// move, G40 or flush() decides it; dwells and messages issued meanwhile are held with it so
/// that the sink sees everything in program order.
class CutterComp {
 public:
  /// Turns compensation on: `side` with tool radius `radius_mm` (a negative radius, from a
  /// tool table whose diameters are differences to a nominal tool, swaps the side, as in
  /// LinuxCNC), in `plane`. A radius of 0 leaves moves as programmed. Throws GcodeError when
  /// compensation is already on or `plane` is YZ (LinuxCNC compensates in XY and XZ only).
  void start(CompSide side, double radius_mm, Plane plane);
  /// G40: passes the held moves on with the tool where it is, and turns compensation off; after
  /// a compensated move, the next move must be straight (arcForbidden()).
  void stop(MoveSink& sink, bool inch);
  /// M0, M1, M2, M30, M60 and the end of a program: passes the held moves on as they are.
  void flush(MoveSink& sink, bool inch);

  /// G41/G42 is in effect (even with a zero radius).
  [[nodiscard]] bool on() const { return side_ != CompSide::kOff; }
  /// Moves are being compensated: on() with a radius > 0.
  [[nodiscard]] bool compensating() const { return on() && radius_ > 0.0; }
  /// The move after a G40 that ended compensation must not be an arc (LinuxCNC refuses it);
  /// a straight move clears this.
  [[nodiscard]] bool arcForbidden() const { return arc_forbidden_; }
  /// A straight move (compensated or not) was made: arcs are allowed again.
  void allowArc() { arc_forbidden_ = false; }
  /// Where the tool is when compensation put it somewhere else than the programmed position:
  /// after a compensated move, until an uncompensated move (forgetTool) ends the exit. A tool
  /// change reads the position back from there, as LinuxCNC does.
  [[nodiscard]] const Axes* displacedTool() const { return displaced_ ? &tool_at_ : nullptr; }
  /// An uncompensated move was made: the tool is where the program says.
  void forgetTool() { displaced_ = false; }
  /// Tool radius in use (mm, ≥ 0) and side (after a negative radius swapped it).
  [[nodiscard]] double radius() const { return radius_; }
  [[nodiscard]] CompSide side() const { return side_; }

  /// A programmed straight move (G0 when `rapid`, else fed at `feed` mm/min) from programmed
  /// machine position `from` to `to`, from source line `line`. Precondition: compensating().
  /// Throws GcodeError: entry move not longer than the tool radius, zero-degree inside corner,
  /// a corner the tool cannot reach without gouging. `inch`: the program's units (LinuxCNC's
  /// gouging tolerances are in program units).
  void straight(std::size_t line,
                bool rapid,
                const Axes& from,
                const Axes& to,
                double feed,
                MoveSink& sink,
                bool inch);
  /// A programmed arc `programmed` (end, centre in the plane, turns, feed as the uncompensated
  /// interpreter computes them) from programmed position `from`. Precondition: compensating().
  /// Throws GcodeError: entry arc not longer than the tool radius, the tool not fitting inside
  /// the arc, corners the tool cannot reach without gouging, concentric arcs meeting.
  void arc(const Move& programmed, const Axes& from, MoveSink& sink, bool inch);
  /// A dwell: passed on at once when nothing is held, else after the held moves.
  void dwell(std::size_t line, double seconds, MoveSink& sink);
  /// An active comment's message, ordered like dwell().
  void message(std::size_t line, CommentKind kind, const std::string& text, MoveSink& sink);

 private:
  struct P2 {
    double u = 0.0, v = 0.0;
  };
  struct Held {
    enum class Kind { kMove, kDwell, kMessage } kind = Kind::kMove;
    Move move;
    P2 dir;              ///< straight: the programmed direction (0 for entry and non-plane moves)
    double sweep = 0.0;  ///< arc: programmed sweep (rad, signed), the gouging reference
    double seconds = 0.0;
    CommentKind comment = CommentKind::kNone;
    std::string text;
  };

  [[nodiscard]] P2 inPlane(const Axes& a) const { return {a[axes_[0]], a[axes_[1]]}; }
  [[nodiscard]] Move lineTo(std::size_t line, bool rapid, const Axes& to, P2 at, double feed) const;
  void hold(const Move& m, P2 dir, double sweep);
  /// Passes every held item on (LinuxCNC's dequeue); the held start becomes unknown.
  void release(MoveSink& sink);
  /// Moves the end of every held move to `p`, checking for gouging, then releases them.
  void endHeldAt(P2 p, MoveSink& sink, bool inch);
  /// The arc about programmed corner `corner` from the tool position to `to` (straight when
  /// `rapid`): normal axis where the tool is, rotary axes at `end_axes`.
  void cornerMove(std::size_t line,
                  bool rapid,
                  P2 corner,
                  P2 to,
                  const Axes& end_axes,
                  double feed,
                  MoveSink& sink);
  [[nodiscard]] const Move* heldPlaneMove() const;
  /// Where the held line ends at a concave corner before a line (beta, theta as in straight()).
  [[nodiscard]] P2 concaveLineEnd(double beta, double theta) const;
  [[nodiscard]] P2 arcToLineEnd(const Move& prev, P2 o, double alpha) const;
  [[nodiscard]] P2 lineToArcEnd(
      P2 centre, double arc_radius, double beta, double theta, bool inside, int turns) const;
  [[nodiscard]] P2 arcToArcEnd(const Move& prev, P2 centre, double new_rad, int turns) const;
  void arcEntry(const Move& programmed, const Axes& from);
  void arcNext(const Move& programmed, const Axes& from, MoveSink& sink, bool inch);

  CompSide side_ = CompSide::kOff;
  double radius_ = 0.0;
  std::array<std::size_t, 3> axes_{0, 1, 2};  // plane axes and normal (planeAxes)
  bool first_ = true;                         // the next move is the entry move
  bool arc_forbidden_ = false;
  bool displaced_ = false;  // see displacedTool()
  P2 tool_;         // compensated end of the last move (held or passed on), plane coordinates
  Axes tool_at_{};  // the same, all axes
  std::vector<Held> held_;
  P2 start_;  // where the first held plane move starts
  bool start_known_ = false;
};

}  // namespace pkm::cnc
