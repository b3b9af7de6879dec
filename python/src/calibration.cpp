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
const std::vector<std::string> kExechonColumns{"q1", "q2", "q3", "c", "a", "x", "y", "z"};
const std::vector<std::string> kExechonDirectionColumns{
    "q1", "q2", "q3", "c", "a", "x", "y", "z", "i", "j", "k"};
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

/// The uncertainty budgets' sources file (`--uncertainty FILE`; None: the typical values).
template <class Request>
void setUncertainty(Request& r, const py::object& file) {
  if (file.is_none()) return;
  r.uncertainty_name = fspath(file);
  r.uncertainty = io::readUncertaintySources(io::readNamedText(r.uncertainty_name));
}

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

}  // namespace

CalibrationResult runHexapodCalibration(const py::object& machine,
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
  r.prior_uncertainty = options.prior_uncertainty;
  r.sigma_gauge = options.sigma_gauge;
  setUncertainty(r, options.uncertainty);
  r.uncertainty_trials = options.uncertainty_trials;
  if (!options.registration.is_none())
    r.registration = io::readNamedText(fspath(options.registration));
  workflow::HexapodCalibrationResult result;
  {
    py::gil_scoped_release release;
    result = workflow::calibrateHexapod(r);
  }
  const calibration::HexapodCalibrationSummary& s = result.report.fit;
  if (raise_on_failure) raiseUnconverged(s.converged, s.iterations, s.termination);
  return hexapodResult(std::move(result), r);
}

CalibrationResult runExechonCalibration(const py::object& machine,
                                        const py::object& points,
                                        const py::object& hybrid,
                                        const py::object& files,
                                        const py::object& holdout,
                                        const py::object& hybrid_holdout,
                                        const py::object& errors,
                                        const py::object& hybrid_target_offset,
                                        const py::object& uncertainty,
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
  setUncertainty(r, uncertainty);
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

}  // namespace pkm::python
