/// @file
/// @brief The geometry part of pkm.Hexapod (hexapod_geometry.cpp): the joint, offset, stroke, tool
/// and home properties and with_geometry, and fk_file (hexapod_fk_file.cpp), registered by
/// exposeHexapod (hexapod.cpp).
#pragma once

#include "common.hpp"
#include "machines.hpp"

namespace pkm::python {

/// Registers pkm.Hexapod's geometry properties (base_joints ... home) and with_geometry on `cls`.
void defHexapodGeometry(py::class_<Hexapod>& cls);

/// Registers pkm.Hexapod.fk_file (hexapod_fk_file.cpp): `pkm hexapod fk` on a file.
void defHexapodFkFile(py::class_<Hexapod>& cls);

}  // namespace pkm::python
