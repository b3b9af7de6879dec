/// @file
/// @brief The dependent rotational motion part of pkm.Exechon (exechon_drm_circle.cpp):
/// drm_circle, registered by exposeExechon (exechon.cpp).
#pragma once

#include "common.hpp"
#include "machines.hpp"

namespace pkm::python {

/// Registers pkm.Exechon's drm_circle on `cls`.
void defExechonDrmCircle(py::class_<Exechon>& cls);

}  // namespace pkm::python
