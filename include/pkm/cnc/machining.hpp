/// @file
/// @brief The machining preview (docs/machining.md): a tool swept along a program's path
/// through a height-field stock, removing material, with rapid moves through the stock, the
/// holder or a machine part (a hexapod's platform) in the stock and anything below the table
/// flagged as collisions, and the stock's changes kept at chosen moments for an animation.
/// The mechanism preview of a graphic-programming simulator extended to the machining process
/// (Lee et al., "Development of a Parallel-Typed CNC Machine": its graphic simulator).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "pkm/cnc/cutting_tool.hpp"
#include "pkm/cnc/height_field.hpp"

namespace pkm::cnc {

/// How finely the tool is swept and what is kept.
struct MachiningOptions {
  /// Longest step of the tool between two cuts, mm (0: half a cell). A tilt moves the gauge end
  /// by length·angle, which counts too. ≥ 0.
  double max_step = 0.0;
  /// Moments (s, increasing) at which the stock's changes since the previous moment are kept
  /// (MachiningResult::frames); empty: none.
  std::vector<double> frame_times;
  /// Most cell changes kept over all frames; past it the frames stop (the result says so) and
  /// only the finished part is complete. > 0.
  std::size_t max_changes = 2'000'000;
  /// Most distinct (kind, line) collision entries kept (the counts include the rest).
  std::size_t max_events = 500;
  /// Depth below which an overlap is not a collision (rounding of the stored heights), mm. ≥ 0.
  double collision_depth = 1e-3;
  /// Throws pkm::InvalidArgument for a value out of range or frame times not increasing.
  void validate() const;
};

/// One collision, grouped by kind and program line: its deepest moment.
struct MachiningEvent {
  /// "rapid" (a G0 removed material), "holder" (the holder in the stock), "table" (tool or holder
  /// below the table top, the stock's bottom), or a machine part's name (e.g. "platform").
  std::string kind;
  std::size_t line = 0;
  double t = 0.0;               ///< moment of the deepest overlap, s
  std::array<double, 3> tip{};  ///< the tool tip then, mm
  double depth = 0.0;           ///< how deep, mm
  std::size_t count = 0;        ///< tool positions of this line with this overlap
};

/// The stock's changes up to moment t: cells (index j·nx + i) and their new heights.
struct StockFrame {
  double t = 0.0;
  std::vector<std::uint32_t> cells;
  std::vector<float> heights;
};

/// What a preview found.
struct MachiningResult {
  double initial_volume = 0.0;  ///< mm³
  double final_volume = 0.0;    ///< mm³
  std::size_t positions = 0;    ///< tool positions swept
  std::vector<StockFrame> frames;
  bool frames_complete = true;         ///< false: max_changes was reached, later frames are missing
  std::vector<MachiningEvent> events;  ///< in order of first occurrence
  std::map<std::string, std::size_t> event_counts;  ///< tool positions per kind
};

/// Sweeps tools through a stock. Use: setTool, moveTo along the path (the first moveTo places
/// the tool), checkPart for machine parts, then finish.
class MachiningSimulator {
 public:
  /// Throws pkm::InvalidArgument as HeightField and MachiningOptions::validate.
  MachiningSimulator(const StockShape& stock, double cell, MachiningOptions options);
  /// The tool in the spindle from now on (validated).
  void setTool(const CuttingTool& tool);
  /// Moves the tool in straight steps from where it is to `pose` (tip and axis interpolated),
  /// reaching it at time `t` (s) on program line `line`; `rapid` flags material it removes.
  /// The first call only places it (and cuts there).
  void moveTo(const ToolPose& pose, double t, std::size_t line, bool rapid);
  /// Checks the convex polygon `points` (mm; e.g. a platform's joints) against the stock at
  /// time `t`: any part of it below the stock's surface or the table is a collision `kind`.
  void checkPart(const std::string& kind,
                 const std::vector<std::array<double, 3>>& points,
                 double t,
                 std::size_t line);
  [[nodiscard]] const HeightField& stock() const { return field_; }
  /// Closes the frames (one at the last moment given) and returns the result.
  [[nodiscard]] MachiningResult finish();

 private:
  void cutAt(const ToolPose& pose, double t, std::size_t line, bool rapid);
  void record(std::size_t k);
  void closeFramesUpTo(double t);
  void event(
      const std::string& kind, std::size_t line, double t, const ToolPose& pose, double depth);

  HeightField field_;
  MachiningOptions options_;
  CuttingTool tool_;
  bool placed_ = false;
  ToolPose at_{};
  double t_ = 0.0;
  MachiningResult result_;
  std::size_t next_frame_ = 0;
  std::vector<std::uint32_t> stamp_;  ///< frame (+1) whose change list holds each cell
  std::vector<std::uint32_t> pending_;
  std::size_t changes_ = 0;
  std::map<std::pair<std::string, std::size_t>, std::size_t> event_index_;
  /// Depth each cell has lost to the rapid being swept (a rapid's collision depth).
  std::unordered_map<std::size_t, double> rapid_removed_;
};

}  // namespace pkm::cnc
