/// @file
/// @brief File-name arguments from Python (str or os.PathLike), for the simulation, campaign and
/// G-code bindings.
#pragma once

#include <string>

#include "common.hpp"

namespace pkm::python {

/// os.fspath(obj) as a str. Throws pkm::InvalidArgument (ValueError) "WHAT: a file name (str or
/// os.PathLike) is required, got TYPE" for another type.
[[nodiscard]] std::string pathOf(py::handle obj, const char* what);

/// pathOf(obj, what), or "" for None (an optional file argument not given).
[[nodiscard]] inline std::string optionalPath(const py::object& obj, const char* what) {
  return obj.is_none() ? std::string() : pathOf(obj, what);
}

}  // namespace pkm::python
