// pkm.Hexapod: geometry (hexapod_geometry.cpp), inverse and forward kinematics, Jacobian and limit
// checks on numpy arrays (the rules of `pkm hexapod ik|fk|check`: kinematics::checkPose,
// workflow::HexapodFkPath).
#include <fmt/format.h>
#include <pybind11/stl.h>

#include <optional>

#include "common.hpp"
#include "hexapod_geometry.hpp"
#include "machines.hpp"
#include "pkm/core/units.hpp"
#include "pkm/io/machine_description.hpp"
#include "pkm/kinematics/hexapod_checks.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"
#include "pkm/workflow/hexapod_ik_rows.hpp"
#include "pkm/workflow/kinematics_path.hpp"

namespace pkm::python {
namespace {

namespace kin = pkm::kinematics;

/// Row `i` of an (N, 6) x, y, z, a, b, c array (degrees) as a pose (radians).
kin::PoseRpy poseAt(const double* p) {
  kin::PoseRpy pose;
  pose.position = {p[0], p[1], p[2]};
  pose.rpy = {degToRad(p[3]), degToRad(p[4]), degToRad(p[5])};
  return pose;
}

const kin::HexapodModel& modelOf(const Hexapod& h) { return h.machine->model; }

py::object hexapodIk(const Hexapod& h, py::handle poses_obj, bool status, bool raise) {
  bool single = false;
  const DoubleArray poses = rowsOf(poses_obj, 6, "poses", true, &single);
  const py::ssize_t n = poses.shape(0);
  py::array_t<double> out = newArray(n, 6);
  const double* in = poses.data();
  double* o = out.mutable_data();
  std::vector<std::string_view> words;
  if (status || raise) words.resize(static_cast<std::size_t>(n));
  {
    py::gil_scoped_release release;
    const auto size = static_cast<std::size_t>(6 * n);
    workflow::hexapodIkRows(modelOf(h), {in, size}, {o, size}, words);
  }
  if (raise) raiseOnFailure(words, "Hexapod.ik", true);
  py::object readings = single ? py::object(out.reshape({py::ssize_t{6}})) : py::object(out);
  if (!status) return readings;
  return py::make_tuple(readings, statusArray(words));
}

py::tuple hexapodFk(
    const Hexapod& h, py::handle lengths_obj, py::handle seed_obj, bool from_seed, bool raise) {
  bool single = false;
  const DoubleArray lengths = rowsOf(lengths_obj, 6, "lengths", true, &single);
  std::optional<kin::PoseRpy> seed;
  if (!seed_obj.is_none()) seed = poseAt(vectorOf(seed_obj, 6, "seed").data());
  const py::ssize_t n = lengths.shape(0);
  py::array_t<double> poses = newArray(n, 6);
  py::array_t<int> iterations(std::vector<py::ssize_t>{n});
  std::vector<std::string_view> words(static_cast<std::size_t>(n));
  const double* in = lengths.data();
  double* o = poses.mutable_data();
  int* it = iterations.mutable_data();
  {
    py::gil_scoped_release release;
    // As `pkm hexapod fk`: the path solves without angles, HexapodFkAngles converts them in order.
    workflow::HexapodFkPath path(*h.machine, seed, from_seed, /*angles=*/false);
    workflow::HexapodFkAngles angles(*h.machine, seed, from_seed);
    for (py::ssize_t i = 0; i < n; ++i) {
      const workflow::FkStep step = path.solve(kin::StrutVector(in + 6 * i));
      const Eigen::Vector3d rpy = angles.next(step);
      double* row = o + 6 * i;
      if (step.summary.ok()) {
        for (int k = 0; k < 3; ++k) row[k] = step.pose.position[k];
        for (int k = 0; k < 3; ++k) row[3 + k] = radToDeg(rpy[k]);
      } else {
        std::fill(row, row + 6, std::numeric_limits<double>::quiet_NaN());
      }
      it[i] = step.summary.iterations;
      words[static_cast<std::size_t>(i)] = kin::toString(step.summary.status);
    }
  }
  if (raise) raiseOnFailure(words, "Hexapod.fk", false);
  if (single)
    return py::make_tuple(poses.reshape({py::ssize_t{6}}), statusArray(words)[py::int_(0)], it[0]);
  return py::make_tuple(poses, statusArray(words), iterations);
}

py::array_t<double> jacobian(const Hexapod& h, py::handle poses_obj) {
  bool single = false;
  const DoubleArray poses = rowsOf(poses_obj, 6, "pose", true, &single);
  const py::ssize_t n = poses.shape(0);
  py::array_t<double> out(std::vector<py::ssize_t>{n, 6, 6});
  const double* in = poses.data();
  double* o = out.mutable_data();
  {
    py::gil_scoped_release release;
    kin::HexapodData data(modelOf(h));
    for (py::ssize_t i = 0; i < n; ++i) {
      kin::inverseKinematics(modelOf(h), data, poseAt(in + 6 * i));
      Eigen::Map<Eigen::Matrix<double, 6, 6, Eigen::RowMajor>>(o + 36 * i) =
          kin::computeStrutJacobian(modelOf(h), data);
    }
  }
  if (single) return out.reshape({py::ssize_t{6}, py::ssize_t{6}});
  return out;
}

py::dict hexapodCheck(const Hexapod& h, py::handle poses_obj, bool raise) {
  const DoubleArray poses = rowsOf(poses_obj, 6, "poses", true);
  const py::ssize_t n = poses.shape(0);
  std::vector<kin::HexapodCheckResult> results(static_cast<std::size_t>(n));
  {
    py::gil_scoped_release release;
    kin::HexapodData data(modelOf(h));
    for (py::ssize_t i = 0; i < n; ++i)
      results[static_cast<std::size_t>(i)] =
          kin::checkPose(modelOf(h), data, poseAt(poses.data() + 6 * i));
  }
  std::vector<std::string_view> words;
  for (const auto& r : results) words.push_back(r.status());
  if (raise) raiseOnFailure(words, "Hexapod.check", true);
  // Per-strut quantities (N, 6); angles in degrees.
  auto strutArray = [&](auto field, double scale) {
    py::array_t<double> a = newArray(n, 6);
    double* o = a.mutable_data();
    for (py::ssize_t i = 0; i < n; ++i)
      Eigen::Map<kin::StrutVector>(o + 6 * i) =
          (results[static_cast<std::size_t>(i)].*field) * scale;
    return a;
  };
  auto scalarArray = [&](double kin::HexapodCheckResult::*field) {
    py::array_t<double> a = newArray(n);
    for (py::ssize_t i = 0; i < n; ++i)
      a.mutable_data()[i] = results[static_cast<std::size_t>(i)].*field;
    return a;
  };
  const double deg = radToDeg(1.0);
  py::dict d;
  d["status"] = statusArray(words);
  d["readings"] = strutArray(&kin::HexapodCheckResult::readings, 1.0);
  d["stroke_margin"] = strutArray(&kin::HexapodCheckResult::stroke_margin, 1.0);
  d["base_angle_deg"] = strutArray(&kin::HexapodCheckResult::base_angle, deg);
  d["platform_angle_deg"] = strutArray(&kin::HexapodCheckResult::platform_angle, deg);
  d["base_angle_margin_deg"] = strutArray(&kin::HexapodCheckResult::base_angle_margin, deg);
  d["platform_angle_margin_deg"] = strutArray(&kin::HexapodCheckResult::platform_angle_margin, deg);
  d["min_leg_distance"] = scalarArray(&kin::HexapodCheckResult::min_leg_distance);
  d["interference_margin"] = scalarArray(&kin::HexapodCheckResult::interference_margin);
  d["condition_number"] = scalarArray(&kin::HexapodCheckResult::condition_number);
  d["condition_margin"] = scalarArray(&kin::HexapodCheckResult::condition_margin);
  py::array_t<int> pair(std::vector<py::ssize_t>{n, 2});
  py::list violations;
  for (py::ssize_t i = 0; i < n; ++i) {
    const auto& r = results[static_cast<std::size_t>(i)];
    pair.mutable_data()[2 * i] = r.closest_pair[0];
    pair.mutable_data()[2 * i + 1] = r.closest_pair[1];
    py::list row;
    for (const kin::LimitViolation& v : r.violations) {
      const double s = v.kind == kin::LimitKind::kJointAngle ? deg : 1.0;
      row.append(py::dict(py::arg("kind") = std::string(kin::toString(v.kind)),
                          py::arg("item") = v.item,
                          py::arg("value") = v.value * s,
                          py::arg("limit") = v.limit * s,
                          py::arg("margin") = v.margin * s));
    }
    violations.append(row);
  }
  d["closest_pair"] = pair;
  d["violations"] = violations;
  return d;
}

constexpr const char* kHexapodIkDoc =
    R"doc(Inverse kinematics: poses -> strut readings (as `pkm hexapod ik`).

Parameters
----------
poses : array_like, shape (N, 6) or (6,)
    x, y, z (TCP, world frame, machine unit), a, b, c (degrees).
status : bool, default False
    Also run every limit check (kinematics::checkPose) and return the status per pose:
    "ok" or the first violated limit ("stroke", "joint_angle", "interference",
    "singular", "degenerate"), as the CLI's status column.
raise_on_failure : bool, default False
    Raise pkm.LimitError naming the first pose whose status is not "ok".

Returns
-------
readings : ndarray, shape (N, 6) or (6,)
    Strut readings l0..l5 (machine unit). No limits are applied.
status : ndarray of str, shape (N,)
    Only with status=True: the tuple (readings, status).

Raises
------
ValueError
    For a wrong shape or a value that is not finite.)doc";

constexpr const char* kHexapodFkDoc =
    R"doc(Forward kinematics along a path of strut readings (as `pkm hexapod fk`).

Each row is seeded with the previous rows' solutions (a servo loop), the first with `seed`
or home; after a failure the next row starts from home again.

Parameters
----------
lengths : array_like, shape (N, 6) or (6,)
    Strut readings l0..l5, machine unit.
seed : array_like, shape (6,), optional
    First row's seed x, y, z, a, b, c (degrees); default the machine's home.
from_seed : bool, default False
    Solve every row on its own from the seed (rows that are not a path).
raise_on_failure : bool, default False
    Raise pkm.ConvergenceError naming the first row that did not converge.

Returns
-------
poses : ndarray, shape (N, 6)
    x, y, z, a, b, c (degrees); NaN on rows that failed. Angles stay continuous along the
    path (nearest to the previous solution's).
status : ndarray of str, shape (N,)
    "ok", "no_convergence", "singular" or "invalid_input".
iterations : ndarray of int, shape (N,)
    Newton iterations per row.)doc";

constexpr const char* kHexapodJacobianDoc =
    R"doc(Strut Jacobian J_q_x = d(readings)/d(pose perturbation) at a pose.

Rows are [u_i^T, (R a_i x u_i)^T]: translation of the TCP (machine unit) and a small rotation
(radians) about world axes (docs/conventions.md, "Perturbations and the Jacobian").

Parameters
----------
pose : array_like, shape (6,) or (N, 6)
    x, y, z, a, b, c (degrees).

Returns
-------
ndarray, shape (6, 6) or (N, 6, 6))doc";

constexpr const char* kHexapodCheckDoc = R"doc(Every limit check per pose (as `pkm hexapod check`).

Parameters
----------
poses : array_like, shape (N, 6) or (6,)
    x, y, z, a, b, c (degrees).
raise_on_failure : bool, default False
    Raise pkm.LimitError naming the first pose that violates a limit.

Returns
-------
dict
    status (N,) str; readings, stroke_margin (N, 6) machine unit; base_angle_deg,
    platform_angle_deg, base_angle_margin_deg, platform_angle_margin_deg (N, 6) degrees;
    min_leg_distance, interference_margin (N,) machine unit; closest_pair (N, 2) int
    (-1 when no pair is checked); condition_number, condition_margin (N,); violations: per
    pose a list of dicts (kind, item, value, limit, margin; joint angles in degrees).
    Margins are >= 0 when a limit holds and +inf when it is disabled.)doc";

/// Registers pkm.Hexapod's ik, fk, jacobian and check on `cls`.
void defHexapodKinematics(py::class_<Hexapod>& cls) {
  cls.def("ik",
          &hexapodIk,
          py::arg("poses"),
          py::arg("status") = false,
          py::arg("raise_on_failure") = false,
          kHexapodIkDoc)
      .def("fk",
           &hexapodFk,
           py::arg("lengths"),
           py::arg("seed") = py::none(),
           py::arg("from_seed") = false,
           py::arg("raise_on_failure") = false,
           kHexapodFkDoc)
      .def("jacobian", &jacobian, py::arg("pose"), kHexapodJacobianDoc)
      .def("check",
           &hexapodCheck,
           py::arg("poses"),
           py::arg("raise_on_failure") = false,
           kHexapodCheckDoc);
}

}  // namespace

void exposeHexapod(py::module_& m) {
  py::class_<Hexapod> cls(
      m,
      "Hexapod",
      "A hexapod (6-UPS Stewart platform) machine, as `pkm.load_machine` loads it.\n\n"
      "Poses are rows x, y, z, a, b, c: the TCP in the world (base) frame in the "
      "machine's length unit and LinuxCNC roll-pitch-yaw angles in degrees "
      "(R = Rz(c) Ry(b) Rx(a)). Strut readings are l0..l5 in the machine unit.");
  cls.def("__str__", [](const Hexapod& h) { return io::describeHexapodMachine(*h.machine); })
      .def("__repr__",
           [](const Hexapod& h) {
             return fmt::format("<pkm.Hexapod '{}' from {} ({})>",
                                h.machine->model.name,
                                h.machine->source,
                                toString(h.machine->model.unit));
           })
      .def_property_readonly("name", [](const Hexapod& h) { return h.machine->model.name; })
      .def_property_readonly(
          "source",
          [](const Hexapod& h) { return h.machine->source; },
          "Where the machine came from: a path or 'builtin:NAME'.")
      .def_property_readonly("description", [](const Hexapod& h) { return h.machine->description; })
      .def_property_readonly(
          "notices",
          [](const Hexapod& h) { return h.machine->notices; },
          "What the reader ignored or assumed (the CLI's 'pkm: note:' lines).")
      .def_property_readonly(
          "unit", [](const Hexapod& h) { return std::string(toString(h.machine->model.unit)); });
  defHexapodGeometry(cls);
  cls.def(
      "to_json",
      [](const Hexapod& h) { return io::writeHexapodJson(*h.machine); },
      "The machine as a pkm JSON machine file (`pkm hexapod describe --json`).");
  defHexapodKinematics(cls);
  defHexapodFkFile(cls);
}

}  // namespace pkm::python
