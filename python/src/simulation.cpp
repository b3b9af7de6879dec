// pkm.simulate and pkm.scenarios: `pkm simulate` as arrays (workflow::simulateScenario,
// simulateScenarioText, writeSimulation). The measurement files the command writes are made by
// the workflow and read back by io::TextTable (columns.hpp), so the arrays hold the printed values.
#include "simulation.hpp"

#include <fmt/format.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "columns.hpp"
#include "common.hpp"
#include "paths.hpp"
#include "pkm/core/error.hpp"
#include "pkm/workflow/simulate.hpp"

namespace pkm::python {
namespace {

/// pkm.Simulation: what a simulation produced, as Python objects, and the files to write.
struct Simulation {
  workflow::SimulateResult result;
  py::dict tables;    ///< file stem -> {column: array}
  py::dict metadata;  ///< file stem -> {key: value}
  py::dict files;     ///< file name -> text
  py::object truth;
  py::object scenario_doc;
};

/// A seed from Python: None, or an integer in [0, 2^64).
std::optional<std::uint64_t> seedOf(const py::object& seed) {
  if (seed.is_none()) return std::nullopt;
  if (!py::isinstance<py::int_>(seed) || py::isinstance<py::bool_>(seed))
    throw InvalidArgument("seed: an integer is required");
  const unsigned long long v = PyLong_AsUnsignedLongLong(seed.ptr());
  if (PyErr_Occurred() != nullptr) {
    PyErr_Clear();
    throw InvalidArgument(
        fmt::format("seed: {} is not an integer in [0, 2^64)", py::str(seed).cast<std::string>()));
  }
  return static_cast<std::uint64_t>(v);
}

/// The workflow's result turned into tables, metadata and documents.
Simulation simulationOf(workflow::SimulateResult result) {
  Simulation s;
  for (const workflow::SimulatedFile& f : result.files) {
    s.files[py::str(f.name)] = py::str(f.text);
    const std::filesystem::path name(f.name);
    if (f.name == "truth.json") {
      s.truth = jsonLoads(f.text);
    } else if (f.name == "scenario.json") {
      s.scenario_doc = jsonLoads(f.text);
    } else if (name.extension() == ".csv") {
      const io::TextTable table = io::TextTable::parse(f.text, f.name);
      const py::str stem(name.stem().string());
      s.tables[stem] = columnsOf(table);
      s.metadata[stem] = metadataOf(table);
    }
  }
  s.result = std::move(result);
  return s;
}

Simulation simulate(const py::object& scenario,
                    const py::object& seed_obj,
                    const py::object& out,
                    bool force) {
  const std::optional<std::uint64_t> seed = seedOf(seed_obj);
  workflow::SimulateResult result;
  if (py::isinstance<py::dict>(scenario)) {
    const io::NamedText text{"scenario",
                             py::module_::import("json")
                                 .attr("dumps")(scenario, py::arg("indent") = 2)
                                 .cast<std::string>()};
    py::gil_scoped_release release;
    result = workflow::simulateScenarioText(text, seed, std::filesystem::current_path().string());
  } else {
    const std::string spec = pathOf(scenario, "scenario (a built-in name, a file or a dict)");
    py::gil_scoped_release release;
    result = workflow::simulateScenario(spec, seed);
  }
  if (!out.is_none()) {
    const std::string dir = pathOf(out, "out");
    py::gil_scoped_release release;
    workflow::writeSimulation(result, dir, force);
  }
  return simulationOf(std::move(result));
}

/// Registers pkm.Simulation in `m`.
void defSimulationClass(py::module_& m) {
  py::class_<Simulation>(m,
                         "Simulation",
                         "What pkm.simulate produced: the measurement tables of every simulated "
                         "measurement (as `pkm simulate` writes them), the truth and the scenario.")
      .def_property_readonly(
          "scenario", [](const Simulation& s) { return s.result.scenario; }, "The scenario's name.")
      .def_property_readonly(
          "seed", [](const Simulation& s) { return s.result.seed; }, "The random seed used.")
      .def_readonly("tables",
                    &Simulation::tables,
                    "dict: file stem (e.g. 'linear-x_run1', 'tracker-pose') -> {column: array}. "
                    "Numeric columns are float64 in the file's units (the column names say "
                    "which: target_mm, reading_mm, ...; empty fields are NaN); text columns "
                    "(directions '+'/'-') are string arrays.")
      .def_readonly("metadata",
                    &Simulation::metadata,
                    "dict: file stem -> {key: value} of the file's '# key: value' header lines "
                    "(instrument, noise, setup, frames).")
      .def_readonly(
          "truth", &Simulation::truth, "dict: truth.json, the injected errors (docs/formats.md).")
      .def_readonly("scenario_doc",
                    &Simulation::scenario_doc,
                    "dict: scenario.json, the scenario with the seed used (simulating it again "
                    "reproduces every file).")
      .def_readonly("files",
                    &Simulation::files,
                    "dict: file name -> text, every file `pkm simulate --out DIR` writes, in "
                    "the order written.")
      .def(
          "write",
          [](const Simulation& s, const py::object& out, bool force) {
            const std::string dir = pathOf(out, "out");
            py::gil_scoped_release release;
            workflow::writeSimulation(s.result, dir, force);
          },
          py::arg("out"),
          py::arg("force") = false,
          R"doc(Writes the files into the folder `out` (created), as `pkm simulate --out`.

Raises
------
ValueError
    "PATH: exists; refusing to overwrite (use --force)" when a file exists and not `force`
    (nothing is written then).)doc")
      .def("__repr__", [](const Simulation& s) {
        return fmt::format("<pkm.Simulation '{}' seed {}: {} tables>",
                           s.result.scenario,
                           s.result.seed,
                           py::len(s.tables));
      });
}

}  // namespace

void exposeSimulation(py::module_& m) {
  defSimulationClass(m);

  m.def("simulate",
        &simulate,
        py::arg("scenario"),
        py::arg("seed") = py::none(),
        py::arg("out") = py::none(),
        py::arg("force") = false,
        R"doc(Simulates every measurement of a scenario on its virtual machine, as `pkm simulate`.

Parameters
----------
scenario : str, os.PathLike or dict
    A built-in scenario's name (see scenarios()), a scenario JSON file, or the scenario document
    itself as a dict (the file format, docs/formats.md "Scenario files"; relative file names in it
    are taken from the current directory; messages name it "scenario").
seed : int, optional
    The random seed (>= 0); default the scenario's "seed". The same scenario and seed give the
    same numbers as `pkm simulate SCENARIO --seed N`.
out : str or os.PathLike, optional
    Also write the files into this folder (created), as `pkm simulate --out`.
force : bool, default False
    Replace existing files in `out`.

Returns
-------
Simulation
    `.tables[stem]` is a dict of columns per measurement file (numbers as float64 arrays in the
    file's units, mm and the instrument's frame as its metadata states), `.metadata[stem]` its
    header, `.truth` the injected errors, `.files` every file's text.

Raises
------
ValueError
    An unknown scenario name or a bad scenario (pkm's message, "FILE:LINE: /pointer: ..."), a
    negative seed, or existing files in `out` without `force`.)doc");

  m.def(
      "scenarios",
      [] {
        py::list out;
        for (const workflow::ScenarioInfo& s : workflow::listScenarios()) {
          py::dict d;
          d["name"] = s.name;
          d["measurements"] = s.measurements;
          d["description"] = s.description;
          out.append(d);
        }
        return out;
      },
      "The built-in scenarios (`pkm simulate --list`): a list of dicts with name, measurements "
      "and description.");
}

}  // namespace pkm::python
