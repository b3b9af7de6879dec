// pkm.calibration.plan_poses: `pkm plan-poses` (workflow::planPoses) with the chosen poses as
// arrays, the plan's figures as attributes and its documents (JSON, CSV, summary, G-code).
#include <pybind11/stl.h>

#include <optional>

#include "calibration.hpp"
#include "machines.hpp"
#include "paths.hpp"
#include "pkm/core/units.hpp"
#include "pkm/io/pose_plan_report.hpp"
#include "pkm/workflow/plan_poses.hpp"

namespace pkm::python {
namespace {

/// The result of a pose plan: attributes and the documents the workflow produced.
struct PosePlanResult {
  py::dict attributes;
  std::string json, csv, summary, gcode;
};

/// The chosen poses: hexapod (N, 6) x, y, z, a, b, c (degrees); Exechon (N, 6) x, y, z, i, j, k.
py::array_t<double> posesOf(const io::PosePlanReport& r) {
  const bool hexapod = r.kind == "hexapod";
  const std::size_t n = hexapod ? r.poses.size() : r.points.size();
  py::array_t<double> out = newArray(static_cast<py::ssize_t>(n), 6);
  double* p = out.mutable_data();
  for (std::size_t i = 0; i < n; ++i, p += 6) {
    if (hexapod) {
      for (int k = 0; k < 3; ++k) {
        p[k] = r.poses[i].position(k);
        p[3 + k] = radToDeg(r.poses[i].rpy(k));
      }
    } else {
      for (int k = 0; k < 3; ++k) {
        p[k] = r.points[i].position(k);
        p[3 + k] = r.points[i].direction(k);
      }
    }
  }
  return out;
}

/// Exechon: the program's moves (home first) as (N + 1, 5) x, y, z, a, c (a, c in degrees).
py::object planMovesOf(const io::PosePlanReport& r) {
  if (r.kind == "hexapod") return py::none();
  py::array_t<double> out = newArray(static_cast<py::ssize_t>(r.moves.size()), 5);
  double* p = out.mutable_data();
  for (const io::ExechonPlanMove& m : r.moves) {
    for (int k = 0; k < 3; ++k) *p++ = m.tool_point(k);
    *p++ = radToDeg(m.a);
    *p++ = radToDeg(m.c);
  }
  return std::move(out);
}

PosePlanResult planPoses(const py::object& machine,
                         int count,
                         const std::string& index,
                         const std::optional<std::string>& measurement,
                         int candidates,
                         std::uint64_t seed,
                         double reach,
                         double tilt,
                         const std::optional<double>& feed,
                         const std::optional<std::vector<double>>& target_offset,
                         const py::object& gcode,
                         bool force) {
  workflow::PlanPosesRequest r;
  if (py::isinstance<Hexapod>(machine))
    r.hexapod = machine.cast<const Hexapod&>().machine;
  else if (py::isinstance<Exechon>(machine))
    r.exechon = machine.cast<const Exechon&>().machine;
  else
    r.machine = pathOf(machine, "machine (a pkm.Hexapod, a pkm.Exechon, a name or a file)");
  r.count = count;
  r.index = index;
  r.measurement = measurement.value_or("");
  r.candidates = candidates;
  r.seed = seed;
  r.reach = reach;
  r.tilt_deg = tilt;
  r.feed = feed;
  if (target_offset) r.target_offset = *target_offset;
  if (!gcode.is_none()) r.gcode = pathOf(gcode, "gcode");
  r.force = force;
  workflow::PlanPosesResult res;
  {
    py::gil_scoped_release release;
    res = workflow::planPoses(r);
  }
  const io::PosePlanReport& rep = res.report;
  PosePlanResult out{{}, io::posePlanJson(rep), res.csv, res.summary, res.gcode};
  py::dict& a = out.attributes;
  a["kind"] = rep.kind;
  a["machine"] = rep.machine;
  a["poses"] = posesOf(rep);
  a["moves"] = planMovesOf(rep);
  a["chosen"] =
      py::array_t<int>(static_cast<py::ssize_t>(rep.plan.chosen.size()), rep.plan.chosen.data());
  a["index"] = rep.index_label;
  a["index_value"] = rep.plan.index_value;
  a["indices"] = py::array_t<double>(static_cast<py::ssize_t>(rep.plan.indices.size()),
                                     rep.plan.indices.data());
  a["random_baseline"] = rep.plan.random_baseline;
  a["condition_number"] = rep.plan.condition_number;
  a["rank"] = rep.plan.rank;
  a["swaps"] = rep.plan.swaps;
  a["candidates"] = rep.candidates;
  a["parameters"] = rep.parameters;
  a["feed"] = rep.feed;
  return out;
}

/// Registers pkm.calibration.PosePlan in `m`.
void defPosePlanClass(py::module_& m) {
  py::class_<PosePlanResult>(m, "PosePlan", R"doc(A calibration pose plan (`pkm plan-poses`).

Attributes
----------
poses : ndarray (N, 6)
    The chosen poses in order: hexapod x, y, z (machine unit), a, b, c (degrees, roll-pitch-yaw);
    Exechon tool points x, y, z and unit tool directions i, j, k (world frame).
moves : ndarray (N + 1, 5) or None
    Exechon: the program's moves, home first: tool point x, y, z and wrist readings a, c (deg).
chosen : ndarray of int
    Indices of the chosen poses among the random candidates.
index, index_value, indices, random_baseline, condition_number, rank, swaps
    The maximised observability index (name, value), all five O1..O5, the mean of random
    choices of the same size, the condition number and rank of the chosen set, exchanges made.
kind, machine, candidates, parameters, feed
    "hexapod" or "exechon", the machine's name, candidates drawn, parameters identified, the
    program's feed rate (machine unit per minute).
csv, summary, gcode : str
    The CSV `pkm plan-poses` prints, its summary line, the program ("" without gcode=).)doc")
      .def("__getattr__",
           [](const PosePlanResult& r, const std::string& name) -> py::object {
             if (!r.attributes.contains(name))
               throw py::attribute_error("PosePlan has no attribute '" + name + "'");
             return r.attributes[py::str(name)];
           })
      .def_readonly("csv", &PosePlanResult::csv)
      .def_readonly("summary", &PosePlanResult::summary)
      .def_readonly("gcode", &PosePlanResult::gcode)
      .def(
          "to_dict",
          [](const PosePlanResult& r) { return jsonLoads(r.json); },
          "The plan as the JSON document of io::posePlanJson.")
      .def("__repr__",
           [](const PosePlanResult& r) { return "<pkm.calibration.PosePlan " + r.summary + ">"; });
}

}  // namespace

void exposePosePlanning(py::module_& m) {
  defPosePlanClass(m);
  m.def("plan_poses",
        &planPoses,
        py::arg("machine") = "default",
        py::kw_only(),
        py::arg("count") = 30,
        py::arg("index") = "O1",
        py::arg("measurement") = py::none(),
        py::arg("candidates") = 1000,
        py::arg("seed") = 1,
        py::arg("reach") = 0.0,
        py::arg("tilt") = 10.0,
        py::arg("feed") = py::none(),
        py::arg("target_offset") = py::none(),
        py::arg("gcode") = py::none(),
        py::arg("force") = false,
        R"doc(Chooses calibration poses maximising an observability index: `pkm plan-poses`.

Parameters
----------
machine : Hexapod, Exechon, str or os.PathLike, default "default"
    A loaded machine (pkm.load_machine, a calibration's result.machine, possibly with a changed
    geometry), a built-in name or a machine file (hexapod or Exechon: the type chooses the
    planner).
count : int
    Poses to choose (>= 1).
index : {"O1", "O2", "O3", "O4", "O5"}
    Observability index (Sun & Hollerbach): O1 D-optimal ... O5 A-optimal.
measurement : {"pose", "point"}, optional
    Hexapod: 6-DOF poses (default) or tracker points; Exechon: points only.
candidates, seed : int
    Random workspace candidates (>= count) and their random seed.
reach : float
    Half-range of x, y, z about home, machine unit (0: the planner's default).
tilt : float
    Degrees: hexapod, half-range of a, b, c about home; Exechon, the largest tool tilt.
feed : float, optional
    G-code feed rate, machine unit per minute (default: 1000 or lower to respect joint speeds).
target_offset : sequence of 3 float, optional
    Exechon: the tracker target in the tool frame.
gcode, force : str, bool
    Also write the program (refused when it exists unless force).

Returns
-------
PosePlan

Raises
------
ValueError
    For a bad request, with pkm's message.)doc");
}

}  // namespace pkm::python
