// pkm.calibration: `pkm calibrate hexapod` and `pkm calibrate exechon` from arrays. The arrays are
// written as the calibration files the command reads (tables.hpp: numbers in round-trip form,
// with the metadata lines the files carry), and the workflow reads them with the same readers as
// the command line, so the fit, its checks and its messages are the command's.
#include "calibration.hpp"

#include <fmt/format.h>
#include <pybind11/stl.h>

#include <functional>
#include <optional>

#include "machines.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/number_format.hpp"
#include "pkm/io/uncertainty_sources.hpp"
#include "tables.hpp"

namespace pkm::python {
namespace {

const std::vector<std::string> kPoseColumns{
    "l0", "l1", "l2", "l3", "l4", "l5", "x", "y", "z", "a", "b", "c"};
const std::vector<std::string> kPointColumns{"l0", "l1", "l2", "l3", "l4", "l5", "x", "y", "z"};
const std::vector<std::string> kGaugeColumns{
    "station", "x", "y", "z", "a", "b", "c", "l0", "l1", "l2", "l3", "l4", "l5", "g0", "g1", "g2"};
const std::vector<std::string> kDistanceColumns{"l0", "l1", "l2", "l3", "l4", "l5", "distance"};
const std::vector<std::string> kExechonColumns{"q0", "q1", "q2", "c", "a", "x", "y", "z"};
const std::vector<std::string> kExechonDirectionColumns{
    "q0", "q1", "q2", "c", "a", "x", "y", "z", "i", "j", "k"};
const std::vector<std::string> kHybridColumns{"x2", "y2", "xp", "yp", "zp", "x", "y", "z"};

bool isPath(py::handle obj) {
  return py::isinstance<py::str>(obj) || py::hasattr(obj, "__fspath__");
}

/// The tables of a data argument: none for None; each item of a list or tuple of tables (2-D
/// arrays, dicts, paths); else the argument itself.
std::vector<py::handle> itemsOf(py::handle obj) {
  if (obj.is_none()) return {};
  if ((py::isinstance<py::list>(obj) || py::isinstance<py::tuple>(obj)) && py::len(obj) > 0) {
    const py::handle first = obj.begin()->ptr();
    if (py::isinstance<py::dict>(first) || isPath(first) ||
        (py::isinstance<py::array>(first) &&
         py::reinterpret_borrow<py::array>(first).ndim() == 2)) {
      std::vector<py::handle> items;
      for (py::handle item : obj) items.push_back(item);
      return items;
    }
  }
  return {obj};
}

/// The number of columns of an array-like table (0 for a dict, a path or a non-2-D value).
py::ssize_t columnsOf(py::handle item) {
  if (py::isinstance<py::dict>(item) || isPath(item)) return 0;
  const py::array a = py::array::ensure(item);
  return a && a.ndim() == 2 ? a.shape(1) : 0;
}

/// Appends the files of data argument `obj` to `out`: paths read whole, arrays and dicts written
/// as a table named NAME (NAME[i] in a list) after the metadata lines `metadata`. `columns` picks
/// the header of an array from its column count.
void addTables(std::vector<io::NamedText>& out,
               py::handle obj,
               const std::string& name,
               const std::function<std::vector<std::string>(py::ssize_t)>& columns,
               const std::string& metadata = {}) {
  const std::vector<py::handle> items = itemsOf(obj);
  for (std::size_t i = 0; i < items.size(); ++i) {
    const std::string n = items.size() > 1 ? fmt::format("{}[{}]", name, i) : name;
    io::NamedText t = tableOf(items[i], n, columns(columnsOf(items[i])));
    if (!isPath(items[i])) t.text = metadata + t.text;
    out.push_back(std::move(t));
  }
}

auto fixed(const std::vector<std::string>& columns) {
  return [&columns](py::ssize_t) { return columns; };
}

/// "(x, y, z)" groups of the rows of `obj` ((n, 3) or (3,)), numbers in round-trip form.
std::string vectorsText(py::handle obj, py::ssize_t n, const char* name) {
  const DoubleArray a = rowsOf(obj, 3, name, n == 1);
  if (a.shape(0) != n)
    throw InvalidArgument(
        fmt::format("{}: expected {} rows of x, y, z, got {}", name, n, a.shape(0)));
  std::string text;
  for (py::ssize_t i = 0; i < n; ++i) {
    text += i ? ", (" : "(";
    for (py::ssize_t k = 0; k < 3; ++k) {
      if (k) text += ", ";
      io::appendNumber(text, a.data()[i * 3 + k]);
    }
    text += ')';
  }
  return text;
}

std::optional<Eigen::Vector3d> vector3(py::handle obj, const char* name) {
  if (obj.is_none()) return std::nullopt;
  const DoubleArray a = vectorOf(obj, 3, name);
  return Eigen::Vector3d(a.data()[0], a.data()[1], a.data()[2]);
}

std::string fspath(py::handle obj) {
  return py::str(py::module_::import("os").attr("fspath")(obj));
}

std::vector<io::NamedText> filesOf(py::handle files) {
  std::vector<io::NamedText> out;
  for (py::handle item : itemsOf(files)) out.push_back(io::readNamedText(fspath(item)));
  return out;
}

/// Raises pkm.ConvergenceError when a fit stopped without meeting its stopping rule.
void raiseUnconverged(bool converged, int iterations, const std::string& termination) {
  if (converged) return;
  const std::string message =
      fmt::format("calibration did not converge after {} iterations: {}", iterations, termination);
  PyErr_SetString(convergenceError().ptr(), message.c_str());
  throw py::error_already_set();
}

/// The metadata line that states the frame of tracker arrays: `frame` "world" or "tracker" (arrays
/// carry no metadata of their own); none for "auto", whose check then asks for one.
std::string frameLine(const std::string& frame) {
  return frame == "world" || frame == "tracker" ? "# frame: " + frame + "\n" : "";
}

/// What both calibrations share in their requests.
struct CommonOptions {
  std::string frame;
  py::object target_offset;
  std::vector<std::string> fix;
  std::string loss;
  double loss_scale;
  int monte_carlo;
  double sigma_position, sigma_orientation;
  int threads;
  bool allow_large_changes;
  py::object out;
  bool force;
  py::object db;
};

/// The options only a hexapod calibration has.
struct HexapodOptions {
  bool backlash;
  double prior_sigma, measurement_sigma, sigma_gauge;
  py::object uncertainty;  ///< the sources file of the uncertainty budgets, or None
  int uncertainty_trials;
};

template <class Request>
void setCommon(Request& r, const CommonOptions& o) {
  r.frame = o.frame;
  r.target_offset = vector3(o.target_offset, "target_offset");
  r.fix = o.fix;
  r.loss = o.loss;
  r.loss_scale = o.loss_scale;
  r.monte_carlo = o.monte_carlo;
  r.sigma_position = o.sigma_position;
  r.sigma_orientation_urad = o.sigma_orientation;
  r.threads = o.threads;
  r.allow_large_changes = o.allow_large_changes;
  if (!o.out.is_none()) r.out = fspath(o.out);
  r.force = o.force;
  if (!o.db.is_none()) r.db = fspath(o.db);
}

CalibrationResult hexapod(const py::object& machine,
                          const py::object& poses,
                          const py::object& points,
                          const py::object& gauges,
                          const py::object& gauge_points,
                          const py::object& table_normal,
                          const py::object& distances,
                          const py::object& pivot,
                          const py::object& files,
                          const py::object& holdout,
                          const HexapodOptions& options,
                          bool raise_on_failure,
                          const CommonOptions& common) {
  workflow::HexapodCalibrationRequest r;
  if (py::isinstance<Hexapod>(machine))
    r.loaded = *machine.cast<const Hexapod&>().machine;
  else
    r.machine = fspath(machine);
  const std::string frame = frameLine(common.frame);
  addTables(r.data, poses, "poses", fixed(kPoseColumns), frame);
  addTables(r.data, points, "points", fixed(kPointColumns), frame);
  if (!gauges.is_none()) {
    bool from_arrays = false;
    for (py::handle g : itemsOf(gauges)) from_arrays = from_arrays || !isPath(g);
    if (from_arrays && gauge_points.is_none())
      throw InvalidArgument(
          "gauge_points: give the three dial-gauge tips in the tool frame, a (3, 3) array, "
          "with gauge arrays");
    std::string meta;
    if (!gauge_points.is_none())
      meta += "# gauge points mm: " + vectorsText(gauge_points, 3, "gauge_points") + "\n";
    if (!table_normal.is_none())
      meta += "# table normal: " + vectorsText(table_normal, 1, "table_normal") + "\n";
    addTables(r.data, gauges, "gauges", fixed(kGaugeColumns), meta);
  }
  const std::string pivot_meta =
      pivot.is_none() ? "" : "# pivot mm: " + vectorsText(pivot, 1, "pivot") + "\n";
  addTables(r.data, distances, "distances", fixed(kDistanceColumns), pivot_meta);
  for (io::NamedText& f : filesOf(files)) r.data.push_back(std::move(f));
  addTables(
      r.holdout,
      holdout,
      "holdout",
      [](py::ssize_t cols) {
        return cols == static_cast<py::ssize_t>(kPointColumns.size()) ? kPointColumns
                                                                      : kPoseColumns;
      },
      frame);
  setCommon(r, common);
  r.backlash = options.backlash;
  r.prior_sigma = options.prior_sigma;
  r.measurement_sigma = options.measurement_sigma;
  r.sigma_gauge = options.sigma_gauge;
  if (!options.uncertainty.is_none()) {
    r.uncertainty_name = fspath(options.uncertainty);
    r.uncertainty = io::readUncertaintySources(io::readNamedText(r.uncertainty_name));
  }
  r.uncertainty_trials = options.uncertainty_trials;
  workflow::HexapodCalibrationResult result;
  {
    py::gil_scoped_release release;
    result = workflow::calibrateHexapod(r);
  }
  const calibration::HexapodCalibrationSummary& s = result.report.fit;
  if (raise_on_failure) raiseUnconverged(s.converged, s.iterations, s.termination);
  return hexapodResult(std::move(result));
}

CalibrationResult exechon(const py::object& machine,
                          const py::object& points,
                          const py::object& hybrid,
                          const py::object& files,
                          const py::object& holdout,
                          const py::object& hybrid_holdout,
                          const py::object& errors,
                          const py::object& hybrid_target_offset,
                          bool raise_on_failure,
                          const CommonOptions& common) {
  workflow::ExechonCalibrationRequest r;
  if (py::isinstance<Exechon>(machine))
    r.loaded = *machine.cast<const Exechon&>().machine;
  else
    r.machine = fspath(machine);
  const auto tracker = [](py::ssize_t cols) {
    return cols == static_cast<py::ssize_t>(kExechonDirectionColumns.size())
               ? kExechonDirectionColumns
               : kExechonColumns;
  };
  const std::string frame = frameLine(common.frame);
  const std::string hybrid_meta =
      frame + (hybrid_target_offset.is_none()
                   ? ""
                   : "# smr offset mm: " +
                         vectorsText(hybrid_target_offset, 1, "hybrid_target_offset") + "\n");
  addTables(r.data, points, "points", tracker, frame);
  addTables(r.data, hybrid, "hybrid", fixed(kHybridColumns), hybrid_meta);
  for (io::NamedText& f : filesOf(files)) r.data.push_back(std::move(f));
  addTables(r.holdout, holdout, "holdout", tracker, frame);
  addTables(r.holdout, hybrid_holdout, "hybrid_holdout", fixed(kHybridColumns), hybrid_meta);
  if (!errors.is_none()) r.errors = fspath(errors);
  setCommon(r, common);
  workflow::ExechonCalibrationResult result;
  {
    py::gil_scoped_release release;
    result = workflow::calibrateExechon(r);
  }
  if (raise_on_failure && result.report.tripod) {
    const auto& s = result.report.tripod->fit;
    raiseUnconverged(s.converged, s.iterations, s.termination);
  }
  if (raise_on_failure && result.report.hybrid) {
    const auto& s = result.report.hybrid->fit;
    raiseUnconverged(s.converged, s.iterations, s.termination);
  }
  return exechonResult(std::move(result));
}

void defHexapod(py::module_& c) {
  c.def(
      "hexapod",
      [](const py::object& machine,
         const py::object& poses,
         const py::object& points,
         const py::object& gauges,
         const py::object& gauge_points,
         const py::object& table_normal,
         const py::object& distances,
         const py::object& pivot,
         const py::object& files,
         const py::object& holdout,
         const std::string& frame,
         const py::object& target_offset,
         const std::vector<std::string>& fix,
         const std::string& loss,
         double loss_scale,
         bool backlash,
         double prior_sigma,
         double measurement_sigma,
         int monte_carlo,
         double sigma_position,
         double sigma_orientation,
         double sigma_gauge,
         int threads,
         bool allow_large_changes,
         const py::object& out,
         bool force,
         const py::object& db,
         const py::object& uncertainty,
         int uncertainty_trials,
         bool raise_on_failure) {
        const HexapodOptions options{
            backlash, prior_sigma, measurement_sigma, sigma_gauge, uncertainty, uncertainty_trials};
        const CommonOptions common{frame,
                                   target_offset,
                                   fix,
                                   loss,
                                   loss_scale,
                                   monte_carlo,
                                   sigma_position,
                                   sigma_orientation,
                                   threads,
                                   allow_large_changes,
                                   out,
                                   force,
                                   db};
        return hexapod(machine,
                       poses,
                       points,
                       gauges,
                       gauge_points,
                       table_normal,
                       distances,
                       pivot,
                       files,
                       holdout,
                       options,
                       raise_on_failure,
                       common);
      },
      py::arg("machine") = "default",
      py::kw_only(),
      py::arg("poses") = py::none(),
      py::arg("points") = py::none(),
      py::arg("gauges") = py::none(),
      py::arg("gauge_points") = py::none(),
      py::arg("table_normal") = py::none(),
      py::arg("distances") = py::none(),
      py::arg("pivot") = py::none(),
      py::arg("files") = py::none(),
      py::arg("holdout") = py::none(),
      py::arg("frame") = "auto",
      py::arg("target_offset") = py::none(),
      py::arg("fix") = std::vector<std::string>{},
      py::arg("loss") = "none",
      py::arg("loss_scale") = 0.0,
      py::arg("backlash") = false,
      py::arg("prior_sigma") = 0.0,
      py::arg("measurement_sigma") = 0.0,
      py::arg("monte_carlo") = 0,
      py::arg("sigma_position") = 0.0,
      py::arg("sigma_orientation") = 0.0,
      py::arg("sigma_gauge") = 0.0,
      py::arg("threads") = 0,
      py::arg("allow_large_changes") = false,
      py::arg("out") = py::none(),
      py::arg("force") = false,
      py::arg("db") = py::none(),
      py::arg("uncertainty") = py::none(),
      py::arg("uncertainty_trials") = 0,
      py::arg("raise_on_failure") = false,
      R"doc(Calibrates a hexapod's 42 kinematic parameters: `pkm calibrate hexapod`.

Observations (any mix; each an array, a dict of named columns, a file path, or a list of them,
one list item per file: backlash approach directions follow the row order of each). Lengths in
the machine's unit, angles in degrees; l0..l5 are the strut readings the controller commanded.

Parameters
----------
machine : str, os.PathLike or Hexapod, default "default"
    Built-in name, machine file (JSON, .hal, calibration file) or a loaded Hexapod.
poses : array_like (N, 12)
    Laser-tracker full poses: l0..l5, x, y, z, a, b, c of the measured target (6-DOF probe),
    in the world frame (frame="world") or the tracker's (frame="tracker").
points : array_like (N, 9)
    Laser-tracker points: l0..l5, x, y, z of the measured SMR.
gauges : array_like (N, 16)
    Constrained-motion (dial-gauge) sets: station (0 = the reference), x, y, z, a, b, c of
    the commanded pose, l0..l5, g0, g1, g2 (gauge readings). One array per set.
gauge_points : array_like (3, 3)
    The three gauge tips in the tool frame (required with gauge arrays).
table_normal : array_like (3,), optional
    The table's normal in the world frame (default 0, 0, 1).
distances : array_like (N, 7)
    l0..l5, distance: ball-bar lengths to `pivot`, or without it distances from the first
    row's TCP (whose distance is 0).
pivot : array_like (3,), optional
    The ball bar's fixed pivot in the world frame.
files : str or list of str
    Calibration files as `--data` reads them (after the arrays).
holdout : array_like (N, 12) or (N, 9), or files
    Tracker poses or points kept out of the fit: the held-out error before and after.
frame : {"auto", "world", "tracker"}
    Where tracker readings are; "auto": as the files state. Arrays carry no metadata: with
    "world" or "tracker" they are written with that `frame` line (so "auto" refuses them).
target_offset : array_like (3,), optional
    The tracker target in the tool frame (default: the files' `smr offset mm`, else 0).
fix : list of str
    Parameters held at their initial value (names as in parameter_names, e.g. "offset0").
loss, loss_scale : str, float
    Robust loss "none", "huber" or "cauchy" and its scale (length unit).
backlash : bool
    Also estimate a per-strut backlash.
prior_sigma, measurement_sigma : float
    Tikhonov prior toward the machine file (length unit; needs measurement_sigma) and the
    residual sigma for the prior and the covariance (0: estimated).
monte_carlo, sigma_position, sigma_orientation, sigma_gauge, threads
    Monte Carlo trials of the calibration (0 or 2..100000) and their noise (length unit;
    orientation in urad); worker threads (0: all cores).
allow_large_changes : bool
    Accept parameters that moved implausibly far (refused otherwise).
out, force : str, bool
    Also write the files `--out` writes (see CalibrationResult.save).
db : str, optional
    Record the calibration in this result store (needs `out`).
uncertainty : str, optional
    The instruments' uncertainty sources file of the budgets (`--uncertainty`; default typical
    datasheet values); the budgets are in to_dict()["uncertainty"] and expanded_uncertainty.
uncertainty_trials : int
    GUM Supplement 1 Monte Carlo of the budgets: the trial limit (0: linear budgets only).
raise_on_failure : bool
    Raise pkm.ConvergenceError when the solver stopped without converging.

Returns
-------
CalibrationResult

Raises
------
ValueError
    Bad shapes or values, unknown names, too few observations, a fit that does not explain the
    data or moves the machine implausibly: pkm's message (NAME:LINE: ... for a table: the line
    of the file the array was written as, its metadata lines, the header, then row 0).
ConvergenceError
    With raise_on_failure=True only.)doc");
}

void defExechon(py::module_& c) {
  c.def(
      "exechon",
      [](const py::object& machine,
         const py::object& points,
         const py::object& hybrid,
         const py::object& files,
         const py::object& holdout,
         const py::object& hybrid_holdout,
         const py::object& errors,
         const py::object& hybrid_target_offset,
         const std::string& frame,
         const py::object& target_offset,
         const std::vector<std::string>& fix,
         const std::string& loss,
         double loss_scale,
         int monte_carlo,
         double sigma_position,
         double sigma_orientation,
         int threads,
         bool allow_large_changes,
         const py::object& out,
         bool force,
         const py::object& db,
         bool raise_on_failure) {
        const CommonOptions common{frame,
                                   target_offset,
                                   fix,
                                   loss,
                                   loss_scale,
                                   monte_carlo,
                                   sigma_position,
                                   sigma_orientation,
                                   threads,
                                   allow_large_changes,
                                   out,
                                   force,
                                   db};
        return exechon(machine,
                       points,
                       hybrid,
                       files,
                       holdout,
                       hybrid_holdout,
                       errors,
                       hybrid_target_offset,
                       raise_on_failure,
                       common);
      },
      py::arg("machine") = "mxt700s-like",
      py::kw_only(),
      py::arg("points") = py::none(),
      py::arg("hybrid") = py::none(),
      py::arg("files") = py::none(),
      py::arg("holdout") = py::none(),
      py::arg("hybrid_holdout") = py::none(),
      py::arg("errors") = py::none(),
      py::arg("hybrid_target_offset") = py::none(),
      py::arg("frame") = "auto",
      py::arg("target_offset") = py::none(),
      py::arg("fix") = std::vector<std::string>{},
      py::arg("loss") = "none",
      py::arg("loss_scale") = 0.0,
      py::arg("monte_carlo") = 0,
      py::arg("sigma_position") = 0.0,
      py::arg("sigma_orientation") = 0.0,
      py::arg("threads") = 0,
      py::arg("allow_large_changes") = false,
      py::arg("out") = py::none(),
      py::arg("force") = false,
      py::arg("db") = py::none(),
      py::arg("raise_on_failure") = false,
      R"doc(Calibrates an Exechon (26 parameters) and/or a hybrid machine's four squareness
errors: `pkm calibrate exechon`.

Parameters
----------
machine : str, os.PathLike or Exechon, default "mxt700s-like"
points : array_like (N, 8) or (N, 11)
    Exechon tracker readings: q0, q1, q2 (leg readings), c, a (wrist readings, degrees), x, y, z
    (measured SMR), optionally i, j, k (a measured unit tool direction).
hybrid : array_like (N, 8)
    Hybrid tracker readings: x2, y2, xp, yp, zp (axis commands), x, y, z (measured target).
files : str or list of str
    Tracker files as `--data` reads them (after the arrays).
holdout, hybrid_holdout : array_like or files
    Readings kept out of the fit (as `points` and `hybrid`).
errors : str, optional
    Hybrid: the known geometric errors (PDGE file or built-in name) under the squareness fit.
hybrid_target_offset : array_like (3,), optional
    Hybrid arrays: the SMR in the tool frame (a hybrid file's `smr offset mm`; target_offset
    is the Exechon tracker readings' only).
frame, target_offset, fix, loss, loss_scale, monte_carlo, sigma_position, sigma_orientation,
threads, allow_large_changes, out, force, db, raise_on_failure
    As in hexapod() (fix names e.g. "tripod.hx").

Returns
-------
CalibrationResult
    The tripod fit's attributes (None without tripod data) and the squareness (None without
    hybrid data).

Raises
------
ValueError, ConvergenceError
    As hexapod().)doc");
}

}  // namespace

void exposeCalibration(py::module_& m) {
  py::module_ c = m.def_submodule(
      "calibration",
      "Kinematic calibration (`pkm calibrate hexapod`, `pkm calibrate exechon`) and calibration "
      "pose planning (`pkm plan-poses`) from numpy arrays (docs/python.md, docs/calibration.md).");
  exposeCalibrationResult(c);
  defHexapod(c);
  defExechon(c);
  exposePosePlanning(c);
}

}  // namespace pkm::python
