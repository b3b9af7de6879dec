// pkm.calibration.CalibrationResult (calibration.hpp): a calibration workflow's result as
// attributes (numpy arrays of the fit, the members of the summary document), the calibrated
// machine as a pkm.Hexapod / pkm.Exechon, to_dict() = the summary document the command line prints
// with --json, and save() = the files `--out` writes.
#include <pybind11/stl.h>

#include <array>
#include <limits>
#include <optional>
#include <string_view>

#include "calibration.hpp"
#include "machines.hpp"
#include "pkm/calibration/exechon_parameters.hpp"
#include "pkm/calibration/hexapod_calibration.hpp"
#include "pkm/calibration/hexapod_parameters.hpp"
#include "pkm/calibration/hybrid_calibration.hpp"
#include "pkm/workflow/calibration_text.hpp"

namespace pkm::python {
namespace {

namespace cal = pkm::calibration;

py::array_t<double> vectorArray(const double* v, Eigen::Index n) {
  py::array_t<double> out = newArray(n);
  std::copy(v, v + n, out.mutable_data());
  return out;
}

py::array_t<double> matrixArray(const Eigen::MatrixXd& m) {
  py::array_t<double> out = newArray(m.rows(), m.cols());
  double* p = out.mutable_data();
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (Eigen::Index j = 0; j < m.cols(); ++j) p[i * m.cols() + j] = m(i, j);
  return out;
}

py::array namesArray(const std::vector<std::string>& names) {
  return statusArray(std::vector<std::string_view>(names.begin(), names.end()));
}

/// |error| per held-out observation (NaN: no prediction).
py::array_t<double> errorsArray(const calibration::HoldoutErrors& e) {
  return vectorArray(e.errors.data(), static_cast<Eigen::Index>(e.errors.size()));
}

/// holdout_errors_before / _after (None without held-out data).
template <class Holdout>
void addHoldoutErrors(py::dict& a, const std::optional<Holdout>& h) {
  a["holdout_errors_before"] = h ? py::object(errorsArray(h->before)) : py::none();
  a["holdout_errors_after"] = h ? py::object(errorsArray(h->after)) : py::none();
}

py::object member(const py::dict& doc, const char* key) {
  return doc.contains(key) ? py::object(doc[key]) : py::object(py::none());
}

/// The attributes a least-squares fit has (hexapod, Exechon tripod): `names` are the parameter
/// names, `columns` the identifiability columns, `covariance_names` the covariance's rows.
template <class Summary, std::size_t N>
void addFit(py::dict& a,
            const Summary& s,
            const py::dict& doc,
            const std::vector<std::string>& names,
            const std::array<bool, N>& free,
            const std::vector<std::string>& columns,
            const std::vector<std::string>& covariance_names) {
  const auto n = static_cast<Eigen::Index>(names.size());
  a["parameter_names"] = namesArray(names);
  a["initial"] = vectorArray(s.initial.data(), n);
  a["parameters"] = vectorArray(s.parameters.data(), n);
  a["change"] = vectorArray(Eigen::VectorXd(s.parameters - s.initial).data(), n);
  a["standard_deviation"] = vectorArray(s.standard_deviation.data(), n);
  py::array_t<bool> f(static_cast<py::ssize_t>(N));
  std::copy(free.begin(), free.end(), f.mutable_data());
  a["free"] = f;
  a["covariance"] = matrixArray(s.covariance);
  a["covariance_names"] = namesArray(covariance_names);
  a["sigma"] = s.sigma;
  a["converged"] = s.converged;
  a["iterations"] = s.iterations;
  a["termination"] = s.termination;
  const cal::Identifiability& id = s.identifiability;
  a["rank"] = id.rank;
  a["condition_number"] = id.condition_number;
  py::dict ident = py::dict(doc["identifiability"]);
  ident["equations"] = id.equations;
  ident["names"] = namesArray(columns);
  ident["singular_values"] = vectorArray(id.singular_values.data(), id.singular_values.size());
  ident["null_space"] = matrixArray(id.null_space);
  a["identifiability"] = ident;
  a["residuals_before"] = doc["residuals"]["before"];
  a["residuals_after"] = doc["residuals"]["after"];
  a["holdout"] = member(doc, "holdout");
  a["measurement_frame"] =
      s.measurement_frame ? py::object(matrixArray(s.measurement_frame->matrix())) : py::none();
  a["frame_sigma"] = s.measurement_frame
                         ? py::object(vectorArray(s.frame_standard_deviation.data(), 6))
                         : py::none();
  a["worst_observations"] = doc["worst_observations"];
  a["tcp_error_map"] = member(doc, "tcp_error_map");
  a["monte_carlo"] = member(doc, "monte_carlo");
  a["uncertainty"] = member(doc, "uncertainty");
  // U (k = 2) of each parameter, when the summary has uncertainty budgets.
  const py::list rows = doc["parameters"];
  if (rows.size() > 0 && py::dict(rows[0]).contains("U")) {
    py::array_t<double> u = newArray(static_cast<py::ssize_t>(rows.size()));
    for (std::size_t k = 0; k < rows.size(); ++k) {
      const py::object value = rows[k]["U"];  // null for fixed parameters
      u.mutable_data()[k] =
          value.is_none() ? std::numeric_limits<double>::quiet_NaN() : value.cast<double>();
    }
    a["expanded_uncertainty"] = u;
  } else {
    a["expanded_uncertainty"] = py::none();
  }
}

/// The fit attributes as None (an Exechon calibration from hybrid data only).
void addNoFit(py::dict& a) {
  for (const char* key : {"parameter_names",
                          "initial",
                          "parameters",
                          "change",
                          "standard_deviation",
                          "free",
                          "covariance",
                          "covariance_names",
                          "sigma",
                          "converged",
                          "iterations",
                          "termination",
                          "rank",
                          "condition_number",
                          "identifiability",
                          "residuals_before",
                          "residuals_after",
                          "holdout",
                          "measurement_frame",
                          "frame_sigma",
                          "worst_observations",
                          "tcp_error_map",
                          "monte_carlo",
                          "uncertainty",
                          "expanded_uncertainty"})
    a[key] = py::none();
}

std::vector<std::string> hexapodNames() {
  std::vector<std::string> names;
  for (int k = 0; k < cal::kHexapodParameters; ++k) names.push_back(cal::hexapodParameterName(k));
  return names;
}

std::vector<std::string> exechonNames(int unknowns) {
  std::vector<std::string> names;
  for (int k = 0; k < unknowns; ++k)
    names.push_back(
        k < cal::kExechonParameters
            ? cal::exechonParameterName(k)
            : cal::measurementFrameNames()[static_cast<std::size_t>(k - cal::kExechonParameters)]);
  return names;
}

/// The hybrid squareness attributes (None without hybrid data).
void addHybrid(py::dict& a, const workflow::ExechonCalibrationResult& r, const py::dict& doc) {
  if (!r.report.hybrid) {
    for (const char* key : {"squareness",
                            "squareness_names",
                            "squareness_sigma",
                            "hybrid",
                            "geometric_errors",
                            "hybrid_holdout_errors_before",
                            "hybrid_holdout_errors_after"})
      a[key] = py::none();
    return;
  }
  const cal::HybridCalibrationSummary& s = r.report.hybrid->fit;
  const Eigen::Vector4d q(
      s.squareness.sz_x2, s.squareness.sx_p, s.squareness.sy_p, s.squareness.sz_p);
  a["squareness"] = vectorArray(q.data(), 4);
  a["squareness_names"] = namesArray(cal::hybridSquarenessNames());
  a["squareness_sigma"] = vectorArray(s.standard_deviation.data(), 4);
  a["hybrid"] = doc["hybrid"];
  const std::optional<io::HoldoutComparison>& h = r.report.hybrid->holdout;
  a["hybrid_holdout_errors_before"] = h ? py::object(errorsArray(h->before)) : py::none();
  a["hybrid_holdout_errors_after"] = h ? py::object(errorsArray(h->after)) : py::none();
  a["geometric_errors"] = jsonLoads(r.errors_json);
}

constexpr const char* kCalibrationResultDoc = R"doc(The result of a calibration.

Attributes (lengths in the machine's unit, angles in rad unless the name says deg):

machine : Hexapod or Exechon
    The calibrated machine, usable at once (ik, fk, check).
parameter_names, initial, parameters, change, standard_deviation, free : ndarray
    The kinematic parameters (42 for a hexapod: per strut the base joint bx, by, bz, the
    platform joint px, py, pz and the length offset; 26 for an Exechon), in the order of the
    summary document's "parameters"; `free` is False for parameters held (`fix`).
covariance : ndarray
    The estimate's covariance (hexapod 42 x 42; Exechon 26 x 26, or 32 x 32 with the tracker
    frame), rows named by `covariance_names`; zero rows and columns for fixed parameters.
sigma : float
    The residual standard deviation the covariance uses.
rank, condition_number : int, float
    Identifiability of the free unknowns (with the tracker frame and backlash when fitted).
identifiability : dict
    parameters, equations, rank, condition_number, unidentifiable (one {name: coefficient}
    dict per direction the data cannot see), names (the columns), singular_values and
    null_space (columns x unidentifiable directions) as arrays.
residuals_before, residuals_after : dict
    equations, rms, max, fk_failures of the fitted data before and after.
holdout : dict or None
    The held-out errors before and after ("before"/"after": poses, fk_failures, mean, rms, max).
holdout_errors_before, holdout_errors_after : ndarray or None
    |error| of each held-out observation (TCP or target position, length unit), in the order
    of the held-out data (hexapod: poses, then points); NaN where the FK did not converge.
    Before: the nominal machine (with its own fitted tracker frame); after: the calibrated one.
converged, iterations, termination : bool, int, str
    How the solver stopped.
measurement_frame : ndarray (4, 4) or None
    world_T_tracker, estimated when the readings are in the tracker's frame; frame_sigma its
    standard deviations (dx, dy, dz, rx, ry, rz; world axes).
worst_observations, tcp_error_map, monte_carlo, observations, target_offset, uncertainty
    As in the summary document (None when it has no such member).
expanded_uncertainty : ndarray or None
    U (k = 2) of each parameter from the uncertainty budgets, when the summary has them.
backlash, backlash_sigma : ndarray (6,) or None
    Hexapod, with backlash=True: the per-strut backlash.
squareness, squareness_names, squareness_sigma, hybrid, geometric_errors
    Exechon with hybrid data: szX2, sxP, syP, szP (rad), the hybrid fit's summary and the
    estimated geometric errors document (CAL.errors.json); None otherwise.
hybrid_holdout_errors_before, hybrid_holdout_errors_after : ndarray or None
    |error| of each held-out hybrid observation (NaN: a command the tripod cannot reach).
)doc";

constexpr const char* kCalibrationSaveDoc =
    R"doc(Writes the files `pkm calibrate KIND --out OUT` writes.

Hexapod: OUT (the calibrated machine JSON), OUT.hal (genhexkins setp block),
OUT.pkmhexkins.hal and OUT.summary.json (OUT without .json as the stem). Exechon: OUT,
OUT.summary.json and with hybrid data OUT.errors.json. The summary's "outputs" name them.

Returns
-------
list of str
    The paths written.

Raises
------
ValueError
    When a file exists and not `force` (nothing is written then), or cannot be written.)doc";

}  // namespace

const std::string& CalibrationResult::summaryJson() const {
  return std::visit([](const auto& r) -> const std::string& { return r.summary_json; }, *result);
}

std::string CalibrationResult::text() const {
  if (const auto* h = std::get_if<workflow::HexapodCalibrationResult>(result.get()))
    return workflow::hexapodCalibrationText(*hexapod_request, *h);
  return workflow::exechonCalibrationText(std::get<workflow::ExechonCalibrationResult>(*result));
}

CalibrationResult hexapodResult(workflow::HexapodCalibrationResult result,
                                const workflow::HexapodCalibrationRequest& request) {
  CalibrationResult out{"hexapod", {}, {}, {}};
  auto settings = std::make_shared<workflow::HexapodCalibrationRequest>(request);
  settings->data.clear();  // the text needs the settings only
  settings->holdout.clear();
  settings->loaded.reset();
  out.hexapod_request = std::move(settings);
  const py::dict doc = jsonLoads(result.summary_json);
  const cal::HexapodCalibrationSummary& s = result.report.fit;
  std::vector<std::string> columns;
  for (const int k : s.free_indices) columns.push_back(cal::hexapodParameterName(k));
  if (s.measurement_frame)
    columns.insert(
        columns.end(), cal::measurementFrameNames().begin(), cal::measurementFrameNames().end());
  if (s.backlash)
    columns.insert(columns.end(), cal::backlashNames().begin(), cal::backlashNames().end());
  const std::vector<std::string> names = hexapodNames();
  addFit(out.attributes, s, doc, names, result.report.free, columns, names);
  py::dict& a = out.attributes;
  a["backlash"] = s.backlash ? py::object(vectorArray(s.backlash->data(), 6)) : py::none();
  a["backlash_sigma"] =
      s.backlash ? py::object(vectorArray(s.backlash_standard_deviation.data(), 6)) : py::none();
  a["observations"] = doc["observations"];
  a["target_offset"] = vectorArray(result.report.target_offset.data(), 3);
  addHoldoutErrors(a, result.report.holdout);
  a["notices"] = result.notices;
  a["machine"] = py::cast(Hexapod{std::make_shared<const io::HexapodMachine>(result.calibrated)});
  out.result = std::make_shared<decltype(out.result)::element_type>(std::move(result));
  return out;
}

CalibrationResult exechonResult(workflow::ExechonCalibrationResult result) {
  CalibrationResult out{"exechon", {}, {}, {}};
  const py::dict doc = jsonLoads(result.summary_json);
  py::dict& a = out.attributes;
  if (result.report.tripod) {
    const io::ExechonTripodReport& t = *result.report.tripod;
    std::vector<std::string> columns;
    for (const int k : t.fit.free_indices) columns.push_back(exechonNames(k + 1).back());
    addFit(a,
           t.fit,
           doc,
           exechonNames(cal::kExechonParameters),
           t.free,
           columns,
           exechonNames(static_cast<int>(t.fit.covariance.rows())));
    a["observations"] = doc["observations"];
    a["target_offset"] = vectorArray(t.target_offset.data(), 3);
    addHoldoutErrors(a, t.holdout);
  } else {
    addNoFit(a);
    addHoldoutErrors(a, std::optional<io::HoldoutComparison>());
    a["observations"] = py::none();
    a["target_offset"] = py::none();
  }
  addHybrid(a, result, doc);
  a["machine"] = py::cast(Exechon{std::make_shared<const io::ExechonMachine>(result.calibrated)});
  out.result = std::make_shared<decltype(out.result)::element_type>(std::move(result));
  return out;
}

void exposeCalibrationResult(py::module_& m) {
  py::class_<CalibrationResult>(m, "CalibrationResult", kCalibrationResultDoc)
      .def_readonly("kind", &CalibrationResult::kind, "'hexapod' or 'exechon'.")
      .def("__getattr__",
           [](const CalibrationResult& r, const std::string& name) -> py::object {
             if (!r.attributes.contains(name))
               throw py::attribute_error("CalibrationResult has no attribute '" + name + "'");
             return r.attributes[py::str(name)];
           })
      .def("__dir__",
           [](const CalibrationResult& r) {
             py::list names;
             for (auto item : r.attributes) names.append(item.first);
             for (const char* s : {"kind", "to_dict", "to_json", "save"}) names.append(s);
             return names;
           })
      .def(
          "to_dict",
          [](const CalibrationResult& r) { return jsonLoads(r.summaryJson()); },
          "The summary document as dicts and lists: what `pkm calibrate KIND --json` prints "
          "(its `outputs` name the files once save() wrote them).")
      .def(
          "to_json",
          [](const CalibrationResult& r) { return r.summaryJson(); },
          "The summary document as text, byte for byte what the command line writes.")
      .def(
          "save",
          [](CalibrationResult& r, const py::object& out, bool force) {
            const std::string path = py::str(py::module_::import("os").attr("fspath")(out));
            std::vector<std::string> written;
            {
              py::gil_scoped_release release;
              std::visit(
                  [&](auto& res) {
                    using T = std::decay_t<decltype(res)>;
                    if constexpr (std::is_same_v<T, workflow::HexapodCalibrationResult>) {
                      workflow::writeHexapodCalibration(res, path, force);
                      const workflow::CalibrationOutputs o = workflow::calibrationOutputs(path);
                      written =
                          res.calibrated.world_frame_unregistered
                              ? std::vector<std::string>{o.machine, o.summary}
                              : std::vector<std::string>{o.machine, o.hal, o.pkmhexkins, o.summary};
                    } else {
                      workflow::writeExechonCalibration(res, path, force);
                      written = res.written;
                    }
                  },
                  *r.result);
            }
            return written;
          },
          py::arg("out"),
          py::arg("force") = false,
          kCalibrationSaveDoc)
      .def("__str__",
           &CalibrationResult::text,
           "The text summary `pkm calibrate KIND` prints, line for line (its \"wrote\" line "
           "once the files are written: out= or save()).")
      .def("__repr__", [](const CalibrationResult& r) {
        const py::dict& a = r.attributes;
        if (a["rank"].is_none())
          return std::string("<pkm.calibration.CalibrationResult exechon (hybrid)>");
        return py::str("<pkm.calibration.CalibrationResult {}: rank {}, residual RMS {} -> {}>")
            .format(r.kind, a["rank"], a["residuals_before"]["rms"], a["residuals_after"]["rms"])
            .cast<std::string>();
      });
}

}  // namespace pkm::python
