// pkm.gcode.compensate and pkm.gcode.flatten: `pkm gcode compensate` and `pkm gcode flatten`
// (workflow::compensateGcode, workflow::flattenGcode) on a program's text or file, returning the
// output program's text, byte for byte what the command prints, and a report dict (the command's
// note line and the counts).
#include <pybind11/stl.h>

#include <cstdint>
#include <optional>
#include <string>
#include <utility>

#include "common.hpp"
#include "gcode_program.hpp"
#include "machines.hpp"
#include "paths.hpp"
#include "pkm/cnc/interpreter.hpp"
#include "pkm/workflow/gcode_compensate.hpp"
#include "pkm/workflow/gcode_flatten.hpp"

namespace pkm::python {
namespace {

/// (N, 6) x, y, z (mm), a, b, c (degrees) of the compensated points, `desired` or command.
py::array_t<double> pointsArray(const cnc::ProgramCompensation& c, bool desired) {
  py::array_t<double> out = newArray(static_cast<py::ssize_t>(c.points.size()), 6);
  double* p = out.mutable_data();
  for (const cnc::CompensatedPoint& q : c.points) {
    const cnc::Axes& a = desired ? q.desired : q.command;
    for (const double v : a) *p++ = v;
  }
  return out;
}

py::tuple compensate(const py::object& program,
                     const py::object& machine,
                     const py::object& nominal,
                     const py::object& hybrid_frame,
                     std::optional<double> x2,
                     bool base_frame_not_in_controller,
                     const py::object& ini,
                     const std::optional<std::string>& orientation,
                     std::optional<double> tolerance,
                     std::size_t max_points,
                     const py::object& tool_table,
                     const std::string& tool_units,
                     const py::object& out,
                     bool force,
                     const std::optional<std::string>& name) {
  workflow::GcodeCompensateRequest q;
  if (py::isinstance<Hexapod>(machine))
    q.hexapod = machine.cast<const Hexapod&>().machine;
  else if (py::isinstance<Exechon>(machine))
    q.exechon = machine.cast<const Exechon&>().machine;
  else
    q.machine = optionalPath(machine, "machine (a pkm.Hexapod, a pkm.Exechon, a name or a file)");
  q.nominal = optionalPath(nominal, "nominal");
  q.hybrid_frame = optionalPath(hybrid_frame, "hybrid_frame");
  q.x2 = x2;
  q.frame_not_in_controller = base_frame_not_in_controller;
  q.ini = optionalPath(ini, "ini");
  q.orientation = orientation;
  q.tolerance = tolerance;
  q.max_points = max_points;
  q.interpreter.tool_table = optionalPath(tool_table, "tool_table");
  q.interpreter.tool_units = tool_units;
  q.out = optionalPath(out, "out");
  q.force = force;
  q.validate();  // option errors before the program is read, as the command
  q.program = programOf(program, name);
  workflow::GcodeCompensateResult r;
  {
    py::gil_scoped_release release;
    r = workflow::compensateGcode(q);
  }
  const cnc::ProgramCompensation& c = r.compensation;
  py::dict report;
  report["note"] = r.note;
  report["motion_lines"] = c.motion_lines;
  report["added_lines"] = c.added_lines;
  report["offset_lines"] = c.offset_lines;
  report["max_correction"] = c.max_correction;
  report["flattened_blocks"] = c.flattened_blocks;
  py::array_t<std::int64_t> line(static_cast<py::ssize_t>(c.points.size()));
  for (std::size_t i = 0; i < c.points.size(); ++i)
    line.mutable_data()[i] = static_cast<std::int64_t>(c.points[i].line);
  report["line"] = line;
  report["desired"] = pointsArray(c, true);
  report["command"] = pointsArray(c, false);
  return py::make_tuple(c.text, report);
}

py::tuple flatten(const py::object& program,
                  const py::object& tool_table,
                  const std::string& tool_units,
                  bool block_delete,
                  std::uint64_t max_iterations,
                  const py::object& ini,
                  const py::object& out,
                  bool force,
                  const std::optional<std::string>& name) {
  workflow::GcodeFlattenRequest q;
  q.interpreter = interpreterOf(tool_table, tool_units, block_delete, max_iterations);
  q.interpreter.ini = optionalPath(ini, "ini");
  q.out = optionalPath(out, "out");
  q.force = force;
  q.validate();  // option errors before the program is read, as the command
  q.program = programOf(program, name);
  workflow::GcodeFlattenResult r;
  {
    py::gil_scoped_release release;
    r = workflow::flattenGcode(q);
  }
  py::dict report;
  report["note"] = r.note;
  report["blocks"] = r.flat.blocks;
  report["had_o_words"] = r.flat.had_o_words;
  py::array_t<std::int64_t> source(static_cast<py::ssize_t>(r.flat.source_line.size()));
  for (std::size_t i = 0; i < r.flat.source_line.size(); ++i)
    source.mutable_data()[i] = static_cast<std::int64_t>(r.flat.source_line[i]);
  report["source_line"] = source;
  return py::make_tuple(r.flat.text, report);
}

constexpr const char* kCompensateDoc = R"doc(Pre-distorts a program, as `pkm gcode compensate`.

For a controller that keeps the nominal kinematics of a calibrated hexapod or Exechon
(X_cmd = FK_nominal(IK_calibrated(X)), docs/compensation.md), or, with hybrid_frame and x2,
the hybrid machine's X2-Y2 squareness corrected in a PKM program (docs/gcode.md).

Parameters
----------
program : str or os.PathLike
    A G-code file or the program's text (as pkm.gcode.moves).
machine : Hexapod, Exechon, str or os.PathLike, optional
    The calibrated hexapod or Exechon machine: a loaded one (a calibration's result.machine,
    pkm.load_machine), or a file (`pkm calibrate ... --out`, result.save()).
nominal : str or os.PathLike, optional
    The controller's nominal machine (default: the built-in one the calibrated machine's name
    refers to, its name without "-calibrated").
hybrid_frame : str or os.PathLike, optional
    Hybrid machine: pkm-base-frame.txt of a campaign (instead of machine).
x2 : float, optional
    Hybrid machine: the X2 position the program runs at, mm.
base_frame_not_in_controller : bool
    Hybrid machine: also apply the base frame's rotation and offset in the program.
ini : str or os.PathLike, optional
    Hexapod: the LinuxCNC INI the program runs under (its RS274NGC_STARTUP_CODE runs first).
orientation : {"vector", "axes"}, optional
    Exechon: A/C as the tool vector (default) or the wrist readings.
tolerance : float, optional
    Chordal tolerance in the machine's length unit (default 0.01 mm).
max_points : int
    Most interpolated points the program may need.
tool_table, tool_units
    A LinuxCNC tool table for G43 H and its unit ("mm" or "inch").
out, force
    Also write the program to this file (refused when it exists unless force).
name : str, optional
    The program's name in messages.

Returns
-------
(str, dict)
    The compensated program, byte for byte what the command prints, and a report: note (the
    command's note line), motion_lines, added_lines, offset_lines, max_correction (mm),
    flattened_blocks, and per commanded point line (source line), desired and command
    ((N, 6) x, y, z in mm, a, b, c in degrees, the program's frame).

Raises
------
ValueError
    With pkm's message ("NAME:LINE: message" for a line the compensation rejects), for a bad
    option, an unreadable machine or program, or an existing out without force.)doc";

constexpr const char* kFlattenDoc = R"doc(Flattens a program, as `pkm gcode flatten`.

The blocks the program executes, in execution order, with every expression evaluated and no
O-word statements (subroutines, loops and conditions unrolled; docs/gcode.md).

Parameters
----------
program : str or os.PathLike
    A G-code file or the program's text (as pkm.gcode.moves).
tool_table, tool_units, block_delete, max_iterations, ini
    As pkm.gcode.moves.
out, force
    Also write the program to this file (refused when it exists unless force).
name : str, optional
    The program's name in messages.

Returns
-------
(str, dict)
    The flattened program, byte for byte what the command prints, and a report: note (the
    command's note line), blocks (executed blocks written), had_o_words, and source_line
    (the 1-based source line of each output line).

Raises
------
ValueError
    With pkm's message ("NAME:LINE: message") for a line the interpreter rejects, a missing
    file, a bad option or an existing out without force.)doc";

}  // namespace

void exposeGcodeTransforms(py::module_& g) {
  g.def("compensate",
        &compensate,
        py::arg("program"),
        py::kw_only(),
        py::arg("machine") = py::none(),
        py::arg("nominal") = py::none(),
        py::arg("hybrid_frame") = py::none(),
        py::arg("x2") = py::none(),
        py::arg("base_frame_not_in_controller") = false,
        py::arg("ini") = py::none(),
        py::arg("orientation") = py::none(),
        py::arg("tolerance") = py::none(),
        py::arg("max_points") = cnc::kDefaultMaxPathPoints,
        py::arg("tool_table") = py::none(),
        py::arg("tool_units") = "mm",
        py::arg("out") = py::none(),
        py::arg("force") = false,
        py::arg("name") = py::none(),
        kCompensateDoc);
  g.def("flatten",
        &flatten,
        py::arg("program"),
        py::kw_only(),
        py::arg("tool_table") = py::none(),
        py::arg("tool_units") = "mm",
        py::arg("block_delete") = false,
        py::arg("max_iterations") = cnc::InterpreterOptions{}.max_loop_iterations,
        py::arg("ini") = py::none(),
        py::arg("out") = py::none(),
        py::arg("force") = false,
        py::arg("name") = py::none(),
        kFlattenDoc);
}

}  // namespace pkm::python
