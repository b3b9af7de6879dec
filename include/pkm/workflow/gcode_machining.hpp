/// @file
/// @brief The machining preview of a `gcode run` (docs/machining.md): the stock sized by the
/// user or from the program, the tools from the tool table, material removed along the whole
/// interpolated path, rapid moves through the stock, the holder, the machine's platform and the
/// table checked, the stock's changes kept for an animation.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "pkm/cnc/cutting_tool.hpp"
#include "pkm/cnc/height_field.hpp"
#include "pkm/cnc/machining.hpp"

namespace pkm::workflow {

/// Cells along the longer side of the stock when the cell size is automatic (default).
inline constexpr double kAutoCells = 500.0;
/// The finest automatic cell, mm.
inline constexpr double kMinAutoCell = 0.05;

/// What to machine and how finely (GcodeRunRequest::machining).
struct MachiningRequest {
  /// "auto": the box holding every feed move's tool tip, grown in XY by the largest tool radius
  /// plus `margin`, its top at the highest tip of a feed moving sideways (a plunge starts in the
  /// air) and its bottom `margin` (at least 1 mm) under the lowest;
  /// "box" (`box`) or "cylinder" (`cylinder`).
  std::string stock = "auto";
  std::array<double, 6> box{};       ///< x0 y0 z0 x1 y1 z1, mm (machine coordinates)
  std::array<double, 5> cylinder{};  ///< centre x y, radius, z0 z1, mm
  double margin = 5.0;               ///< auto stock, mm, ≥ 0
  /// Cell size, mm (0: the stock's longer side / auto_cells, at least kMinAutoCell).
  double cell = 0.0;
  double auto_cells = kAutoCells;  ///< 10 to 2,000
  /// Without a tool in the spindle (no M6, or T0): this tool with its tip at the controlled
  /// point. Its holder sizes every tool's holder.
  cnc::CuttingTool default_tool{};
  std::size_t frames = 0;  ///< animation moments, evenly spaced in time (0: none); ≤ 10,000
  std::size_t max_changes = 2'000'000;  ///< cnc::MachiningOptions::max_changes
  /// Throws pkm::InvalidArgument naming the field for an unknown stock kind or a bad value.
  void validate() const;
};

/// A tool the preview used.
struct MachiningTool {
  cnc::CuttingTool tool;
  /// From the controlled point to the tip along the tool axis, mm: the tool table's length, or 0
  /// for the default tool.
  double tip_offset = 0.0;
  std::size_t first_line = 0;  ///< where it first cut or moved
};

/// What the preview found (GcodeRunResult::machining).
struct MachiningReport {
  cnc::StockShape stock;  ///< the stock machined (auto: as sized)
  double cell = 0.0;      ///< mm
  std::size_t nx = 0, ny = 0;
  double x0 = 0.0, y0 = 0.0;  ///< lower corner of the grid, mm
  /// Initial heights (cells outside a cylinder at the bottom) and the finished part's, j·nx + i.
  std::vector<float> initial, heights;
  cnc::MachiningResult result;
  std::vector<MachiningTool> tools;
  /// The tool at each point of GcodeRunResult::path: its tip and axis (mm) and its number.
  std::vector<cnc::ToolPose> path_tools;
  std::vector<int> path_tool_numbers;
  double seconds = 0.0;  ///< wall time of the removal, s
  /// Collisions in all (tool positions), by kind: the sum of result.event_counts.
  [[nodiscard]] std::size_t collisions() const;
};

/// Sets the stock of `request` from a command-line SPEC: "auto", "box:X0,Y0,Z0,X1,Y1,Z1" or
/// "cylinder:CX,CY,R,Z0,Z1" (mm). Throws pkm::InvalidArgument naming the spec for another form.
void setStock(MachiningRequest& request, std::string_view spec);

/// The preview's summary for the text report: the stock, the tools, volumes, time and every
/// collision group (kind, line, depth, tip, moment).
[[nodiscard]] std::string machiningText(const MachiningReport& report);

}  // namespace pkm::workflow
