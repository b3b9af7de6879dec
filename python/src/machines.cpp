// pkm.load_machine and pkm.builtin_machines: the machine loaders of the command line's --machine
// (io::machineTypeOf, io::loadHexapodMachine, io::loadExechonMachine).
#include "machines.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "common.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/machine_loader.hpp"

namespace pkm::python {

void exposeMachines(py::module_& m) {
  m.def(
      "load_machine",
      [](const py::object& spec_obj, const std::optional<std::string>& ini) -> py::object {
        const std::string spec = py::str(py::module_::import("os").attr("fspath")(spec_obj));
        const std::vector<std::string> builtin = io::builtinMachineNames("");
        if (!std::filesystem::exists(spec) &&
            std::find(builtin.begin(), builtin.end(), spec) == builtin.end())
          throw InvalidArgument(
              fmt::format("{}: no such file, and not a built-in machine (built-in: {})",
                          spec,
                          fmt::join(builtin, ", ")));
        if (io::machineTypeOf(spec) == "exechon")
          return py::cast(
              Exechon{std::make_shared<const io::ExechonMachine>(io::loadExechonMachine(spec))});
        io::HalReadOptions hal;
        if (ini) hal.ini_path = *ini;
        return py::cast(
            Hexapod{std::make_shared<const io::HexapodMachine>(io::loadHexapodMachine(spec, hal))});
      },
      py::arg("name_or_path") = io::kDefaultMachine,
      py::arg("ini") = py::none(),
      R"doc(Loads a machine as the command line's --machine does.

Parameters
----------
name_or_path : str or os.PathLike, default "hexapod-default"
    A path ending in .hal (a LinuxCNC genhexkins configuration; the INI from `ini` or found
    through [HAL] HALFILE), an existing pkm JSON machine file (hexapod or Exechon, by its
    "type"), a pkm calibration file, or a built-in name (see builtin_machines()).
ini : str, optional
    The LinuxCNC INI file of a .hal machine.

Returns
-------
Hexapod or Exechon

Raises
------
ValueError
    For an unknown name or a bad file, with pkm's message (FILE:LINE: ...).)doc");
  m.def(
      "builtin_machines",
      [](const std::string& type) { return io::builtinMachineNames(type); },
      py::arg("type") = "",
      "Names of the built-in machines: of one type ('hexapod', 'exechon') or of every type ('').");
}

}  // namespace pkm::python
