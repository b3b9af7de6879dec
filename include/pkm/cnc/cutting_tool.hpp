/// @file
/// @brief The solid of a milling tool and its holder for the machining preview
/// (docs/machining.md): a flat or ball end mill of diameter D reaching from its tip to the gauge
/// line (the spindle's controlled point) at length L, and a cylindrical holder above it; and the
/// lowest point of either solid on a vertical line, which is what removes material from a
/// height-field stock (cnc::HeightField).
#pragma once

#include <array>
#include <string>
#include <string_view>

#include "pkm/cnc/tool_table.hpp"

namespace pkm::cnc {

/// The end of a milling tool: flat (end mill, drill treated as flat) or ball.
enum class ToolEnd { kFlat, kBall };

/// "flat" or "ball".
[[nodiscard]] const char* toString(ToolEnd end);

/// A tool's end from its tool-table comment: "ball" when the comment names a ball (any case:
/// "ball", "ball-end", "ballnose"), else flat.
[[nodiscard]] ToolEnd toolEndOf(std::string_view comment);

/// A milling tool and its holder, lengths in mm.
struct CuttingTool {
  int number = 0;         ///< tool-table number (0: the default tool of a run without one)
  double diameter = 6.0;  ///< cutting diameter, > 0
  double length = 50.0;   ///< tip to gauge line (the tool table's Z offset), > 0
  ToolEnd end = ToolEnd::kFlat;
  double holder_diameter = 40.0;  ///< the holder above the gauge line, > 0
  double holder_length = 60.0;    ///< > 0
  /// Throws pkm::InvalidArgument naming the tool for a value that is not finite and > 0, or a
  /// ball whose radius exceeds its length.
  void validate() const;
};

/// The tool of tool-table `entry`: its diameter, its Z offset as length and its comment's end;
/// the holder from `holder` (diameter and length). Throws as CuttingTool::validate (a tool
/// without a diameter or length names the table entry).
[[nodiscard]] CuttingTool cuttingToolOf(const ToolEntry& entry, const CuttingTool& holder);

/// Where a tool is: its tip (mm) and its unit axis from the tip towards the spindle.
struct ToolPose {
  std::array<double, 3> tip{};
  std::array<double, 3> axis{0.0, 0.0, 1.0};
};

/// The solid cylinder of radius `radius` whose axis runs from `from` a length `length` along the
/// unit vector `axis`, with flat ends.
struct SolidCylinder {
  std::array<double, 3> from{};
  std::array<double, 3> axis{0.0, 0.0, 1.0};
  double length = 0.0;
  double radius = 0.0;
};

/// The lowest z of `c` on the vertical line through (x, y), or +infinity when the line misses
/// it. Exact: the line's interval inside the infinite cylinder (a quadratic in z) cut by the slab
/// of the two end planes.
[[nodiscard]] double lowestZ(const SolidCylinder& c, double x, double y);

/// The cutting part of `tool` at `pose`: for a flat end one cylinder from the tip; for a ball the
/// ball (centre one radius up the axis) and the cylinder from its centre to the gauge line.
struct ToolSolid {
  SolidCylinder body;
  bool ball = false;
  std::array<double, 3> ball_centre{};
  double ball_radius = 0.0;
  SolidCylinder holder;  ///< from the gauge line upwards
  /// The lowest z of the cutting part on the vertical line through (x, y) (+inf: missed).
  [[nodiscard]] double cutterZ(double x, double y) const;
  /// The lowest z of the holder on that line (+inf: missed).
  [[nodiscard]] double holderZ(double x, double y) const { return lowestZ(holder, x, y); }
  /// The XY box (min x, min y, max x, max y) that holds the cutting part, or with `with_holder`
  /// the holder too.
  [[nodiscard]] std::array<double, 4> footprint(bool with_holder) const;
  /// The lowest z of the cutting part anywhere.
  [[nodiscard]] double bottom() const;
  /// The lowest z of the holder anywhere.
  [[nodiscard]] double holderBottom() const;
};

/// The solid of `tool` at `pose` (pose.axis of unit length).
[[nodiscard]] ToolSolid toolSolid(const CuttingTool& tool, const ToolPose& pose);

}  // namespace pkm::cnc
