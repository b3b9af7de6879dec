// pkm.calibration's registration: hexapod(), exechon() (calibration.cpp builds their requests),
// CalibrationResult (calibration_result.cpp) and plan_poses (calibration_plan.cpp), with the
// numpy-style docstrings (units, frames) that help() shows.
#include <pybind11/stl.h>

#include "calibration.hpp"

namespace pkm::python {
namespace {

/// pkm.calibration.hexapod: the keyword arguments as the options of runHexapodCalibration.
CalibrationResult hexapodCalibration(const py::object& machine,
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
                                     const py::object& registration,
                                     bool raise_on_failure,
                                     double prior_uncertainty) {
  const HexapodOptions options{backlash,
                               prior_sigma,
                               measurement_sigma,
                               prior_uncertainty,
                               sigma_gauge,
                               uncertainty,
                               uncertainty_trials,
                               registration};
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
  return runHexapodCalibration(machine,
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
}

constexpr const char* kHexapodCalibrationDoc =
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
registration : str or path
    The tracker's readings of fiducial nests on the table (a pkm.tracker-registration/1 file,
    `pkm calibrate hexapod --registration`): puts tracker-frame readings in the machine's world
    frame. Without it, tracker-frame data give a machine marked "world_frame": "unregistered"
    that no controller command accepts (docs/calibration.md, "Frames").
prior_sigma, measurement_sigma : float
    Tikhonov prior toward the machine file (length unit; needs measurement_sigma) and the
    residual sigma for the prior and the covariance (0: estimated).
prior_uncertainty : float
    The machine file's geometry as an input of the uncertainty budgets, one standard deviation
    per parameter (length unit; 0: prior_sigma). Needs prior_sigma.
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
    With raise_on_failure=True only.)doc";

/// Registers pkm.calibration.hexapod in `c`.
void defHexapod(py::module_& c) {
  c.def("hexapod",
        &hexapodCalibration,
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
        py::arg("registration") = py::none(),
        py::arg("raise_on_failure") = false,
        py::arg("prior_uncertainty") = 0.0,
        kHexapodCalibrationDoc);
}

/// pkm.calibration.exechon: the keyword arguments as the options of runExechonCalibration.
CalibrationResult exechonCalibration(const py::object& machine,
                                     const py::object& points,
                                     const py::object& hybrid,
                                     const py::object& files,
                                     const py::object& holdout,
                                     const py::object& hybrid_holdout,
                                     const py::object& errors,
                                     const py::object& hybrid_target_offset,
                                     const py::object& uncertainty,
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
  return runExechonCalibration(machine,
                               points,
                               hybrid,
                               files,
                               holdout,
                               hybrid_holdout,
                               errors,
                               hybrid_target_offset,
                               uncertainty,
                               raise_on_failure,
                               common);
}

constexpr const char* kExechonCalibrationDoc =
    R"doc(Calibrates an Exechon (26 parameters) and/or a hybrid machine's four squareness
errors: `pkm calibrate exechon`.

Parameters
----------
machine : str, os.PathLike or Exechon, default "mxt700s-like"
points : array_like (N, 8) or (N, 11)
    Exechon tracker readings: q1, q2, q3 (leg readings A, B, C), c, a (wrist readings, degrees), x, y, z
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
threads, allow_large_changes, out, force, db, uncertainty, raise_on_failure
    As in hexapod() (fix names e.g. "tripod.hx"; the budgets are the tripod fit's).

Returns
-------
CalibrationResult
    The tripod fit's attributes (None without tripod data) and the squareness (None without
    hybrid data).

Raises
------
ValueError, ConvergenceError
    As hexapod().)doc";

/// Registers pkm.calibration.exechon in `c`.
void defExechon(py::module_& c) {
  c.def("exechon",
        &exechonCalibration,
        py::arg("machine") = "mxt700s-like",
        py::kw_only(),
        py::arg("points") = py::none(),
        py::arg("hybrid") = py::none(),
        py::arg("files") = py::none(),
        py::arg("holdout") = py::none(),
        py::arg("hybrid_holdout") = py::none(),
        py::arg("errors") = py::none(),
        py::arg("hybrid_target_offset") = py::none(),
        py::arg("uncertainty") = py::none(),
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
        kExechonCalibrationDoc);
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
