// pkm.gcode.moves: `pkm gcode moves` as arrays (workflow::runGcodeMoves). The workflow writes the
// moves CSV the command prints; io::TextTable reads it back into the arrays, so they hold exactly
// the printed values and the rules of the columns (machine coordinates, arc centres, feeds) stay
// in the library.
#include <fmt/format.h>
#include <pybind11/stl.h>

#include <array>
#include <limits>
#include <optional>
#include <string>

#include "columns.hpp"
#include "common.hpp"
#include "gcode_program.hpp"
#include "paths.hpp"
#include "pkm/cnc/interpreter.hpp"
#include "pkm/cnc/move.hpp"
#include "pkm/io/text_table.hpp"
#include "pkm/workflow/gcode_moves.hpp"
#include "simulation.hpp"

namespace pkm::python {

void exposeGcodeRun(py::module_& g);         // gcode_run.cpp
void exposeGcodeTransforms(py::module_& g);  // gcode_transform.cpp
void exposeGcodeMake(py::module_& g);        // gcode_make.cpp

namespace {

/// pkm.gcode.Moves.
struct Moves {
  py::object line, kind, position, center, turns, plane, feed;
  workflow::GcodeMovesResult result;
};

/// Fills `out` (rows × cols, row-major) from the columns `names` of `t`; empty fields are NaN.
void fillColumns(const io::TextTable& t,
                 std::initializer_list<std::string_view> names,
                 double* out) {
  std::vector<std::size_t> cols;
  for (const std::string_view n : names) cols.push_back(t.column({n}));
  const std::size_t k = cols.size();
  for (std::size_t r = 0; r < t.rows(); ++r)
    for (std::size_t c = 0; c < k; ++c)
      out[r * k + c] = t.text(r, cols[c]).empty() ? std::numeric_limits<double>::quiet_NaN()
                                                  : t.number(r, cols[c]);
}

Moves movesOf(workflow::GcodeMovesResult result, const std::string& name) {
  const io::TextTable t = io::TextTable::parse(result.csv, name);
  const auto n = static_cast<py::ssize_t>(t.rows());
  Moves m;
  py::array_t<std::int64_t> line(n);
  py::array_t<double> position = newArray(n, 6), center = newArray(n, 3), turns = newArray(n),
                      feed = newArray(n);
  {
    py::gil_scoped_release release;
    const std::size_t line_col = t.column({"line"});
    std::int64_t* l = line.mutable_data();
    for (std::size_t r = 0; r < t.rows(); ++r) l[r] = t.integer(r, line_col);
    fillColumns(t, {"x", "y", "z", "a", "b", "c"}, position.mutable_data());
    fillColumns(t, {"cx", "cy", "cz"}, center.mutable_data());
    fillColumns(t, {"turns"}, turns.mutable_data());
    fillColumns(t, {"feed"}, feed.mutable_data());
  }
  m.line = line;
  m.kind = columnOf(t, t.column({"kind"}));
  m.plane = columnOf(t, t.column({"plane"}));
  m.position = position;
  m.center = center;
  m.turns = turns;
  m.feed = feed;
  m.result = std::move(result);
  return m;
}

Moves moves(const py::object& program,
            const py::object& tool_table,
            const std::string& tool_units,
            bool block_delete,
            std::uint64_t max_iterations,
            const py::object& ini,
            const std::optional<std::string>& name) {
  workflow::GcodeMovesRequest r;
  r.interpreter = interpreterOf(tool_table, tool_units, block_delete, max_iterations);
  r.interpreter.ini = optionalPath(ini, "ini");
  r.validate();  // option errors before the program is read, as the command
  r.program = programOf(program, name);
  workflow::GcodeMovesResult result;
  {
    py::gil_scoped_release release;
    result = workflow::runGcodeMoves(r);
  }
  return movesOf(std::move(result), r.program.name);
}

/// Registers pkm.gcode.Moves in `g`.
void defMovesClass(py::module_& g) {
  py::class_<Moves>(g,
                    "Moves",
                    "The motions of a program, one row per motion as `pkm gcode moves` prints "
                    "them (docs/gcode.md \"The moves CSV\"), in machine coordinates: G5x, G92 and "
                    "tool length offsets applied; mm and degrees whatever G20/G21 says.")
      .def_readonly("line", &Moves::line, "(N,) int64: 1-based source line of each motion.")
      .def_readonly("kind", &Moves::kind, "(N,) str: 'rapid', 'linear' or 'arc'.")
      .def_readonly("position",
                    &Moves::position,
                    "(N, 6) float64: end point x, y, z (mm), a, b, c (degrees), machine "
                    "coordinates.")
      .def_readonly("center",
                    &Moves::center,
                    "(N, 3) float64: arc centre cx, cy, cz (mm, machine coordinates); NaN for "
                    "lines and along the plane normal.")
      .def_readonly("turns",
                    &Moves::turns,
                    "(N,) float64: signed turns (G2 negative, G3 positive; 0 for lines).")
      .def_readonly("plane", &Moves::plane, "(N,) str: 'XY', 'XZ' or 'YZ'.")
      .def_readonly("feed",
                    &Moves::feed,
                    "(N,) float64: feed, mm/min (NaN for rapids; G93: the equivalent rate).")
      .def_property_readonly(
          "lines", [](const Moves& x) { return x.result.lines; }, "Source lines read.")
      .def_property_readonly(
          "blocks",
          [](const Moves& x) { return x.result.blocks; },
          "Blocks executed (loops counted per pass).")
      .def_property_readonly(
          "ended_by_m2",
          [](const Moves& x) { return x.result.ended_by_m2; },
          "The program ended with M2 or M30.")
      .def_property_readonly(
          "note",
          [](const Moves& x) { return x.result.note; },
          "The command's note line (counts of lines, blocks and moves).")
      .def_property_readonly(
          "csv",
          [](const Moves& x) { return x.result.csv; },
          "The CSV text `pkm gcode moves` prints for the program.")
      .def("__len__", [](const Moves& x) { return x.result.moves; })
      .def("__repr__",
           [](const Moves& x) { return fmt::format("<pkm.gcode.Moves: {}>", x.result.note); });
}

}  // namespace

void exposeGcode(py::module_& m) {
  py::module_ g = m.def_submodule(
      "gcode",
      "RS274NGC (LinuxCNC 2.9) G-code programs: the interpreted moves, runs on a hexapod or an "
      "Exechon, compensated and flattened programs (`pkm gcode moves|run|compensate|flatten`, "
      "docs/gcode.md).");
  defMovesClass(g);

  g.def("moves",
        &moves,
        py::arg("program"),
        py::kw_only(),
        py::arg("tool_table") = py::none(),
        py::arg("tool_units") = "mm",
        py::arg("block_delete") = false,
        py::arg("max_iterations") = cnc::InterpreterOptions{}.max_loop_iterations,
        py::arg("ini") = py::none(),
        py::arg("name") = py::none(),
        R"doc(Interprets a program with LinuxCNC semantics, as `pkm gcode moves PROGRAM`.

Parameters
----------
program : str or os.PathLike
    A G-code file (an os.PathLike, an existing file's name, or a name ending in .ngc, .nc, .tap
    or .gcode) or the program's text (a str with a newline, or not naming a file).
tool_table : str or os.PathLike, optional
    A LinuxCNC tool table (.tbl) for G43 and M6 (--tool-table).
tool_units : {"mm", "inch"}, default "mm"
    The tool table's length unit (--tool-units).
block_delete : bool, default False
    Skip lines starting with '/' (--block-delete).
max_iterations : int, default 10_000_000
    Iterations one loop may make before the program is rejected as runaway.
ini : str or os.PathLike, optional
    A LinuxCNC INI whose [RS274NGC] section sets the interpreter up, as rs274 -i does (--ini):
    start-up code, arc tolerances, parameter file, sub-file path, #<_ini[...]> values.
name : str, optional
    The program's name in messages (default: its path, or "program" for a text).

Returns
-------
Moves
    line, kind, position (N, 6), center (N, 3), turns, plane, feed; lines, blocks, ended_by_m2,
    note and csv (the command's output).

Raises
------
ValueError
    A line the interpreter rejects ("NAME:LINE: message", pkm's message), a missing file, or a
    bad option.)doc");
  exposeGcodeRun(g);
  exposeGcodeTransforms(g);
  exposeGcodeMake(g);
}

}  // namespace pkm::python
