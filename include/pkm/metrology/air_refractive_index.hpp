/// @file
/// @brief The refractive index of air in the metrology namespace: the modified Edlén equation
/// lives in pkm/core/air_refractive_index.hpp (core, so that the simulator, which cannot see
/// metrology, computes the true air's wavelength with the same function the budgets use).
#pragma once

#include "pkm/core/air_refractive_index.hpp"

namespace pkm::metrology {

using pkm::AirConditions;
using pkm::AirIndexSensitivity;
using pkm::edlenSensitivity;
using pkm::kHeNeVacuumWavelengthUm;
using pkm::refractiveIndexEdlen;
using pkm::saturationVapourPressure;

}  // namespace pkm::metrology
