// pkm.metrology: every `pkm analyze <kind>` as a function of arrays. Each builds the kind's
// workflow request from the tables (tables.hpp), calls the workflow and returns an
// AnalysisResult made from the command's --json document (io::analysisJson) and its table
// (io::analysisText): the attributes are the document's keys, so they cannot drift from the CLI.
#include <fmt/format.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <optional>

#include "common.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/analysis_text.hpp"
#include "pkm/io/export_columns.hpp"
#include "pkm/workflow/analyze_circle.hpp"
#include "pkm/workflow/analyze_diagonals.hpp"
#include "pkm/workflow/analyze_positioning.hpp"
#include "tables.hpp"

namespace pkm::python {
namespace {

/// The result of an analysis: the --json document and the table the command prints.
struct AnalysisResult {
  std::string kind;
  py::dict doc;
  std::string text;
};

template <typename Report>
AnalysisResult resultOf(const char* kind, const Report& report) {
  return {kind, jsonLoads(io::analysisJson(report)), io::analysisText(report)};
}

/// A JSON value for attribute access: a list of numbers (or nulls) as a float array.
py::object attributeValue(const py::object& v) {
  if (!py::isinstance<py::list>(v) || py::len(v) == 0) return v;
  for (py::handle item : v)
    if (!(item.is_none() || py::isinstance<py::float_>(item) || py::isinstance<py::int_>(item)) ||
        py::isinstance<py::bool_>(item))
      return v;
  py::list copy;
  for (py::handle item : v)
    copy.append(item.is_none() ? py::float_(std::numeric_limits<double>::quiet_NaN())
                               : py::float_(py::reinterpret_borrow<py::object>(item)));
  return py::module_::import("numpy").attr("array")(copy, "float64");
}

metrology::StraightnessReference referenceOf(const std::string& name) {
  return metrology::parseStraightnessReference(name);
}

/// Runs a workflow with the GIL released.
template <typename F>
auto released(F&& f) {
  py::gil_scoped_release release;
  return f();
}

AnalysisResult iso230_2(py::handle data,
                        double coverage,
                        const std::optional<std::string>& columns,
                        const std::optional<std::string>& unit,
                        const std::optional<std::string>& error_unit,
                        const std::optional<std::string>& machine,
                        bool strict) {
  workflow::Iso230_2Request r;
  r.data = tablesOf(data, "data", {"target", "direction", "run", "measured"});
  if (columns) r.columns.columns = io::parseColumnAssignments(*columns);
  if (unit) r.columns.unit = *unit;
  if (error_unit) r.columns.error_unit = *error_unit;
  if (machine) r.machine = *machine;
  r.coverage = coverage;
  r.strict = strict;
  return resultOf("iso230_2", released([&] { return workflow::analyzeIso230_2(r); }));
}

AnalysisResult straightness(py::handle data, const std::string& reference) {
  workflow::StraightnessRequest r{tablesOf(data, "data", {"position", "deviation"}),
                                  referenceOf(reference)};
  return resultOf("straightness", released([&] { return workflow::analyzeStraightness(r); }));
}

AnalysisResult parallelism(py::handle reference,
                           py::handle axis,
                           int reference_sign,
                           int axis_sign,
                           const std::string& line,
                           const std::string& plane,
                           std::optional<double> szX2) {
  workflow::ParallelismRequest r;
  r.reference = tablesOf(reference, "reference", {"position", "deviation"});
  r.axis = tablesOf(axis, "axis", {"position", "deviation"});
  r.reference_sign = reference_sign;
  r.axis_sign = axis_sign;
  r.line = referenceOf(line);
  if (plane != "horizontal" && plane != "vertical")
    throw InvalidArgument(fmt::format("plane '{}': expected horizontal or vertical", plane));
  r.plane =
      plane == "horizontal" ? io::ParallelismPlane::kHorizontal : io::ParallelismPlane::kVertical;
  r.szX2 = szX2;
  return resultOf("parallelism", released([&] { return workflow::analyzeParallelism(r); }));
}

AnalysisResult squareness(py::handle data,
                          py::handle start,
                          const std::optional<py::dict>& pdge,
                          const std::vector<std::string>& axes,
                          bool fit_scale,
                          bool first_moves_work,
                          bool second_moves_work) {
  workflow::SquarenessRequest r;
  r.data = tablesOf(data, "data", {"u", "v", "deviation"});
  if (!start.is_none()) {
    const DoubleArray s = rowsOf(start, 2, "start", true);
    for (py::ssize_t i = 0; i < s.shape(0); ++i)
      r.start.push_back({s.data()[2 * i], s.data()[2 * i + 1]});
  }
  if (pdge) {
    for (auto [key, table] : *pdge) {
      const std::string k = py::str(key);
      if (k.size() != 2 || (k[0] != 'u' && k[0] != 'v') || (k[1] != 'u' && k[1] != 'v'))
        throw InvalidArgument(fmt::format("pdge '{}': expected the keys uu, uv, vv or vu", k));
      r.pdge.push_back({k[0] == 'u' ? 0 : 1,
                        k[1] == 'u' ? 0 : 1,
                        tableOf(table, fmt::format("pdge[{}]", k), {"position", "deviation"})});
    }
  }
  r.axes = axes;
  r.fit_scale = fit_scale;
  r.first_moves_work = first_moves_work;
  r.second_moves_work = second_moves_work;
  return resultOf("squareness", released([&] { return workflow::analyzeSquareness(r); }));
}

AnalysisResult diagonals(py::handle data,
                         py::handle size,
                         const std::string& method,
                         double coverage,
                         py::handle compare) {
  workflow::DiagonalsRequest r;
  r.data = tablesOf(data, "data", {});
  if (method == "body")
    r.method = io::DiagonalMethod::kBody;
  else if (method == "step")
    r.method = io::DiagonalMethod::kStep;
  else if (method == "shifted")
    r.method = io::DiagonalMethod::kShifted;
  else
    throw InvalidArgument(fmt::format("method '{}': expected body, shifted or step", method));
  r.size = Eigen::Vector3d(vectorOf(size, 3, "size").data());
  r.coverage = coverage;
  if (!compare.is_none()) r.compare = tablesOf(compare, "compare", {});
  return resultOf("diagonals", released([&] { return workflow::analyzeDiagonals(r); }));
}

/// An (N, 2) array as points read where they are: float64, C order and aligned as Eigen's 2-vectors
/// need (a copy in that form otherwise). Nothing for anything that is not such an array.
std::optional<py::array> circlePoints(py::handle data) {
  if (!py::isinstance<py::array>(data)) return std::nullopt;
  py::array a = py::reinterpret_borrow<py::array>(data);
  if (a.ndim() != 2 || a.shape(1) != 2 || a.shape(0) == 0) return std::nullopt;
  constexpr auto kForm = py::array::c_style | py::array::forcecast;
  py::array_t<double, kForm> v = py::array_t<double, kForm>::ensure(a);
  if (!v) throw InvalidArgument("data: an (N, 2) array of numbers is needed");
  if (reinterpret_cast<std::uintptr_t>(v.data()) % alignof(metrology::Point2) != 0)
    v = py::array_t<double, kForm>(v.request());  // a misaligned view: copied once
  return std::move(v);
}

AnalysisResult circle(py::handle data, const std::string& fit, bool budget) {
  workflow::CircleRequest r;
  r.fit = fit;
  r.budget = budget;
  const std::optional<py::array> points = circlePoints(data);
  if (points) {
    r.points = {reinterpret_cast<const metrology::Point2*>(points->data()),
                static_cast<std::size_t>(points->shape(0))};
  } else {
    r.data = tablesOf(data, "data", {"x", "y"});
  }
  return resultOf("circle", released([&] { return workflow::analyzeCircle(r); }));
}

AnalysisResult circular(py::handle data,
                        const std::string& centre,
                        py::handle nominal_center,
                        std::optional<double> nominal_radius) {
  workflow::CircularRequest r;
  r.data = tablesOf(data, "data", {"x", "y"});
  if (centre == "lsc")
    r.centre = metrology::CircularCentre::kLeastSquares;
  else if (centre == "mzc")
    r.centre = metrology::CircularCentre::kMinimumZone;
  else if (centre == "nominal")
    r.centre = metrology::CircularCentre::kNominal;
  else
    throw InvalidArgument(fmt::format("centre '{}': expected lsc, mzc or nominal", centre));
  if (!nominal_center.is_none()) {
    const DoubleArray c = vectorOf(nominal_center, 2, "nominal_center");
    r.nominal_center = metrology::Point2(c.data()[0], c.data()[1]);
  }
  r.nominal_radius = nominal_radius;
  return resultOf("circular", released([&] { return workflow::analyzeCircular(r); }));
}

AnalysisResult probeOffset(py::handle data,
                           std::optional<double> ring_diameter,
                           std::optional<double> stylus_diameter,
                           const std::string& tool_direction) {
  if (tool_direction != "-z" && tool_direction != "+z")
    throw InvalidArgument(fmt::format("tool_direction '{}': expected -z or +z", tool_direction));
  workflow::ProbeOffsetRequest r{tablesOf(data, "data", {"spindle_deg", "x", "y"}),
                                 ring_diameter,
                                 stylus_diameter,
                                 tool_direction == "+z"};
  return resultOf("probe_offset", released([&] { return workflow::analyzeProbeOffset(r); }));
}

constexpr const char* kTables = R"doc(
Tables (data, reference, axis, compare) are each a dict {column name: 1-D array or list of
strings} with the columns `pkm analyze` reads (docs/analysis.md), an (N, k) array with the
default columns named below, or a file path; a list of tables is read concatenated as several
--data files. Messages name a table as data[I] and its rows as lines (line 2 is row 0).

Returns
-------
AnalysisResult
    Attributes are the keys of the command's --json document (lists of numbers as float
    arrays); to_dict() gives the document, str() the command's table.

Raises
------
ValueError
    For bad input, with pkm's message.)doc";

std::string doc(const char* head) { return std::string(head) + kTables; }

/// Registers pkm.metrology.AnalysisResult in `mm`.
void defAnalysisResult(py::module_& mm) {
  py::class_<AnalysisResult>(mm,
                             "AnalysisResult",
                             "The result of a pkm.metrology analysis: attributes are the keys of "
                             "the `pkm analyze KIND --json` document.")
      .def_readonly("kind", &AnalysisResult::kind)
      .def("__getattr__",
           [](const AnalysisResult& r, const std::string& name) -> py::object {
             if (!r.doc.contains(name))
               throw py::attribute_error(
                   fmt::format("'{}' result has no attribute '{}'", r.kind, name));
             return attributeValue(r.doc[name.c_str()]);
           })
      .def("__dir__",
           [](const AnalysisResult& r) {
             py::list keys;
             for (auto [k, v] : r.doc) keys.append(k);
             keys.append("kind");
             keys.append("to_dict");
             return keys;
           })
      .def("keys", [](const AnalysisResult& r) { return r.doc.attr("keys")(); })
      .def(
          "to_dict",
          [](const AnalysisResult& r) {
            return py::module_::import("copy").attr("deepcopy")(r.doc);
          },
          "The --json document as a dict (a copy).")
      .def("__str__", [](const AnalysisResult& r) { return r.text; })
      .def("__repr__", [](const AnalysisResult& r) {
        std::string keys;
        for (auto [k, v] : r.doc) keys += (keys.empty() ? "" : ", ") + std::string(py::str(k));
        return fmt::format("<pkm.metrology.AnalysisResult {}: {}>", r.kind, keys);
      });
}

/// Registers iso230_2, straightness, parallelism and squareness in `mm`.
void defAxisAnalyses(py::module_& mm) {
  mm.def("iso230_2",
         &iso230_2,
         py::arg("data"),
         py::arg("coverage") = 2.0,
         py::arg("columns") = py::none(),
         py::arg("unit") = py::none(),
         py::arg("error_unit") = py::none(),
         py::arg("machine") = py::none(),
         py::arg("strict") = false,
         doc("ISO 230-2 positioning accuracy and repeatability of one axis (`pkm analyze "
             "iso230-2`).\n\nArray columns: target, direction (+1/-1), run, measured (mm). "
             "coverage: factor k; columns: 'role=COLUMN,...' assignments; unit, error_unit: of "
             "columns whose header states none; machine: a machine spec (inch check); strict: "
             "refuse non-conforming data.")
             .c_str());
  mm.def("straightness",
         &straightness,
         py::arg("data"),
         py::arg("reference") = "lsq",
         doc("Straightness about a reference line (`pkm analyze straightness`).\n\nArray "
             "columns: position, deviation (length unit). reference: 'endpoint', 'lsq' or "
             "'minzone'.")
             .c_str());
  mm.def("parallelism",
         &parallelism,
         py::arg("reference"),
         py::arg("axis"),
         py::arg("reference_sign") = 1,
         py::arg("axis_sign") = 1,
         py::arg("line") = "lsq",
         py::arg("plane") = "horizontal",
         py::arg("szX2") = py::none(),
         doc("Parallelism of an axis to a reference axis from two straightness runs along one "
             "beam (`pkm analyze parallelism`, seed 000 §3.1).\n\nArray columns: position, "
             "deviation. Signs +1/-1; line 'endpoint'/'lsq'; plane 'horizontal'/'vertical'; "
             "szX2 in rad.")
             .c_str());
  mm.def("squareness",
         &squareness,
         py::arg("data"),
         py::arg("start") = py::none(),
         py::arg("pdge") = py::none(),
         py::arg("axes") = std::vector<std::string>{},
         py::arg("fit_scale") = false,
         py::arg("first_moves_work") = false,
         py::arg("second_moves_work") = false,
         doc("Face-diagonal squareness (`pkm analyze squareness`, seed 000 eqs 4-10): one table "
             "per diagonal.\n\nArray columns: u, v, deviation. start: (D, 2) axis positions at "
             "each diagonal's start; pdge: {'uu'|'uv'|'vv'|'vu': table (position, deviation)}; "
             "axes: the two axes of simulator files.")
             .c_str());
}

/// Registers diagonals, circle, circular and probe_offset in `mm`.
void defDiagonalAndCircleAnalyses(py::module_& mm) {
  mm.def("diagonals",
         &diagonals,
         py::arg("data"),
         py::arg("size"),
         py::arg("method") = "body",
         py::arg("coverage") = 2.0,
         py::arg("compare") = py::none(),
         doc("Body, shifted or step diagonals (`pkm analyze diagonals`).\n\nTables are dicts or "
             "files (the diagonal column holds names such as PPP). size: the box LX, LY, LZ "
             "(mm); method 'body', 'shifted' or 'step'; compare: XY line files (step, shifted).")
             .c_str());
  mm.def("circle",
         &circle,
         py::arg("data"),
         py::kw_only(),
         py::arg("fit") = "both",
         py::arg("budget") = true,
         doc("Least-squares and minimum-zone circles and roundness (`pkm analyze circle`).\n\n"
             "Array columns: x, y (length unit), e.g. circle(xy) with xy of shape (N, 2); an "
             "(N, 2) float64 array is read where it is, not copied. fit: 'lsc' (the "
             "least-squares circle alone, the fastest), 'mzc' (the minimum-zone circle alone) or "
             "'both' (`--fit`). budget: False leaves the uncertainty budgets out (their probe and "
             "unit assumptions do not fit unitless points).")
             .c_str());
  mm.def("circular",
         &circular,
         py::arg("data"),
         py::arg("centre") = "lsc",
         py::arg("nominal_center") = py::none(),
         py::arg("nominal_radius") = py::none(),
         doc("ISO 230-4 circular test (`pkm analyze circular`): one table with a direction "
             "column (cw/ccw), or a list of two x, y tables (CW then CCW).\n\ncentre: 'lsc', "
             "'mzc' or 'nominal'; nominal_center (x, y); nominal_radius R0 (enables F).")
             .c_str());
  mm.def("probe_offset",
         &probeOffset,
         py::arg("data"),
         py::arg("ring_diameter") = py::none(),
         py::arg("stylus_diameter") = py::none(),
         py::arg("tool_direction") = "-z",
         doc("Touch-probe stylus offset (`pkm analyze probe-offset`, seed 003).\n\nArray columns: "
             "spindle_deg, x, y; dicts may add drm_deg, touch (+x, -x, +y, -y) and run. "
             "ring_diameter, stylus_diameter in mm; tool_direction '-z' or '+z'.")
             .c_str());
}

}  // namespace

void exposeMetrology(py::module_& m) {
  py::module_ mm = m.def_submodule(
      "metrology",
      "Measurement analysis: one function per `pkm analyze <kind>` (docs/analysis.md).");
  defAnalysisResult(mm);
  defAxisAnalyses(mm);
  defDiagonalAndCircleAnalyses(mm);
}

}  // namespace pkm::python
