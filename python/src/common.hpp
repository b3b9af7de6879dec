/// @file
/// @brief What the binding files share: numpy array checks and conversions, status arrays, the
/// JSON documents of the library as Python objects, and the registration functions of each area.
/// No domain logic lives here: the bindings convert, check shapes and call the library.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace py = pybind11;

namespace pkm::python {

/// A C-contiguous float64 array (converted from any array-like on the way in).
using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// `obj` as an (N, cols) float64 array; a 1-D array of `cols` values is one row when
/// `allow_single` (then `*single` is set). Throws pkm::InvalidArgument (ValueError) naming
/// `name` for another shape or a value that is not finite.
[[nodiscard]] DoubleArray rowsOf(py::handle obj,
                                 py::ssize_t cols,
                                 const char* name,
                                 bool allow_single = true,
                                 bool* single = nullptr);

/// `obj` as a 1-D float64 array of exactly `n` finite values (n < 0: any length).
[[nodiscard]] DoubleArray vectorOf(py::handle obj, py::ssize_t n, const char* name);

/// A new (rows, cols) float64 array owned by numpy (cols 0: a 1-D array of `rows`).
[[nodiscard]] py::array_t<double> newArray(py::ssize_t rows, py::ssize_t cols = 0);

/// A numpy array of fixed-width unicode strings (dtype '<U…') from `words`, filled in C++.
[[nodiscard]] py::array statusArray(const std::vector<std::string_view>& words);

/// json.loads(text): a library JSON document as Python dicts, lists and numbers.
[[nodiscard]] py::object jsonLoads(const std::string& text);

/// Raises pkm.ConvergenceError (or pkm.LimitError when `limits`) naming the first row whose
/// status is not "ok", when there is one.
void raiseOnFailure(const std::vector<std::string_view>& status, const char* what, bool limits);

/// The exception types of the module (set by exposeErrors).
py::object& convergenceError();
py::object& limitError();

void exposeErrors(py::module_& m);
void exposeMachines(py::module_& m);
void exposeHexapod(py::module_& m);
void exposeExechon(py::module_& m);
void exposeMetrology(py::module_& m);
void exposeCalibration(py::module_& m);

}  // namespace pkm::python
