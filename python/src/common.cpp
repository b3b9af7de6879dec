// Array checks and conversions shared by the binding files (common.hpp).
#include "common.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "pkm/core/error.hpp"

namespace pkm::python {

namespace {

/// Throws pkm::InvalidArgument naming the first value that is not finite.
void checkFinite(const DoubleArray& a, py::ssize_t cols, const char* name) {
  const double* p = a.data();
  const auto n = static_cast<std::size_t>(a.size());
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(p[i])) {
      if (cols > 0)
        throw InvalidArgument(fmt::format("{}: row {} column {} is not a finite number ({})",
                                          name,
                                          i / static_cast<std::size_t>(cols),
                                          i % static_cast<std::size_t>(cols),
                                          p[i]));
      throw InvalidArgument(
          fmt::format("{}: element {} is not a finite number ({})", name, i, p[i]));
    }
  }
}

std::string shapeText(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) s += fmt::format("{}{}", i ? ", " : "", a.shape(i));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

}  // namespace

DoubleArray rowsOf(
    py::handle obj, py::ssize_t cols, const char* name, bool allow_single, bool* single) {
  if (obj.is_none()) throw InvalidArgument(fmt::format("{}: an array is required", name));
  DoubleArray a;
  try {
    a = DoubleArray::ensure(obj);
  } catch (const py::error_already_set&) {
  }
  if (!a) throw InvalidArgument(fmt::format("{}: not an array of numbers", name));
  if (single != nullptr) *single = false;
  if (a.ndim() == 1 && allow_single && a.shape(0) == cols) {
    if (single != nullptr) *single = true;
    a = a.reshape({py::ssize_t{1}, cols});
  } else if (a.ndim() != 2 || a.shape(1) != cols) {
    throw InvalidArgument(fmt::format("{}: expected an array of shape (N, {}){}, got shape {}",
                                      name,
                                      cols,
                                      allow_single ? fmt::format(" or ({},)", cols) : std::string(),
                                      shapeText(a)));
  }
  checkFinite(a, cols, name);
  return a;
}

DoubleArray vectorOf(py::handle obj, py::ssize_t n, const char* name) {
  if (obj.is_none()) throw InvalidArgument(fmt::format("{}: an array is required", name));
  DoubleArray a;
  try {
    a = DoubleArray::ensure(obj);
  } catch (const py::error_already_set&) {
  }
  if (!a) throw InvalidArgument(fmt::format("{}: not an array of numbers", name));
  if (a.ndim() != 1 || (n >= 0 && a.shape(0) != n))
    throw InvalidArgument(fmt::format("{}: expected {} values, got shape {}",
                                      name,
                                      n >= 0 ? fmt::format("{}", n) : std::string("a 1-D array of"),
                                      shapeText(a)));
  checkFinite(a, 0, name);
  return a;
}

py::array_t<double> newArray(py::ssize_t rows, py::ssize_t cols) {
  if (cols == 0) return py::array_t<double>(std::vector<py::ssize_t>{rows});
  return py::array_t<double>(std::vector<py::ssize_t>{rows, cols});
}

py::array statusArray(const std::vector<std::string_view>& words) {
  std::size_t width = 1;
  for (std::string_view w : words) width = std::max(width, w.size());
  py::array out(py::dtype(fmt::format("<U{}", width)),
                std::vector<py::ssize_t>{static_cast<py::ssize_t>(words.size())});
  auto* p = static_cast<char32_t*>(out.mutable_data());
  std::memset(static_cast<void*>(p), 0, words.size() * width * sizeof(char32_t));
  for (std::size_t i = 0; i < words.size(); ++i)
    std::copy(words[i].begin(), words[i].end(), p + i * width);  // ASCII status words
  return out;
}

py::object jsonLoads(const std::string& text) {
  return py::module_::import("json").attr("loads")(py::str(text));
}

py::object& convergenceError() {
  static py::object e;
  return e;
}

py::object& limitError() {
  static py::object e;
  return e;
}

void raiseOnFailure(const std::vector<std::string_view>& status, const char* what, bool limits) {
  for (std::size_t i = 0; i < status.size(); ++i) {
    if (status[i] != "ok") {
      const std::string message = fmt::format("{}: row {}: {}", what, i, status[i]);
      PyErr_SetString((limits ? limitError() : convergenceError()).ptr(), message.c_str());
      throw py::error_already_set();
    }
  }
}

void exposeErrors(py::module_& m) {
  convergenceError() = py::exception<std::runtime_error>(m, "ConvergenceError", PyExc_RuntimeError);
  convergenceError().attr("__doc__") =
      "An iterative solve (forward kinematics) did not reach an 'ok' status and the caller asked "
      "to raise (raise_on_failure=True). The message names the first failing row.";
  limitError() = py::exception<std::overflow_error>(m, "LimitError", PyExc_RuntimeError);
  limitError().attr("__doc__") =
      "A pose violates a machine limit (stroke, joint angle, interference, conditioning) or is "
      "unreachable, and the caller asked to raise (raise_on_failure=True).";
  // pkm's input errors are ValueError with pkm's message (pkm::InvalidArgument already is one,
  // as a std::invalid_argument).
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const IoError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });
}

}  // namespace pkm::python
