// An environment as a file of its own and its numeric parameters by dotted path
// (pkm/io/environment_file.hpp).
#include "pkm/io/environment_file.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <functional>

#include "io/detail/json_doc.hpp"
#include "io/scenario_detail.hpp"
#include "pkm/core/error.hpp"

namespace pkm::io {
namespace {

namespace sim = pkm::simulation;
using Env = sim::Environment;

/// The source group a parameter belongs to (switched on when the parameter is set).
enum class Group { kNone, kAir, kThermal, kSetup, kStructure };

/// A parameter with its place in the struct: internal value = JSON value / divisor (as the
/// scenario reader converts µrad and µm).
struct Entry {
  EnvironmentParameter parameter;
  Group group = Group::kNone;
  std::function<double&(Env&)> field;  ///< empty for probe_lobes (an int)
  double divisor = 1.0;
};

bool* enabledFlag(Env& e, Group g) {
  switch (g) {
    case Group::kAir:
      return &e.air.enabled;
    case Group::kThermal:
      return &e.thermal.enabled;
    case Group::kSetup:
      return &e.setup.enabled;
    case Group::kStructure:
      return &e.structure.enabled;
    case Group::kNone:
      break;
  }
  return nullptr;
}

void addDrift(std::vector<Entry>& out,
              const std::string& prefix,
              const std::string& unit,
              const std::string& what,
              Group g,
              sim::Drift& (*drift)(Env&)) {
  out.push_back({{prefix + ".start", unit, what + " at the campaign's start"},
                 g,
                 [drift](Env& e) -> double& { return drift(e).start; }});
  out.push_back({{prefix + ".change", unit, what + ": change over the campaign (linear)"},
                 g,
                 [drift](Env& e) -> double& { return drift(e).change; }});
  out.push_back({{prefix + ".fluctuation", unit, what + ": standard deviation of the fluctuation"},
                 g,
                 [drift](Env& e) -> double& { return drift(e).fluctuation; }});
  out.push_back({{prefix + ".correlation_s", "s", what + ": correlation time of the fluctuation"},
                 g,
                 [drift](Env& e) -> double& { return drift(e).correlation_s; }});
}

void addSensor(std::vector<Entry>& out,
               const std::string& prefix,
               const std::string& unit,
               const std::string& what,
               Group g,
               sim::SensorError& (*sensor)(Env&)) {
  out.push_back({{prefix + ".offset", unit, what + ": fixed offset"},
                 g,
                 [sensor](Env& e) -> double& { return sensor(e).offset; }});
  out.push_back({{prefix + ".noise", unit, what + ": noise per reading (standard deviation)"},
                 g,
                 [sensor](Env& e) -> double& { return sensor(e).noise; }});
}

void addAir(std::vector<Entry>& v) {
  const Group g = Group::kAir;
  addDrift(v, "air.temperature_c", "°C", "air temperature", g, [](Env& e) -> sim::Drift& {
    return e.air.temperature_c;
  });
  addDrift(v, "air.pressure_pa", "Pa", "air pressure", g, [](Env& e) -> sim::Drift& {
    return e.air.pressure_pa;
  });
  addDrift(v, "air.humidity_percent", "%", "relative humidity", g, [](Env& e) -> sim::Drift& {
    return e.air.humidity_percent;
  });
  addSensor(
      v, "air.temperature_sensor", "K", "air temperature sensor", g, [](Env & e) -> auto& {
        return e.air.temperature_sensor;
      });
  addSensor(
      v, "air.pressure_sensor", "Pa", "pressure sensor", g, [](Env & e) -> auto& {
        return e.air.pressure_sensor;
      });
  addSensor(
      v, "air.humidity_sensor", "%", "humidity sensor", g, [](Env & e) -> auto& {
        return e.air.humidity_sensor;
      });
  v.push_back({{"air.dead_path_mm", "mm", "dead path (laser head to the reflector at the datum)"},
               g,
               [](Env& e) -> double& { return e.air.dead_path_mm; }});
  v.push_back({{"air.vacuum_wavelength_um", "µm", "the laser's vacuum wavelength"},
               g,
               [](Env& e) -> double& { return e.air.vacuum_wavelength_um; }});
}

void addThermal(std::vector<Entry>& v) {
  const Group g = Group::kThermal;
  addDrift(v,
           "thermal.material_temperature_c",
           "°C",
           "material temperature",
           g,
           [](Env& e) -> sim::Drift& { return e.thermal.material_temperature_c; });
  addSensor(
      v, "thermal.material_sensor", "K", "material temperature sensor", g, [](Env & e) -> auto& {
        return e.thermal.material_sensor;
      });
  v.push_back({{"thermal.machine_cte_per_k", "1/K", "true expansion coefficient of the machine"},
               g,
               [](Env& e) -> double& { return e.thermal.machine_cte_per_k; }});
  v.push_back({{"thermal.assumed_cte_per_k", "1/K", "expansion coefficient entered in the laser"},
               g,
               [](Env& e) -> double& { return e.thermal.assumed_cte_per_k; }});
  for (int k = 0; k < 3; ++k)
    v.push_back({{fmt::format("thermal.warmup_drift_mm.{}", k),
                  "mm",
                  fmt::format("warm-up drift of the tool point, {}", "xyz"[k])},
                 g,
                 [k](Env& e) -> double& { return e.thermal.warmup_drift_mm[k]; }});
  for (int k = 0; k < 3; ++k)
    v.push_back({{fmt::format("thermal.warmup_tilt_urad.{}", k),
                  "µrad",
                  fmt::format("thermal tilt of a hybrid machine's PKM, about {}", "xyz"[k])},
                 g,
                 [k](Env& e) -> double& { return e.thermal.warmup_tilt_rad[k]; },
                 1e6});
  v.push_back({{"thermal.warmup_time_constant_h", "h", "warm-up time constant"},
               g,
               [](Env& e) -> double& { return e.thermal.warmup_time_constant_h; }});
  v.push_back({{"thermal.strut_warmup_k", "K", "hexapod struts' temperature rise after warm-up"},
               g,
               [](Env& e) -> double& { return e.thermal.strut_warmup_k; }});
  v.push_back({{"thermal.strut_cte_per_k", "1/K", "expansion coefficient of the struts"},
               g,
               [](Env& e) -> double& { return e.thermal.strut_cte_per_k; }});
}

void addSetupAndStructure(std::vector<Entry>& v) {
  v.push_back({{"setup.beam_misalignment_urad", "µrad", "laser beam misalignment (cosine error)"},
               Group::kSetup,
               [](Env& e) -> double& { return e.setup.beam_misalignment_rad; },
               1e6});
  v.push_back({{"setup.reflector_offset_mm", "mm", "σ of the reflector's unknown offset (Abbe)"},
               Group::kSetup,
               [](Env& e) -> double& { return e.setup.reflector_offset_mm; }});
  v.push_back({{"setup.probe_lobing_um", "µm", "touch probe pre-travel lobing amplitude"},
               Group::kSetup,
               [](Env& e) -> double& { return e.setup.probe_lobing_mm; },
               1e3});
  v.push_back(
      {{"setup.probe_lobes", "", "number of lobes of the probe's pre-travel"}, Group::kSetup, {}});
  v.push_back({{"structure.correlated_sigma_um", "µm", "σ of the correlated (AR(1)) wander"},
               Group::kStructure,
               [](Env& e) -> double& { return e.structure.correlated_sigma_mm; },
               1e3});
  v.push_back({{"structure.correlation_s", "s", "correlation time of the wander"},
               Group::kStructure,
               [](Env& e) -> double& { return e.structure.correlation_s; }});
  v.push_back({{"structure.white_sigma_um", "µm", "σ of the white part per reading"},
               Group::kStructure,
               [](Env& e) -> double& { return e.structure.white_sigma_mm; },
               1e3});
}

const std::vector<Entry>& entries() {
  static const std::vector<Entry> all = [] {
    std::vector<Entry> v;
    v.push_back({{"duration_h", "h", "campaign duration over which the drifts run"},
                 Group::kNone,
                 [](Env& e) -> double& { return e.duration_h; }});
    addAir(v);
    addThermal(v);
    addSetupAndStructure(v);
    return v;
  }();
  return all;
}

const Entry& entry(const std::string& path) {
  for (const Entry& e : entries())
    if (e.parameter.path == path) return e;
  std::string valid;
  for (const Entry& e : entries()) valid += (valid.empty() ? "" : ", ") + e.parameter.path;
  throw InvalidArgument(fmt::format("unknown environment parameter '{}' (valid: {})", path, valid));
}

}  // namespace

Env parseEnvironmentJson(const NamedText& text) {
  const detail::json j = detail::parseJson(text.text, text.name);
  const detail::JsonDoc doc(text.text, text.name);
  if (!j.is_string() && !j.is_object())
    doc.fail("", "expected an environment object or a preset name");
  return detail::readEnvironment(doc, j, "");
}

Env loadEnvironment(const std::string& spec) {
  std::error_code ec;
  if (std::filesystem::is_regular_file(spec, ec)) return parseEnvironmentJson(readNamedText(spec));
  if (const auto preset = sim::environmentPreset(spec)) return *preset;
  std::string known;
  for (const auto n : sim::environmentPresetNames())
    known += (known.empty() ? "" : ", ") + std::string(n);
  throw IoError(fmt::format("{}: no such file, and not an environment preset ({})", spec, known));
}

const std::vector<EnvironmentParameter>& environmentParameters() {
  static const std::vector<EnvironmentParameter> all = [] {
    std::vector<EnvironmentParameter> v;
    for (const Entry& e : entries()) v.push_back(e.parameter);
    return v;
  }();
  return all;
}

double environmentParameter(const Env& environment, const std::string& path) {
  const Entry& e = entry(path);
  if (!e.field) return environment.setup.probe_lobes;
  Env copy = environment;
  return e.field(copy) * e.divisor;
}

void setEnvironmentParameter(Env& environment, const std::string& path, double value) {
  const Entry& e = entry(path);
  PKM_CHECK(std::isfinite(value), "environment parameter '{}': {} is not finite", path, value);
  Env changed = environment;
  if (e.field) {
    e.field(changed) = value / e.divisor;
  } else {
    PKM_CHECK(value == std::floor(value) && value >= 1 && value <= 100,
              "environment parameter '{}': {} must be an integer in [1, 100]",
              path,
              value);
    changed.setup.probe_lobes = static_cast<int>(value);
  }
  if (bool* on = enabledFlag(changed, e.group)) *on = true;
  changed.name = "custom";
  std::string why;
  PKM_CHECK(changed.isValid(&why), "environment parameter '{}' = {:g}: {}", path, value, why);
  environment = std::move(changed);
}

}  // namespace pkm::io
