// Areas not bound yet (docs/python.md, "Not yet bound").
#include "common.hpp"

namespace pkm::python {

void exposeCalibration(py::module_&) {}
void exposeSimulation(py::module_&) {}
void exposeGcode(py::module_&) {}

}  // namespace pkm::python
