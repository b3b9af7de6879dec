// Private state of pkm::cnc::Interpreter, shared by interpreter.cpp (program flow),
// block_executor.cpp (one block's words and modal codes) and motion.cpp (moves, arcs, cycles).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "pkm/cnc/canned_cycle.hpp"
#include "pkm/cnc/cutter_comp.hpp"
#include "pkm/cnc/interpreter.hpp"
#include "pkm/cnc/parameters.hpp"

namespace pkm::cnc {

/// The axis words X Y Z A B C, in the order of Axes.
inline constexpr std::array<char, 6> kAxisWords{'x', 'y', 'z', 'a', 'b', 'c'};

/// The centre-offset (and G87 offset) words I J K of the axes X Y Z.
inline constexpr std::array<char, 3> kOffsetWords{'i', 'j', 'k'};

/// The bit of letter `c` (a..z) in ResolvedBlock::has.
constexpr std::uint32_t letterBit(char c) { return std::uint32_t{1} << (c - 'a'); }

/// The words of one block after evaluation. Letters a..z index `value` and the bits of `has`;
/// `value` is only meaningful (and only written) where `has` says so.
struct ResolvedBlock {
  std::size_t line = 0;
  std::array<double, 28> value;  // a..z, @, ^; not initialised: see hasWord and word
  std::uint32_t has = 0;         // bit letterBit(c): the block has word c
  std::array<int, 16> g;         // G codes x10, the first n_g (one per modal group at most)
  int n_g = 0;
  std::array<int, 12> m;  // M codes, the first n_m
  int n_m = 0;
  [[nodiscard]] bool hasWord(char c) const { return (has & letterBit(c)) != 0; }
  /// The value of word `c`; 0 when the block has none.
  [[nodiscard]] double word(char c) const {
    return hasWord(c) ? value[static_cast<std::size_t>(c - 'a')] : 0.0;
  }
  [[nodiscard]] bool hasAxis() const {
    return (has &
            (letterBit('x') | letterBit('y') | letterBit('z') | letterBit('a') | letterBit('b') |
             letterBit('c') | letterBit(kPolarRadius) | letterBit(kPolarAngle))) != 0;
  }
};

/// An M98 call (kind 98: subprogram `target`, `count` passes) or M99 return (kind 99) that a
/// block asks the program flow for; kind 0: none.
struct FanucRequest {
  int kind = 0;
  std::string target;
  double count = 1.0;
};

/// Per-block decisions of the modal-group check (one code per group at most).
struct BlockCodes {
  int motion = -1;     // group 1
  int non_modal = -1;  // group 0 (G4, G10, G53, G92, G92.x)
  int plane = -1, distance = -1, ijk = -1, feed_mode = -1, units = -1, cutter = -1, tlo = -1,
      retract = -1, wcs = -1, path = -1;
  int spindle_mode = -1;  // group 14: G96 / G97
  int m_stop = -1, m_tool = -1, m_spindle = -1, m_override = -1;
  // M19 (orient), M50-M53 (override switches), M61 (set the tool), M62-M68 (I/O): no motion.
  int m_orient = -1, m_switch = -1, m_set_tool = -1, m_io = -1;
  int m_fanuc = -1;  // M98 / M99
  int m_modes = -1;  // M70-M73
  bool m_mist = false, m_flood = false, m_coolant_off = false;
};

/// The integer value of word `letter` (reals within 0.0001 of one are accepted); throws
/// GcodeError otherwise.
[[nodiscard]] int toInt(double v, char letter);

/// Throws GcodeError for a feed move under G95 with the spindle speed 0 (LinuxCNC's error), or
/// under G96 (the speed would depend on a lathe's X radius: not supported).
void checkFeedPerRev(const MachineState& st);

/// The name of G code `code` (its number ×10): "G1", "G92.1".
[[nodiscard]] std::string gName(int code);

/// Forwards motions, dwells and messages to `inner`, counting the motions in `summary` (the path
/// of the moves cutter compensation passes on, some of them after their block).
class CountingSink final : public MoveSink {
 public:
  CountingSink(MoveSink& inner, RunSummary& summary, bool inch);
  void onMove(const Move& move) override;
  void onDwell(std::size_t line, double seconds) override;
  void onToolChange(std::size_t line, int tool) override { inner_.onToolChange(line, tool); }
  void onMessage(std::size_t line, CommentKind kind, const std::string& text) override;

 private:
  MoveSink& inner_;
  RunSummary& summary_;
  bool inch_;
};

/// What the program flow needs of the interpreter: its parameters, and leaving a call level.
class FlowSource : public ParameterSource {
 public:
  /// Leaving a sub: forgets the modal states it saved, restoring an M73 one.
  virtual void leaveCallLevel() = 0;
};

/// #5599: (DEBUG, ...) messages are shown when 1 (the default), not when 0 (LinuxCNC).
inline constexpr int kDebugFlagParam = 5599;

struct Interpreter::Impl : FlowSource {
  explicit Impl(InterpreterOptions o) : options(std::move(o)) {
    params.set(kDebugFlagParam, 1.0);
    params.setNamed("_value", 0.0);  // LinuxCNC: 0 at program start
    params.setNamed("_value_returned", 0.0);
  }

  // ParameterSource: reads in program units.
  double numbered(int index) override;
  /// A predefined parameter (system_parameters.cpp) or the store's.
  double named(const std::string& name) override;
  bool exists(const std::string& name) override;
  void setNumbered(int index, double value);
  /// Sets `#<name>`; throws GcodeError for a read-only one (predefined, INI, #<_value>...).
  void setNamedChecked(const std::string& name, double value);
  /// The value of predefined parameter `name` (lower case, without '#<' '>'): LinuxCNC's
  /// #<_x>, #<_metric>, #<_current_tool>, ..., and #<_ini[section]name>; nullopt for others.
  [[nodiscard]] std::optional<double> systemParameter(const std::string& name) const;

  // interpreter.cpp, sub_files.cpp
  /// How a run of blocks ended: M2/M30 (or M99 in the main program), past its last block, or
  /// by the return of the sub file it was started for.
  enum class Outcome { kEnded, kFellOff, kReturned };
  /// Runs `program` from block `pc`; `external`: a sub file's sub, whose endsub returns.
  Outcome runProgram(const Program& program, std::size_t pc, MoveSink& sink, bool external);
  /// Calls sub `name` with `args` (for the calling block at `line`) from the file NAME.ngc in the
  /// working folder or options.subroutine_path (LinuxCNC's SUBROUTINE_PATH); throws GcodeError when
  /// there is none or it does not define the sub.
  Outcome callExternal(std::size_t line,
                       const std::string& name,
                       const std::vector<double>& args,
                       MoveSink& sink);

  // block_executor.cpp
  /// Executes one block; returns false when the program ends (M2/M30).
  bool execute(const Block& block, MoveSink& sink);
  /// M70 (save), M71 (forget), M72 (restore) or M73 (save, restore on return) of the modal
  /// state at the current call level (modal_save.cpp).
  void modalState(int m);
  /// Restores the modes M70 saves from `s` (not the motion mode; the position stays).
  void restoreModes(const MachineState& s);
  void leaveCallLevel() override;
  /// Feed mode, F, S, T, M6 and M61 of a block, in LinuxCNC's order.
  void setFeedSpeedTool(const ResolvedBlock& rb, const BlockCodes& c);
  /// Throws GcodeError for tool number `tool` (> 0) missing from a non-empty tool table.
  void checkToolExists(int tool) const;
  /// Turns the polar words @ ^ of `rb` into X and Y (LinuxCNC 2.9 G-code overview, "Polar
  /// Coordinates": about the program's XY zero, cumulative under G91).
  void applyPolar(ResolvedBlock& rb) const;
  /// The M98 call (P subprogram, L passes, default 1) or M99 return block `rb` asks for.
  [[nodiscard]] FanucRequest fanucRequest(const ResolvedBlock& rb, int m) const;
  /// Runs the block's active comment (after its parameter settings, before its motion): a
  /// message to `sink`, or the error of an ABORT.
  void activeComment(const Block& block, MoveSink& sink);
  /// Evaluates the words of `block` into `rb` (freshly constructed) and performs its parameter
  /// settings.
  void resolve(const Block& block, ResolvedBlock& rb, MoveSink& sink);
  BlockCodes classify(const ResolvedBlock& rb) const;  // block_codes.cpp
  void checkWords(const ResolvedBlock& rb, const BlockCodes& c) const;
  /// The words M61 and M62-M68 need (LinuxCNC 2.9 M-code reference): P for M62-M65, P or E for
  /// M66 (L mode 0..4), E and Q for M67/M68, Q for M61. They make no motion.
  void checkIoWords(const ResolvedBlock& rb, const BlockCodes& c) const;
  /// Throws GcodeError for a G or M code of `rb` that options.remapped_codes names.
  void refuseRemapped(const ResolvedBlock& rb) const;
  void setTlo(const ResolvedBlock& rb, int code);
  void selectSystem(int n);
  /// Applies options.initial_parameters: stores them, selects the system #5220 names (1..9,
  /// else G54) and applies the stored G92 offset when #5210 is 1, as LinuxCNC starts up.
  void loadParameters();
  void doG10(const ResolvedBlock& rb);
  /// G10 L1 (entry = words), L10 and L11 (entry from the current position) of tool P
  /// (tool_entries.cpp).
  void doG10Tool(const ResolvedBlock& rb, int l);
  void doG92(const ResolvedBlock& rb, int code);
  /// G28/G30: rapid to the intermediate point of the axis words, then to the stored position
  /// (#5161-#5166, #5181-#5186, machine coordinates) of those axes, or of all without words;
  /// G28.1/G30.1 store the current machine position there.
  void doHome(const ResolvedBlock& rb, int code, MoveSink& sink);

  // cutter_comp_block.cpp
  /// G40, G41, G42, G41.1, G42.1 of a block (after its plane and units, before its motion).
  void cutterCompensation(const ResolvedBlock& rb, int code, MoveSink& sink);
  /// The radius (mm) of G41/G42's D word (a tool number; the tool in the spindle without one) or
  /// of G41.1/G42.1's D word (a diameter in program units).
  [[nodiscard]] double compRadius(const ResolvedBlock& rb, int code) const;
  /// Throws GcodeError for what LinuxCNC refuses while compensation is on in block `rb`
  /// (changing planes, systems, offsets, path or retract modes; G28/G30, probes, cycles,
  /// G53, I/O and override M-codes).
  void checkCompRestrictions(const ResolvedBlock& rb, const BlockCodes& c) const;
  /// M0, M1, M2, M30, M60 and the end of a program: the held compensated moves go out.
  void flushCompensation(MoveSink& sink);

  // motion.cpp
  void doMotion(const ResolvedBlock& rb, const BlockCodes& c, MoveSink& sink);
  void straight(const ResolvedBlock& rb, bool rapid, bool g53, MoveSink& sink);
  void arc(const ResolvedBlock& rb, bool clockwise, MoveSink& sink);
  /// G33 (a feed synchronised with the spindle, K length units per revolution) and G33.1 (rigid
  /// tapping: in to the axis words and back out), as rs274 emits them (spindle_sync.cpp).
  void spindleSynchronised(const ResolvedBlock& rb, int code, MoveSink& sink);
  /// G96 D S / G97 S (spindle_sync.cpp).
  void spindleMode(const ResolvedBlock& rb, int code);
  /// G38.2-G38.5: a straight feed to the axis words with the probe on, as rs274 simulates it.
  void probe(const ResolvedBlock& rb, int code, MoveSink& sink);
  void cycle(const ResolvedBlock& rb, int code, MoveSink& sink);
  /// Reads the sticky words of canned cycle `code` (×10) into cycle_q, cycle_p, cycle_i..k and
  /// `q`: Q of G73/G83, P of G74/G82/G84/G86/G88/G89, I J K of G87 (lengths in mm); `entering`:
  /// the cycle's first block, which must have them (but P of G74/G84).
  void cycleStickyWords(const ResolvedBlock& rb, int code, bool entering, CycleRequest& q);
  /// The machine position of a cycle point: `local` (program coordinates, mm) on the program
  /// axes `axes`, the other axes where they are.
  [[nodiscard]] Axes cyclePoint(const std::array<double, 3>& local,
                                const std::array<std::size_t, 3>& axes) const;
  /// Sends the expanded cycle_steps of source line `line` to `sink` as lines, dwells and actions.
  void emitCycleSteps(std::size_t line, MoveSink& sink);
  /// The block's axis words in mm/deg (NaN where it has none), for MachineState::target.
  [[nodiscard]] Axes axisWords(const ResolvedBlock& rb) const;
  /// Emits a line to machine position `to`; updates the position.
  void emitLine(std::size_t line, bool rapid, const Axes& to, double inverse_f, MoveSink& sink);

  InterpreterOptions options;
  MachineState st;
  std::size_t current_line = 0;       // source line of the block being executed (#<_line>)
  mutable bool missing_tool = false;  // the run stopped at a tool the table lacks (missingTool())
  int reported_tool = -1;     // the tool in the spindle the sink was last told of (-1: none)
  Axes tlo_at_last_motion{};  // the tool offset the last motion was made with (M6 re-read)
  Axes spindle_entry{};       // #5401-#5406: the spindle tool's entry, kept for T0
  FanucRequest fanuc;         // set by execute() for the program flow
  struct SavedModes {
    std::optional<MachineState> state;
    bool autorestore = false;  // M73
  };
  std::vector<SavedModes> saved_modes;                        // by call level (M70-M73)
  std::map<std::string, std::unique_ptr<Program>> sub_files;  // loaded, by path
  std::size_t external_depth = 0;                             // sub files being run
  std::size_t external_call_line = 0;  // the main program's line of the outermost file call
  Parameters params;
  RunSummary summary;
  CutterComp comp;  // G40-G42.1
  // Canned-cycle memory (rs274ngc cycle_il / cycle_cc and sticky R, Q, P).
  bool cycle_il_flag = false;
  double cycle_il = 0.0, cycle_cc = 0.0, cycle_r = 0.0, cycle_q = 0.0, cycle_p = 0.0;
  double cycle_i = 0.0, cycle_j = 0.0, cycle_k = 0.0;  // G87's sticky I, J, K
  std::array<std::size_t, 3> cycle_axes{0, 1, 2};      // plane's axes and the hole axis
  int cycle_code = 810;                                // the cycle being expanded (x10)
  std::vector<CycleStep> cycle_steps;
  std::vector<double> values;  // scratch: evaluated assignment values
  // Block reports (MoveSink::wantsBlocks): the index of the block being executed, its words.
  bool report_blocks = false;
  std::size_t block_index = kNoBlock;
  std::vector<EvaluatedWord> evaluated;
};

}  // namespace pkm::cnc
