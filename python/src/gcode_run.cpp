// pkm.gcode.run: `pkm gcode run` on numpy (workflow::runGcode): the interpolated joint path as
// arrays (GcodeRunResult::path) and the check report as the dict of `--report` (io::gcodeRunJson).
#include "pkm/workflow/gcode_run.hpp"

#include <fmt/format.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "common.hpp"
#include "gcode_program.hpp"
#include "machines.hpp"
#include "paths.hpp"
#include "pkm/cnc/interpreter.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/gcode_run_report.hpp"

namespace pkm::python {
namespace {

/// pkm.gcode.Run.
struct Run {
  py::object t, line, index, pose, joints;
  py::object report;    ///< the --report document as a dict
  py::list violations;  ///< the first max_violations violations of each check, as dicts
  std::vector<std::string> notes;
  workflow::GcodeRunResult result;
};

/// The path's arrays (copied once out of the workflow's vectors).
void pathArrays(const workflow::GcodeRunPath& p, Run& run) {
  const auto n = static_cast<py::ssize_t>(p.t.size());
  const auto k = static_cast<py::ssize_t>(p.joints.size());
  py::array_t<double> t = newArray(n), pose = newArray(n, 6);
  py::array_t<double> joints(std::vector<py::ssize_t>{n, k});  // (0, 0) without a path
  py::array_t<std::int64_t> line(n), index(n);
  {
    py::gil_scoped_release release;
    double* tp = t.mutable_data();
    double* pp = pose.mutable_data();
    double* jp = joints.mutable_data();
    std::int64_t* lp = line.mutable_data();
    std::int64_t* ip = index.mutable_data();
    for (std::size_t i = 0; i < p.t.size(); ++i) {
      tp[i] = p.t[i];
      lp[i] = static_cast<std::int64_t>(p.line[i]);
      ip[i] = static_cast<std::int64_t>(p.index[i]);
      for (std::size_t c = 0; c < 6; ++c) pp[6 * i + c] = p.pose[i][c];
      for (std::size_t c = 0; c < p.joints.size(); ++c)
        jp[static_cast<std::size_t>(k) * i + c] = p.q[i][c];
    }
  }
  run.t = t;
  run.pose = pose;
  run.joints = joints;
  run.line = line;
  run.index = index;
}

/// The violations of a run as dicts (check, line, position, item, value, limit, margin, unit).
py::list violationsOf(const std::vector<workflow::GcodeRunViolation>& list) {
  py::list out;
  for (const workflow::GcodeRunViolation& v : list) {
    py::dict d;
    d["check"] = v.check;
    d["line"] = v.event.line;
    py::array_t<double> position = newArray(6);
    std::copy(v.event.position.begin(), v.event.position.end(), position.mutable_data());
    d["position"] = position;
    d["item"] = v.event.item;
    d["value"] = v.event.value;
    d["limit"] = v.event.limit;
    d["margin"] = v.event.margin;
    d["unit"] = v.event.unit;
    out.append(d);
  }
  return out;
}

/// Raises pkm.LimitError naming every violated check and its first violation.
void raiseOnViolation(const io::GcodeRunReport& r) {
  std::string message;
  for (const io::GcodeCheckSummary& c : r.checks)
    if (c.violations > 0)
      message += fmt::format("{}{}:{}: {} violated ({} points), first at {}: {} margin {}",
                             message.empty() ? "" : "; ",
                             r.program,
                             c.first.line,
                             c.name,
                             c.violations,
                             c.first.item,
                             c.first.value,
                             c.first.margin);
  PyErr_SetString(limitError().ptr(), message.c_str());
  throw py::error_already_set();
}

/// The machine argument: a loaded pkm.Hexapod or pkm.Exechon, or a name or path.
void machineOf(const py::object& machine, workflow::GcodeRunRequest& q) {
  if (py::isinstance<Hexapod>(machine))
    q.hexapod = machine.cast<const Hexapod&>().machine;
  else if (py::isinstance<Exechon>(machine))
    q.exechon = machine.cast<const Exechon&>().machine;
  else
    q.machine = pathOf(machine, "machine (a pkm.Hexapod, a pkm.Exechon, a name or a file)");
}

Run run(const py::object& machine,
        const py::object& program,
        std::optional<double> tolerance,
        std::optional<double> strut_diameter,
        const py::object& ini,
        std::optional<double> max_joint_velocity,
        std::optional<double> max_joint_acceleration,
        std::optional<double> max_wrist_velocity,
        std::optional<double> max_wrist_acceleration,
        std::optional<double> rapid_rate,
        const std::string& orientation,
        const py::object& tool_table,
        const std::string& tool_units,
        bool block_delete,
        std::uint64_t max_iterations,
        std::size_t max_points,
        std::optional<std::size_t> path_points,
        std::size_t max_violations,
        const py::object& out,
        const py::object& report,
        bool force,
        const std::optional<std::string>& name,
        bool raise_on_violation) {
  workflow::GcodeRunRequest q;
  machineOf(machine, q);
  q.ini = optionalPath(ini, "ini");
  q.tolerance = tolerance;
  q.strut_diameter = strut_diameter;
  q.max_joint_velocity = max_joint_velocity;
  q.max_joint_acceleration = max_joint_acceleration;
  q.max_wrist_velocity = max_wrist_velocity;
  q.max_wrist_acceleration = max_wrist_acceleration;
  q.rapid_rate = rapid_rate;
  q.orientation = orientation;
  q.interpreter = interpreterOf(tool_table, tool_units, block_delete, max_iterations);
  q.max_points = max_points;
  q.path_points = path_points.value_or(std::numeric_limits<std::size_t>::max());
  q.max_violations = max_violations;
  q.out = optionalPath(out, "out");
  q.report = optionalPath(report, "report");
  q.force = force;
  q.validate();  // option errors before the program is read, as the command
  q.program = programOf(program, name);
  Run r;
  workflow::RunControl control;
  control.notice = [&r](const std::string& n) { r.notes.push_back(n); };
  {
    py::gil_scoped_release release;
    r.result = workflow::runGcode(q, control);
  }
  if (raise_on_violation && !r.result.ok()) raiseOnViolation(r.result.report);
  pathArrays(r.result.path, r);
  r.violations = violationsOf(r.result.violations);
  r.report = jsonLoads(io::gcodeRunJson(r.result.report));
  return r;
}

/// Registers pkm.gcode.Run in `g`.
void defGcodeRunClass(py::module_& g) {
  py::class_<Run>(g,
                  "Run",
                  "A program run on a machine (`pkm gcode run`): the interpolated path in joint "
                  "space with its times, and the check report.")
      .def_readonly("t", &Run::t, "(M,) float64: arrival time at each path point, s.")
      .def_readonly("line", &Run::line, "(M,) int64: the program line of each point.")
      .def_readonly("index",
                    &Run::index,
                    "(M,) int64: each point's index in the full path (all points unless "
                    "path_points decimated it).")
      .def_readonly("pose",
                    &Run::pose,
                    "(M, 6) float64: machine position x, y, z (mm), a, b, c (degrees): the TCP "
                    "pose of the platform in the work frame (hexapod) or the tool point and the "
                    "A/C words (Exechon).")
      .def_readonly("joints",
                    &Run::joints,
                    "(M, J) float64: the joint values, in joint_units: a hexapod's six strut "
                    "readings (machine length unit), an Exechon's three leg readings and wrist "
                    "C, A (degrees).")
      .def_readonly("report",
                    &Run::report,
                    "dict: the check report, the JSON document of `pkm gcode run --report` "
                    "(checks.NAME.{enabled, violations, unit, worst, first_violation}, "
                    "cycle_time_s, points, ok, ...).")
      .def_readonly("violations",
                    &Run::violations,
                    "list of dict: with max_violations > 0, the first max_violations violated "
                    "points of each check, by check then path order: check, line, position (6,) "
                    "(x, y, z mm, a, b, c deg, machine coordinates), item, value, limit, margin "
                    "(< 0) and unit (report['checks'][name]['violations'] counts them all).")
      .def_readonly("notes",
                    &Run::notes,
                    "list of str: the notices the command prints as 'pkm: note:' (a LinuxCNC "
                    "INI's start-up code, assumptions of the machine reader).")
      .def_property_readonly(
          "joint_names", [](const Run& r) { return r.result.path.joints; }, "Joint names.")
      .def_property_readonly(
          "joint_units",
          [](const Run& r) { return r.result.path.joint_units; },
          "Each joint's unit.")
      .def_property_readonly(
          "total_points",
          [](const Run& r) { return r.result.path.total_points; },
          "Points of the full path.")
      .def_property_readonly(
          "ok", [](const Run& r) { return r.result.ok(); }, "No check violated.")
      .def_property_readonly(
          "text",
          [](const Run& r) { return io::gcodeRunText(r.result.report); },
          "The report as the command prints it.")
      .def("__str__", [](const Run& r) { return io::gcodeRunText(r.result.report); })
      .def("__repr__", [](const Run& r) {
        return fmt::format("<pkm.gcode.Run '{}' on '{}': {} points, cycle time {:.3f} s, {}>",
                           r.result.report.program,
                           r.result.report.machine,
                           r.result.report.points,
                           r.result.report.cycle_time_s,
                           r.result.ok() ? "ok" : "VIOLATED");
      });
}

constexpr const char* kGcodeRunDoc =
    R"doc(Runs a program on a hexapod or an Exechon, as `pkm gcode run PROGRAM --machine M`.

Interprets the program, interpolates every motion within the chordal tolerance, converts each
point to the machine's joints, times the path under the joint rate limits and checks every limit
(reach, stroke, joint angles, interference, conditioning, joint velocity and acceleration;
docs/gcode.md "gcode run"). The GIL is released while it runs.

Parameters
----------
machine : pkm.Hexapod, pkm.Exechon, str or os.PathLike
    A loaded machine (used as it is, also with a changed geometry) or, as --machine, a built-in
    name, a machine file or a LinuxCNC .hal (with `ini`).
program : str or os.PathLike
    A G-code file or the program's text (as pkm.gcode.moves).
tolerance : float, optional
    Chordal tolerance, machine length unit (default 0.01 mm).
strut_diameter : float, optional
    Hexapod: strut diameter for the interference check, machine length unit.
ini : str or os.PathLike, optional
    The LinuxCNC INI of a .hal machine.
max_joint_velocity, max_joint_acceleration : float, optional
    Strut or leg limits, machine length unit/s and /s² (default: the machine file's joint_rates,
    else 200 and 2000).
max_wrist_velocity, max_wrist_acceleration : float, optional
    Exechon wrist C/A limits, deg/s and deg/s² (default: the machine file's, else 180 and 1800).
rapid_rate : float, optional
    G0 path speed, mm/min (default: a LinuxCNC INI's [TRAJ] MAX_LINEAR_VELOCITY, else 10000).
orientation : {"vector", "axes"}, default "vector"
    Exechon: A/C words are the tool vector's angles in the world frame or the wrist readings.
tool_table, tool_units, block_delete, max_iterations
    The interpreter options, as pkm.gcode.moves.
max_points : int, default 10_000_000
    Most interpolated points the program may need (--max-points, bounded memory: about 150 bytes
    per point); a program needing more is refused at the line that crosses the limit.
path_points : int, optional
    Most points of the returned arrays (default: every point; 0: none). A longer path is
    decimated evenly, keeping the ends and every check's worst point; the checks always see
    every point.
max_violations : int, default 0
    Most violations returned per check in `violations` (0: none); the report counts them all.
out : str or os.PathLike, optional
    Also write the joint CSV (--out).
report : str or os.PathLike, optional
    Also write the report's JSON (--report).
force : bool, default False
    Replace existing `out` and `report` files.
name : str, optional
    The program's name in messages and the report (default: its path, or "program").
raise_on_violation : bool, default False
    Raise pkm.LimitError when a check is violated (otherwise see `ok` and `report`).

Returns
-------
Run
    t (M,), line (M,), pose (M, 6), joints (M, J), joint_names, joint_units, report (dict, as
    --report writes it), ok, text (the printed report), violations, notes.

Raises
------
ValueError
    A program line the interpreter rejects ("NAME:LINE: message"), a program needing more than
    `max_points` points, an unknown machine, a bad option or existing files without `force`
    (pkm's messages).
pkm.LimitError
    With raise_on_violation, when a check is violated.)doc";

}  // namespace

void exposeGcodeRun(py::module_& g) {
  defGcodeRunClass(g);

  g.def("run",
        &run,
        py::arg("machine"),
        py::arg("program"),
        py::kw_only(),
        py::arg("tolerance") = py::none(),
        py::arg("strut_diameter") = py::none(),
        py::arg("ini") = py::none(),
        py::arg("max_joint_velocity") = py::none(),
        py::arg("max_joint_acceleration") = py::none(),
        py::arg("max_wrist_velocity") = py::none(),
        py::arg("max_wrist_acceleration") = py::none(),
        py::arg("rapid_rate") = py::none(),
        py::arg("orientation") = "vector",
        py::arg("tool_table") = py::none(),
        py::arg("tool_units") = "mm",
        py::arg("block_delete") = false,
        py::arg("max_iterations") = cnc::InterpreterOptions{}.max_loop_iterations,
        py::arg("max_points") = cnc::kDefaultMaxPathPoints,
        py::arg("path_points") = py::none(),
        py::arg("max_violations") = std::size_t{0},
        py::arg("out") = py::none(),
        py::arg("report") = py::none(),
        py::arg("force") = false,
        py::arg("name") = py::none(),
        py::arg("raise_on_violation") = false,
        kGcodeRunDoc);
}

}  // namespace pkm::python
