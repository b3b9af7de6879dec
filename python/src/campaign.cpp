// pkm.run_campaign and pkm.campaigns: `pkm campaign run|list` (workflow::runCampaign,
// workflow::describeCampaign); the summary is the summary.json the workflow wrote.
#include "pkm/workflow/campaign.hpp"

#include <fmt/format.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "common.hpp"
#include "paths.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/environment_file.hpp"
#include "pkm/io/named_text.hpp"
#include "pkm/io/uncertainty_sources.hpp"
#include "pkm/workflow/campaign_sensitivity.hpp"
#include "simulation.hpp"

namespace pkm::python {
namespace {

/// pkm.CampaignSummary: summary.json as a Python object, with the run's figures.
struct CampaignSummary {
  py::dict doc;  ///< summary.json
  workflow::CampaignResult result;
};

/// A summary row key as an array over the rows: numbers and nulls as float64 (null: NaN),
/// anything else as numpy makes it (strings, booleans).
py::object summaryColumnOf(const CampaignSummary& s, const std::string& key) {
  const py::list rows = s.doc["rows"];
  py::list values;
  bool numeric = true;
  for (py::handle row : rows) {
    const py::dict d = py::reinterpret_borrow<py::dict>(row);
    if (!d.contains(key.c_str()))
      throw InvalidArgument(fmt::format("CampaignSummary.column: no row key '{}'", key));
    const py::object v = d[key.c_str()];
    numeric = numeric &&
              (v.is_none() || ((py::isinstance<py::float_>(v) || py::isinstance<py::int_>(v)) &&
                               !py::isinstance<py::bool_>(v)));
    values.append(v);
  }
  const py::module_ np = py::module_::import("numpy");
  if (!numeric) return np.attr("array")(values);
  py::list floats;
  for (py::handle v : values)
    floats.append(v.is_none() ? py::float_(std::numeric_limits<double>::quiet_NaN())
                              : py::float_(py::reinterpret_borrow<py::object>(v)));
  return np.attr("array")(floats, "float64");
}

/// A Python progress callback for the workflow: called with the GIL taken; an exception in it,
/// or a pending signal (Ctrl-C), cancels the run and is raised when the workflow has stopped.
struct PythonProgress {
  py::object callback;
  workflow::CancellationToken token;
  py::object error;  ///< the exception that cancelled the run (with the GIL only)

  void operator()(const workflow::ProgressEvent& e) {
    py::gil_scoped_acquire gil;
    try {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      if (!callback.is_none()) {
        py::dict d;
        d["stage"] = e.stage;
        d["index"] = e.index;
        d["count"] = e.count;
        d["elapsed"] = e.elapsed;
        d["message"] = e.message;
        callback(d);
      }
    } catch (py::error_already_set& err) {
      error = err.value();
      token.cancel();
    }
  }
};

/// The campaign-level settings (docs/campaign.md): environment a preset name or a file,
/// uncertainty a sources file, seed an int; None keeps each step's own.
void applySettings(workflow::CampaignOptions& o,
                   const py::object& environment,
                   const py::object& uncertainty,
                   const py::object& seed) {
  if (!environment.is_none()) {
    o.environment_source = pathOf(environment, "environment (a preset name or a file)");
    o.environment = io::loadEnvironment(o.environment_source);
  }
  if (!uncertainty.is_none()) {
    o.uncertainty_source = pathOf(uncertainty, "uncertainty (a sources file)");
    o.uncertainty = io::readUncertaintySources(io::readNamedText(o.uncertainty_source));
  }
  if (!seed.is_none()) o.seed = seed.cast<std::uint64_t>();
}

CampaignSummary runCampaign(const py::object& campaign,
                            const py::object& out,
                            bool force,
                            const py::object& db,
                            const py::object& progress,
                            const py::object& environment,
                            const py::object& uncertainty,
                            const py::object& seed) {
  workflow::CampaignOptions o;
  if (py::isinstance<py::dict>(campaign)) {
    o.campaign = "campaign";  // names the document in messages and summary.json's source
    o.campaign_text = py::module_::import("json")
                          .attr("dumps")(campaign, py::arg("indent") = 2)
                          .cast<std::string>();
  } else {
    o.campaign = pathOf(campaign, "campaign (a built-in name, a file or a dict)");
  }
  o.out = pathOf(out, "out");
  o.force = force;
  if (!db.is_none()) o.db = pathOf(db, "db");
  applySettings(o, environment, uncertainty, seed);
  PythonProgress watcher{progress, {}, py::none()};
  workflow::RunControl control;
  control.progress = [&watcher](const workflow::ProgressEvent& e) { watcher(e); };
  control.cancel = &watcher.token;
  CampaignSummary s;
  try {
    py::gil_scoped_release release;
    s.result = workflow::runCampaign(o, control);
  } catch (const workflow::Cancelled&) {
    if (!watcher.error.is_none()) {
      PyErr_SetObject(reinterpret_cast<PyObject*>(Py_TYPE(watcher.error.ptr())),
                      watcher.error.ptr());
      throw py::error_already_set();
    }
    throw;
  }
  s.doc = jsonLoads(s.result.summary_json);
  return s;
}

/// `pkm campaign sensitivity`: the study's sensitivity.json as a dict.
py::dict campaignSensitivity(const py::object& campaign,
                             const std::string& source,
                             const std::vector<double>& values,
                             const py::object& out,
                             const py::object& environment,
                             const py::object& uncertainty,
                             const py::object& seed,
                             bool force) {
  workflow::SensitivityOptions o;
  o.campaign = pathOf(campaign, "campaign (a built-in name or a file)");
  o.source = source;
  o.values = values;
  o.out = pathOf(out, "out");
  o.force = force;
  if (!environment.is_none()) {
    o.base_source = pathOf(environment, "environment (a preset name or a file)");
    o.base = io::loadEnvironment(o.base_source);
  }
  if (!uncertainty.is_none()) {
    o.uncertainty_source = pathOf(uncertainty, "uncertainty (a sources file)");
    o.uncertainty = io::readUncertaintySources(io::readNamedText(o.uncertainty_source));
  }
  if (!seed.is_none()) o.seed = seed.cast<std::uint64_t>();
  workflow::SensitivityResult r;
  {
    py::gil_scoped_release release;
    r = workflow::runSensitivity(o);
  }
  return jsonLoads(r.json);
}

/// Registers pkm.CampaignSummary in `m`.
void defCampaignSummary(py::module_& m) {
  py::class_<CampaignSummary>(
      m,
      "CampaignSummary",
      "A campaign's summary.json (pkm.campaign-summary/1, docs/campaign.md) as attributes: "
      "schema, campaign, source, rows (a list of dicts: step, quantity, unit, before, after, "
      "target, paper, noise, pass, before_U, after_U, significant) and steps (id, title, files); "
      "plus the run's figures.")
      .def("__getattr__",
           [](const CampaignSummary& s, const std::string& key) -> py::object {
             if (s.doc.contains(key.c_str())) return s.doc[key.c_str()];
             PyErr_SetString(PyExc_AttributeError,
                             fmt::format("CampaignSummary has no attribute '{}'", key).c_str());
             throw py::error_already_set();
           })
      .def("__dir__",
           [](const CampaignSummary& s) {
             py::list keys;
             for (const char* k : {"all_pass", "column", "report", "seconds", "targets", "to_dict"})
               keys.append(k);
             for (const auto& item : s.doc) keys.append(item.first);
             return keys;
           })
      .def(
          "to_dict",
          [](const CampaignSummary& s) {
            return py::module_::import("copy").attr("deepcopy")(s.doc);
          },
          "summary.json as a dict (a copy).")
      .def("column",
           &summaryColumnOf,
           py::arg("key"),
           R"doc(One key of every summary row as an array.

Parameters
----------
key : str
    A row key: 'before', 'after', 'before_U', 'after_U', 'target' (float64 in each row's unit,
    NaN where summary.json has null: not measured, or no uncertainty budget; U is the expanded
    uncertainty, k = 2), 'step', 'quantity', 'unit', 'paper', 'noise' (strings), 'pass',
    'significant' (booleans; objects when some are None).)doc")
      .def_property_readonly(
          "all_pass",
          [](const CampaignSummary& s) { return s.result.all_pass; },
          "Every target met (`pkm campaign run` exits 1 otherwise).")
      .def_property_readonly(
          "targets",
          [](const CampaignSummary& s) { return s.result.targets; },
          "Number of summary rows with a target.")
      .def_property_readonly(
          "seconds",
          [](const CampaignSummary& s) { return s.result.seconds; },
          "Wall-clock time of the run, s.")
      .def_property_readonly(
          "report",
          [](const CampaignSummary& s) { return s.result.report.string(); },
          "The absolute path of report.html.")
      .def("__repr__", [](const CampaignSummary& s) {
        return fmt::format("<pkm.CampaignSummary '{}': {} steps, {} rows, {}>",
                           s.result.name,
                           s.result.steps.size(),
                           py::len(s.doc["rows"]),
                           s.result.all_pass ? "all targets met" : "SOME TARGETS MISSED");
      });
}

constexpr const char* kRunCampaignDoc =
    R"doc(Runs a campaign into a folder, as `pkm campaign run CAMPAIGN --out OUT --no-db`.

Each step measures on a virtual machine with known errors (or reads measured files), analyses,
calibrates, writes the controller compensation and measures again (docs/campaign.md). The GIL
is released while it runs; Ctrl-C stops it at the next progress report.

Parameters
----------
campaign : str, os.PathLike or dict, default "default"
    A built-in campaign's name (see campaigns()), a pkm.campaign/1 file, or the campaign document
    itself as a dict (messages and summary.json's "source" name it "campaign"; relative file
    names in it are taken from the current directory).
out : str or os.PathLike
    The output folder: summary.json, report-data.json, report.html and one folder per step.
force : bool, default False
    Write into a non-empty folder.
db : str or os.PathLike, optional
    The result store (SQLite) to add the results to; default none (the command's default is
    pkm.db).
progress : callable, optional
    Called with a dict (stage, index, count, elapsed in s, message) at every progress report,
    as the command prints them; an exception it raises stops the run and is raised.
environment : str or os.PathLike, optional
    The environment of every simulated step (--environment): a preset name ("ideal",
    "realistic") or an environment file (docs/simulation-errors.md); default each step's own.
uncertainty : str or os.PathLike, optional
    The instruments and environment of the uncertainty budgets (--uncertainty): a
    pkm.uncertainty-sources/1 file; default the typical datasheet values.
seed : int, optional
    The random seed of every simulated step (--seed); default each step's own.

Returns
-------
CampaignSummary
    summary.json's keys as attributes (rows with before/after and their U), all_pass, targets,
    seconds, report.

Raises
------
ValueError
    A bad campaign, step or data file (pkm's message, naming it), an unknown name, or an output
    folder that is not empty without `force`.)doc";

constexpr const char* kCampaignSensitivityDoc =
    R"doc(A sensitivity study, as `pkm campaign sensitivity CAMPAIGN --source SOURCE --values ...`.

One error source of the simulated environment is set to each value on top of a base
environment, the campaign runs once per value into OUT/runs/value-K/, and OUT/sensitivity.json,
sensitivity.csv and report.html (after-value with its ±U band against the source) are written
(docs/campaign.md, "Sensitivity study"). The GIL is released while it runs.

Parameters
----------
campaign : str or os.PathLike, default "default"
    A built-in campaign's name or a pkm.campaign/1 file.
source : str
    The dotted key path of the swept parameter in the environment JSON, in its JSON unit, e.g.
    "air.temperature_sensor.offset" (K) or "setup.beam_misalignment_urad" (µrad).
values : sequence of float
    The values of the source, distinct and finite.
out : str or os.PathLike
    The output folder.
environment : str or os.PathLike, optional
    The base environment: a preset name or an environment file; default "realistic".
uncertainty : str or os.PathLike, optional
    The instruments and environment of the uncertainty budgets (a pkm.uncertainty-sources/1 file).
seed : int, optional
    The random seed of every simulated step; default each step's own.
force : bool, default False
    Write into a non-empty folder.

Returns
-------
dict
    sensitivity.json (pkm.sensitivity/1): the source, its unit, the values, per value the
    summary rows (before, after and their U in the row's unit) and the coefficients.

Raises
------
ValueError
    An unknown source (the message lists the valid paths), bad values, a bad file, or an output
    folder that is not empty without `force`.)doc";

}  // namespace

void exposeCampaign(py::module_& m) {
  defCampaignSummary(m);

  m.def("run_campaign",
        &runCampaign,
        py::arg("campaign") = "default",
        py::kw_only(),
        py::arg("out"),
        py::arg("force") = false,
        py::arg("db") = py::none(),
        py::arg("progress") = py::none(),
        py::arg("environment") = py::none(),
        py::arg("uncertainty") = py::none(),
        py::arg("seed") = py::none(),
        kRunCampaignDoc);

  m.def("campaign_sensitivity",
        &campaignSensitivity,
        py::arg("campaign") = "default",
        py::kw_only(),
        py::arg("source"),
        py::arg("values"),
        py::arg("out"),
        py::arg("environment") = py::none(),
        py::arg("uncertainty") = py::none(),
        py::arg("seed") = py::none(),
        py::arg("force") = false,
        kCampaignSensitivityDoc);

  m.def(
      "campaigns",
      [] {
        py::list out;
        for (const std::string& name : workflow::builtinCampaignNames()) {
          const workflow::CampaignInfo info = workflow::describeCampaign(name);
          py::dict d;
          d["name"] = name;
          d["steps"] = info.steps;
          d["description"] = info.description;
          out.append(d);
        }
        return out;
      },
      "The built-in campaigns (`pkm campaign list`): a list of dicts with name, steps and "
      "description.");
}

}  // namespace pkm::python
