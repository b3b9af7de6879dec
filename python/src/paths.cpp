// File-name arguments from Python (paths.hpp).
#include "paths.hpp"

#include <fmt/format.h>

#include "pkm/core/error.hpp"

namespace pkm::python {

std::string pathOf(py::handle obj, const char* what) {
  if (!py::isinstance<py::str>(obj) && !py::hasattr(obj, "__fspath__"))
    throw InvalidArgument(
        fmt::format("{}: a file name (str or os.PathLike) is required, got {}",
                    what,
                    py::str(py::type::of(obj).attr("__name__")).cast<std::string>()));
  return py::str(py::module_::import("os").attr("fspath")(obj));
}

}  // namespace pkm::python
