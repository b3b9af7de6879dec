/// @file
/// @brief The composite machining commands of the graphic programming (Lee et al., "Development
/// of a Parallel-Typed CNC Machine": lines, arcs, conditions and sphere machining as icons) as
/// G-code: a hemisphere finished with a ball-end tool, a circular pocket, a drilling pattern on a
/// circle, a face-milling zig-zag. One definition for every front end: `pkm gcode make`, the web
/// page's composite blocks (POST /api/gcode/shape) and Python's `pkm.gcode.make`
/// (docs/gcode.md "gcode make").
#pragma once

#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace pkm::cnc {

/// One parameter of a shape: its name, its default and what it means (with its unit).
struct ShapeParameter {
  std::string name;
  double value = 0.0;
  std::string meaning;
};

/// A shape and the values given for its parameters (the others take their defaults).
struct ShapeSpec {
  std::string kind;  ///< "sphere", "pocket", "drill" or "face"
  std::map<std::string, double> values;
};

/// The most lines a shape may make (a 1 µm step-over over a metre is refused, not generated).
inline constexpr std::size_t kMaxShapeLines = 200'000;

/// The shapes' names, in the order of the page's palette.
[[nodiscard]] const std::vector<std::string>& shapeKinds();

/// The parameters of `kind` with their defaults. Throws pkm::InvalidArgument naming the known
/// kinds for another.
[[nodiscard]] const std::vector<ShapeParameter>& shapeParameters(std::string_view kind);

/// The G-code lines of `spec`: plain moves in absolute mm (the caller sets G21 G90 and a feed);
/// G17 is active after them. The programmed point is the tool tip.
/// - sphere: the hemisphere of `radius` about (x, y, z) finished with a ball of `tool_radius`:
///   from above the equator down to it, then `levels` full circles (G17 G3), each level reached
///   from the one below along the meridian (G18 G2 about the tool-centre sphere, so no feed cuts
///   into the sphere), the last arc ending at the pole, and a retract 5 mm above the pole.
/// - pocket: circles of growing radius (by `stepover`, up to `radius` for the tool centre) at
///   each depth (by `stepdown`, down to `depth` below `top`), from the centre.
/// - drill: `holes` holes equally spaced on the circle of `radius` about (x, y), `depth` below
///   `top`, each a rapid 2 mm above, a feed down and a rapid up.
/// - face: a zig-zag at height `z` over [x0, x1] × [y0, y1], rows `step` apart.
/// Throws pkm::InvalidArgument naming the parameter for an unknown name, a non-finite value, a
/// size that must be > 0, a count that is not a whole number in range, and for more than
/// kMaxShapeLines lines.
[[nodiscard]] std::vector<std::string> shapeLines(const ShapeSpec& spec);

/// A whole program of `spec`: "G21 G90 G17 F<feed> (pkm gcode make KIND)", the shape, "M2"
/// (lines end with '\n'). Throws as shapeLines, and for a feed not > 0.
[[nodiscard]] std::string shapeProgram(const ShapeSpec& spec, double feed = 600.0);

}  // namespace pkm::cnc
