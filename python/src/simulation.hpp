/// @file
/// @brief The registration functions of the simulation, campaign and G-code bindings
/// (simulation.cpp, campaign.cpp, gcode.cpp).
#pragma once

#include "common.hpp"

namespace pkm::python {

void exposeSimulation(py::module_& m);
void exposeCampaign(py::module_& m);
void exposeGcode(py::module_& m);

}  // namespace pkm::python
