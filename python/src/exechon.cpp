// pkm.Exechon: tool pose <-> legs and wrist C, A with the dependent rotational motion, tripod IK
// from wrist points, checks and the DRM circle (exechon_drm_circle.cpp), on numpy arrays (the
// rules of `pkm exechon ik|fk|check|drm`: workflow::ExechonPosePath, ExechonFkPath,
// solveWristPoint).
#include <fmt/format.h>
#include <pybind11/stl.h>

#include <array>
#include <limits>
#include <optional>

#include "common.hpp"
#include "exechon_drm_circle.hpp"
#include "machines.hpp"
#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/workflow/kinematics_path.hpp"

namespace pkm::python {
namespace {

namespace kin = pkm::kinematics;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// The optional (N, 2) x2, y2 array of a hybrid machine; throws for a machine without one.
std::optional<DoubleArray> x2y2Of(const Exechon& e, py::handle obj, py::ssize_t n) {
  if (obj.is_none()) return std::nullopt;
  if (!e.machine->hybrid) throw InvalidArgument("x2y2: needs a machine with a \"hybrid\" section");
  DoubleArray a = rowsOf(obj, 2, "x2y2", false);
  if (a.shape(0) != n)
    throw InvalidArgument(fmt::format("x2y2: {} rows for {} poses", a.shape(0), n));
  return a;
}

std::optional<std::array<double, 2>> rowPair(const std::optional<DoubleArray>& a, py::ssize_t i) {
  if (!a) return std::nullopt;
  return std::array<double, 2>{a->data()[2 * i], a->data()[2 * i + 1]};
}

/// Solves the tool poses along the path; `each` gets the row index and the step.
template <typename Each>
void solvePoses(const Exechon& e,
                const DoubleArray& points,
                const DoubleArray& directions,
                const std::optional<DoubleArray>& x2y2,
                Each&& each) {
  py::gil_scoped_release release;
  workflow::ExechonPosePath path(*e.machine);
  for (py::ssize_t i = 0; i < points.shape(0); ++i) {
    const kin::ExechonToolPose target{Eigen::Vector3d(points.data() + 3 * i),
                                      Eigen::Vector3d(directions.data() + 3 * i)};
    each(i, path.solve(target, rowPair(x2y2, i)));
  }
}

std::pair<DoubleArray, DoubleArray> toolRows(py::handle points, py::handle directions) {
  DoubleArray p = rowsOf(points, 3, "points", true);
  DoubleArray d = rowsOf(directions, 3, "directions", true);
  if (d.shape(0) == 1 && p.shape(0) > 1) {  // one direction for every point
    DoubleArray all(std::vector<py::ssize_t>{p.shape(0), 3});
    for (py::ssize_t i = 0; i < p.shape(0); ++i)
      std::copy_n(d.data(), 3, all.mutable_data() + 3 * i);
    d = all;
  }
  if (d.shape(0) != p.shape(0))
    throw InvalidArgument(fmt::format("directions: {} rows for {} points", d.shape(0), p.shape(0)));
  return {p, d};
}

py::dict exechonIk(
    const Exechon& e, py::handle points, py::handle directions, py::handle x2y2_obj, bool raise) {
  const auto [p, d] = toolRows(points, directions);
  const py::ssize_t n = p.shape(0);
  const std::optional<DoubleArray> x2y2 = x2y2Of(e, x2y2_obj, n);
  py::array_t<double> joints = newArray(n, 5);
  py::array_t<double> drm = newArray(n);
  py::array_t<double> axes = newArray(n, 2);
  std::vector<std::string_view> words(static_cast<std::size_t>(n));
  double* j = joints.mutable_data();
  solvePoses(e, p, d, x2y2, [&](py::ssize_t i, const workflow::ExechonPoseStep& s) {
    double* row = j + 5 * i;
    if (s.solved) {
      for (int k = 0; k < 3; ++k) row[k] = s.joints.readings[k];
      row[3] = radToDeg(s.joints.c);
      row[4] = radToDeg(s.joints.a);
      drm.mutable_data()[i] = radToDeg(s.drm);
      words[static_cast<std::size_t>(i)] = s.status;
    } else {
      std::fill(row, row + 5, kNaN);
      drm.mutable_data()[i] = kNaN;
      words[static_cast<std::size_t>(i)] = s.check.solver_status;
    }
    axes.mutable_data()[2 * i] = s.command.x2;
    axes.mutable_data()[2 * i + 1] = s.command.y2;
  });
  if (raise) raiseOnFailure(words, "Exechon.ik", true);
  py::dict out;
  out["joints"] = joints;
  out["drm"] = drm;
  out["status"] = statusArray(words);
  if (e.machine->hybrid) out["x2y2"] = axes;
  return out;
}

py::tuple exechonFk(const Exechon& e, py::handle joints_obj, py::handle x2y2_obj, bool raise) {
  const DoubleArray joints = rowsOf(joints_obj, 5, "joints", true);
  const py::ssize_t n = joints.shape(0);
  const std::optional<DoubleArray> x2y2 = x2y2Of(e, x2y2_obj, n);
  py::array_t<double> points = newArray(n, 3);
  py::array_t<double> directions = newArray(n, 3);
  py::array_t<int> iterations(std::vector<py::ssize_t>{n});
  std::vector<std::string_view> words(static_cast<std::size_t>(n));
  {
    py::gil_scoped_release release;
    workflow::ExechonFkPath path(*e.machine);
    for (py::ssize_t i = 0; i < n; ++i) {
      const double* r = joints.data() + 5 * i;
      kin::ExechonJoints q;
      q.readings = {r[0], r[1], r[2]};
      q.c = degToRad(r[3]);
      q.a = degToRad(r[4]);
      const workflow::FkStep s = path.solve(q, rowPair(x2y2, i));
      for (int k = 0; k < 3; ++k) {
        points.mutable_data()[3 * i + k] = s.summary.ok() ? s.tool_point[k] : kNaN;
        directions.mutable_data()[3 * i + k] = s.summary.ok() ? s.tool_direction[k] : kNaN;
      }
      iterations.mutable_data()[i] = s.summary.iterations;
      words[static_cast<std::size_t>(i)] = kin::toString(s.summary.status);
    }
  }
  if (raise) raiseOnFailure(words, "Exechon.fk", false);
  return py::make_tuple(points, directions, statusArray(words), iterations);
}

py::tuple ikWrist(const Exechon& e, py::handle wrist) {
  const DoubleArray s = rowsOf(wrist, 3, "wrist_points", true);
  const py::ssize_t n = s.shape(0);
  py::array_t<double> readings = newArray(n, 3);
  py::array_t<double> params = newArray(n, 3);
  std::vector<std::string_view> words(static_cast<std::size_t>(n));
  {
    py::gil_scoped_release release;
    kin::ExechonData data(e.machine->model);
    for (py::ssize_t i = 0; i < n; ++i) {
      const workflow::ExechonWristStep w =
          workflow::solveWristPoint(e.machine->model, data, Eigen::Vector3d(s.data() + 3 * i));
      const bool ok = w.ik == kin::ExechonIkStatus::kOk;
      for (int k = 0; k < 3; ++k) readings.mutable_data()[3 * i + k] = ok ? w.readings[k] : kNaN;
      params.mutable_data()[3 * i] = ok ? radToDeg(w.e[0]) : kNaN;
      params.mutable_data()[3 * i + 1] = ok ? radToDeg(w.e[1]) : kNaN;
      params.mutable_data()[3 * i + 2] = ok ? w.e[2] : kNaN;
      words[static_cast<std::size_t>(i)] = ok ? w.status : kin::toString(w.ik);
    }
  }
  return py::make_tuple(readings, params, statusArray(words));
}

py::dict exechonCheck(
    const Exechon& e, py::handle points, py::handle directions, py::handle x2y2_obj, bool raise) {
  const auto [p, d] = toolRows(points, directions);
  const py::ssize_t n = p.shape(0);
  const std::optional<DoubleArray> x2y2 = x2y2Of(e, x2y2_obj, n);
  std::vector<workflow::ExechonPoseStep> steps(static_cast<std::size_t>(n));
  solvePoses(e, p, d, x2y2, [&](py::ssize_t i, const workflow::ExechonPoseStep& s) {
    steps[static_cast<std::size_t>(i)] = s;
  });
  std::vector<std::string_view> words;
  for (const auto& s : steps) words.push_back(s.status);
  if (raise) raiseOnFailure(words, "Exechon.check", true);
  const double deg = radToDeg(1.0);
  py::array_t<double> stroke = newArray(n, 3);
  auto column = [&](auto get) {
    py::array_t<double> a = newArray(n);
    for (py::ssize_t i = 0; i < n; ++i) {
      const auto& s = steps[static_cast<std::size_t>(i)];
      a.mutable_data()[i] = s.solved ? get(s.check) : kNaN;
    }
    return a;
  };
  py::array_t<bool> pole(std::vector<py::ssize_t>{n});
  py::list violations;
  for (py::ssize_t i = 0; i < n; ++i) {
    const auto& s = steps[static_cast<std::size_t>(i)];
    for (int k = 0; k < 3; ++k)
      stroke.mutable_data()[3 * i + k] = s.solved ? s.check.stroke_margin[k] : kNaN;
    pole.mutable_data()[i] = s.check.wrist_at_pole;
    py::list row;
    for (const kin::LimitViolation& v : s.check.violations) {
      const double f = v.kind == kin::LimitKind::kJointAngle ? deg : 1.0;
      row.append(py::dict(py::arg("kind") = std::string(kin::toString(v.kind)),
                          py::arg("item") = v.item,
                          py::arg("value") = v.value * f,
                          py::arg("limit") = v.limit * f,
                          py::arg("margin") = v.margin * f));
    }
    violations.append(row);
  }
  py::dict out;
  out["status"] = statusArray(words);
  out["stroke_margin"] = stroke;
  out["alpha_margin_deg"] =
      column([&](const kin::ExechonCheckResult& c) { return c.alpha_margin * deg; });
  out["beta_margin_deg"] =
      column([&](const kin::ExechonCheckResult& c) { return c.beta_margin * deg; });
  out["c_margin_deg"] = column([&](const kin::ExechonCheckResult& c) { return c.c_margin * deg; });
  out["a_margin_deg"] = column([&](const kin::ExechonCheckResult& c) { return c.a_margin * deg; });
  out["wrist_at_pole"] = pole;
  out["condition_number"] =
      column([](const kin::ExechonCheckResult& c) { return c.condition_number; });
  out["condition_margin"] =
      column([](const kin::ExechonCheckResult& c) { return c.condition_margin; });
  out["violations"] = violations;
  return out;
}

constexpr const char* kExechonIkDoc = R"doc(Tool IK along a path (as `pkm exechon ik --poses`).

Rows are solved by continuity from home; on a hybrid machine X2/Y2 take their share first
(the given x2y2, or pkm's centred split).

Parameters
----------
points : array_like, shape (N, 3)
    Tool points x, y, z (world frame, or work frame of a hybrid machine; machine unit).
directions : array_like, shape (N, 3) or (3,)
    Tool directions i, j, k (normalised by pkm); one row is used for every point.
x2y2 : array_like, shape (N, 2), optional
    X2, Y2 positions (hybrid machines only).
raise_on_failure : bool, default False
    Raise pkm.LimitError naming the first row whose status is not "ok".

Returns
-------
dict
    joints (N, 5): q1, q2, q3 (machine unit), c, a (degrees), NaN when unsolved;
    drm (N,): the dependent rotation about the tool axis from the first solved pose,
    degrees; status (N,) str; x2y2 (N, 2) on a hybrid machine.)doc";

constexpr const char* kExechonFkDoc =
    R"doc(Tool FK along a path (as `pkm exechon fk`), each row seeded by the previous.

Parameters
----------
joints : array_like, shape (N, 5)
    q1, q2, q3 (machine unit), c, a (degrees).
x2y2 : array_like, shape (N, 2), optional
    Hybrid machines: the tool point is then carried into the work frame.
raise_on_failure : bool, default False
    Raise pkm.ConvergenceError naming the first row that did not converge.

Returns
-------
(points (N, 3), directions (N, 3), status (N,) str, iterations (N,) int); NaN on failed rows.)doc";

constexpr const char* kExechonIkWristDoc =
    R"doc(Tripod IK at wrist points S (as `pkm exechon ik --wrist`).

Parameters
----------
wrist_points : array_like, shape (N, 3)
    S in Zoppi's tripod base frame, machine unit.

Returns
-------
(readings (N, 3) q1..q3, e (N, 3) alpha, beta (degrees), h (machine unit), status (N,) str).)doc";

constexpr const char* kExechonCheckDoc =
    R"doc(Limit checks along a path of tool poses (as `pkm exechon check`).

Returns
-------
dict
    status (N,) str; stroke_margin (N, 3) machine unit; alpha_margin_deg, beta_margin_deg,
    c_margin_deg, a_margin_deg (N,) degrees; wrist_at_pole (N,) bool; condition_number,
    condition_margin (N,); violations (per row a list of dicts). NaN where unsolved,
    +inf for a disabled limit.)doc";

/// Registers pkm.Exechon's ik, fk, ik_wrist and check on `cls`.
void defExechonKinematics(py::class_<Exechon>& cls) {
  cls.def("ik",
          &exechonIk,
          py::arg("points"),
          py::arg("directions"),
          py::arg("x2y2") = py::none(),
          py::arg("raise_on_failure") = false,
          kExechonIkDoc)
      .def("fk",
           &exechonFk,
           py::arg("joints"),
           py::arg("x2y2") = py::none(),
           py::arg("raise_on_failure") = false,
           kExechonFkDoc)
      .def("ik_wrist", &ikWrist, py::arg("wrist_points"), kExechonIkWristDoc)
      .def("check",
           &exechonCheck,
           py::arg("points"),
           py::arg("directions"),
           py::arg("x2y2") = py::none(),
           py::arg("raise_on_failure") = false,
           kExechonCheckDoc);
}

}  // namespace

void exposeExechon(py::module_& m) {
  py::class_<Exechon> cls(
      m,
      "Exechon",
      "An Exechon-type tripod with a C/A wrist (possibly on the extending axes "
      "X2/Y2 of a hybrid machine), as `pkm.load_machine` loads it.\n\n"
      "Tool poses are a tool point (world frame, or the work frame of a hybrid "
      "machine; machine unit) and a tool direction (unit vector, normalised by "
      "pkm). Joints are the leg readings q1, q2, q3 (machine unit) and the wrist "
      "readings C, A (degrees).");
  cls.def("__repr__",
          [](const Exechon& e) {
            return fmt::format("<pkm.Exechon '{}' from {} ({}{})>",
                               e.machine->model.name,
                               e.machine->source,
                               toString(e.machine->model.unit),
                               e.machine->hybrid ? ", hybrid X2/Y2" : "");
          })
      .def("__str__",
           [](const Exechon& e) {
             return fmt::format("Exechon '{}' ({}), unit {}{}\n{}",
                                e.machine->model.name,
                                e.machine->source,
                                toString(e.machine->model.unit),
                                e.machine->hybrid ? ", hybrid machine on X2/Y2" : "",
                                e.machine->description);
           })
      .def_property_readonly("name", [](const Exechon& e) { return e.machine->model.name; })
      .def_property_readonly("source", [](const Exechon& e) { return e.machine->source; })
      .def_property_readonly("description", [](const Exechon& e) { return e.machine->description; })
      .def_property_readonly("notices", [](const Exechon& e) { return e.machine->notices; })
      .def_property_readonly(
          "unit", [](const Exechon& e) { return std::string(toString(e.machine->model.unit)); })
      .def_property_readonly(
          "hybrid",
          [](const Exechon& e) { return e.machine->hybrid.has_value(); },
          "True for a hybrid machine (the tripod on the axes X2, Y2).")
      .def_property_readonly(
          "stroke",
          [](const Exechon& e) {
            py::array_t<double> a = newArray(3, 2);
            for (std::size_t i = 0; i < 3; ++i) {
              a.mutable_data()[2 * i] = e.machine->model.legs[i].min_reading;
              a.mutable_data()[2 * i + 1] = e.machine->model.legs[i].max_reading;
            }
            return a;
          },
          "(3, 2) lowest and highest reading of legs A, B, C, machine unit.")
      .def_property_readonly(
          "length_offsets",
          [](const Exechon& e) {
            py::array_t<double> a = newArray(3);
            for (std::size_t i = 0; i < 3; ++i)
              a.mutable_data()[i] = e.machine->model.legs[i].length_offset;
            return a;
          },
          "(3,) leg length offsets, machine unit.")
      .def(
          "to_json",
          [](const Exechon& e) { return io::writeExechonJson(*e.machine); },
          "The machine as a pkm JSON machine file (`pkm exechon describe`).");
  defExechonKinematics(cls);
  defExechonDrmCircle(cls);
}

}  // namespace pkm::python
