// pkm.gcode.make and pkm.gcode.shape_parameters: the composite machining commands as G-code
// (cnc/shapes.hpp; `pkm gcode make`, docs/gcode.md "gcode make").
#include <pybind11/stl.h>

#include <string>

#include "common.hpp"
#include "pkm/cnc/shapes.hpp"

namespace pkm::python {
namespace {

std::string make(const std::string& shape, double feed, const py::kwargs& values) {
  cnc::ShapeSpec spec{shape, {}};
  for (const auto& [key, value] : values)
    spec.values[py::cast<std::string>(key)] = py::cast<double>(value);
  return cnc::shapeProgram(spec, feed);
}

py::list parameters(const std::string& shape) {
  py::list out;
  for (const cnc::ShapeParameter& p : cnc::shapeParameters(shape))
    out.append(py::make_tuple(p.name, p.value, p.meaning));
  return out;
}

constexpr const char* kMakeDoc =
    R"doc(A composite machining command as a G-code program, as `pkm gcode make SHAPE`.

Parameters
----------
shape : {"sphere", "pocket", "drill", "face"}
    A hemisphere finished with a ball end (meridian arcs between its levels, never into the
    sphere), a circular pocket, holes on a circle, a face-milling zig-zag.
feed : float, default 600
    Feed rate, mm/min.
**values : float
    The shape's parameters by name (shape_parameters(shape) lists them with their defaults),
    e.g. radius=20, z=180, tool_radius=3, levels=6 for a sphere.

Returns
-------
str
    The program: "G21 G90 G17 F...", the shape's moves (the tool tip, absolute mm), "M2".

Raises
------
ValueError
    An unknown shape or parameter, a value out of range, or more than 200,000 lines.)doc";

}  // namespace

void exposeGcodeMake(py::module_& g) {
  g.def("make", &make, py::arg("shape"), py::kw_only(), py::arg("feed") = 600.0, kMakeDoc);
  g.def("shape_parameters",
        &parameters,
        py::arg("shape"),
        "The parameters of a shape of make(): (name, default, meaning) tuples, in order.");
}

}  // namespace pkm::python
