// A scenario's "environment" (docs/formats.md, "Scenario files"; docs/simulation-errors.md): a
// preset name or an object that starts from a preset and overrides its members.
#include <string>

#include "io/scenario_detail.hpp"
#include "pkm/simulation/environment.hpp"

namespace pkm::io::detail {

namespace sim = pkm::simulation;

namespace {

bool boolean(
    const JsonDoc& doc, const json& obj, const std::string& ptr, const char* key, bool fallback) {
  if (!obj.contains(key)) return fallback;
  if (!obj[key].is_boolean()) doc.fail(ptr + "/" + key, "expected true or false");
  return obj[key].get<bool>();
}

void readDrift(const JsonDoc& doc, const json& obj, const std::string& ptr, sim::Drift& d) {
  doc.onlyKeys(obj, ptr, {"start", "change", "fluctuation", "correlation_s"});
  d.start = doc.number(obj, ptr, "start", d.start);
  d.change = doc.number(obj, ptr, "change", d.change);
  d.fluctuation = doc.number(obj, ptr, "fluctuation", d.fluctuation);
  d.correlation_s = doc.number(obj, ptr, "correlation_s", d.correlation_s);
  if (!d.isValid()) doc.fail(ptr, "fluctuation must be >= 0 and correlation_s > 0");
}

void readSensor(const JsonDoc& doc, const json& obj, const std::string& ptr, sim::SensorError& s) {
  doc.onlyKeys(obj, ptr, {"offset", "noise"});
  s.offset = doc.number(obj, ptr, "offset", s.offset);
  s.noise = doc.number(obj, ptr, "noise", s.noise);
  if (!s.isValid()) doc.fail(ptr + "/noise", "must be >= 0");
}

void readAir(const JsonDoc& doc, const json& obj, const std::string& ptr, sim::AirEnvironment& a) {
  doc.onlyKeys(obj,
               ptr,
               {"enabled",
                "temperature_c",
                "pressure_pa",
                "humidity_percent",
                "temperature_sensor",
                "pressure_sensor",
                "humidity_sensor",
                "dead_path_mm",
                "vacuum_wavelength_um"});
  a.enabled = boolean(doc, obj, ptr, "enabled", true);
  const std::pair<const char*, sim::Drift*> drifts[] = {{"temperature_c", &a.temperature_c},
                                                        {"pressure_pa", &a.pressure_pa},
                                                        {"humidity_percent", &a.humidity_percent}};
  for (const auto& [key, drift] : drifts)
    if (obj.contains(key)) readDrift(doc, obj[key], ptr + "/" + key, *drift);
  const std::pair<const char*, sim::SensorError*> sensors[] = {
      {"temperature_sensor", &a.temperature_sensor},
      {"pressure_sensor", &a.pressure_sensor},
      {"humidity_sensor", &a.humidity_sensor}};
  for (const auto& [key, sensor] : sensors)
    if (obj.contains(key)) readSensor(doc, obj[key], ptr + "/" + key, *sensor);
  a.dead_path_mm = doc.number(obj, ptr, "dead_path_mm", a.dead_path_mm);
  a.vacuum_wavelength_um = doc.number(obj, ptr, "vacuum_wavelength_um", a.vacuum_wavelength_um);
  std::string why;
  if (!a.isValid(&why)) doc.fail(ptr, why);
}

/// α from "<prefix>_material" (a name) or "<prefix>_cte_per_k" (a number, 1/K); `fallback` when
/// neither is given. Both at once is an error.
double cte(const JsonDoc& doc,
           const json& obj,
           const std::string& ptr,
           const std::string& prefix,
           double fallback) {
  const std::string by_name = prefix + "_material";
  const std::string by_value = prefix + "_cte_per_k";
  if (obj.contains(by_name) && obj.contains(by_value))
    doc.fail(ptr + "/" + by_name, "give either " + by_name + " or " + by_value);
  if (obj.contains(by_value)) return doc.number(obj, ptr, by_value.c_str(), fallback);
  if (!obj.contains(by_name)) return fallback;
  const std::string name = doc.string(obj, ptr, by_name.c_str(), "");
  const auto alpha = sim::expansionCoefficient(name);
  if (!alpha)
    doc.fail(ptr + "/" + by_name,
             "unknown material '" + name + "' (steel, cast_iron, aluminium, granite, invar)");
  return *alpha;
}

void readThermal(const JsonDoc& doc,
                 const json& obj,
                 const std::string& ptr,
                 sim::ThermalEnvironment& t) {
  doc.onlyKeys(obj,
               ptr,
               {"enabled",
                "material_temperature_c",
                "material_sensor",
                "machine_material",
                "machine_cte_per_k",
                "assumed_material",
                "assumed_cte_per_k",
                "warmup_drift_mm",
                "warmup_tilt_urad",
                "warmup_time_constant_h",
                "strut_warmup_k",
                "strut_material",
                "strut_cte_per_k"});
  t.enabled = boolean(doc, obj, ptr, "enabled", true);
  if (obj.contains("material_temperature_c"))
    readDrift(doc,
              obj["material_temperature_c"],
              ptr + "/material_temperature_c",
              t.material_temperature_c);
  if (obj.contains("material_sensor"))
    readSensor(doc, obj["material_sensor"], ptr + "/material_sensor", t.material_sensor);
  t.machine_cte_per_k = cte(doc, obj, ptr, "machine", t.machine_cte_per_k);
  t.assumed_cte_per_k = cte(doc, obj, ptr, "assumed", t.assumed_cte_per_k);
  t.strut_cte_per_k = cte(doc, obj, ptr, "strut", t.strut_cte_per_k);
  if (obj.contains("warmup_drift_mm"))
    t.warmup_drift_mm = doc.vec3(obj["warmup_drift_mm"], ptr + "/warmup_drift_mm");
  if (obj.contains("warmup_tilt_urad"))
    t.warmup_tilt_rad = doc.vec3(obj["warmup_tilt_urad"], ptr + "/warmup_tilt_urad") / 1e6;
  t.warmup_time_constant_h =
      doc.number(obj, ptr, "warmup_time_constant_h", t.warmup_time_constant_h);
  t.strut_warmup_k = doc.number(obj, ptr, "strut_warmup_k", t.strut_warmup_k);
  std::string why;
  if (!t.isValid(&why)) doc.fail(ptr, why);
}

void readSetup(const JsonDoc& doc,
               const json& obj,
               const std::string& ptr,
               sim::SetupEnvironment& set) {
  doc.onlyKeys(obj,
               ptr,
               {"enabled",
                "beam_misalignment_urad",
                "reflector_offset_mm",
                "probe_lobing_um",
                "probe_lobes"});
  set.enabled = boolean(doc, obj, ptr, "enabled", true);
  set.beam_misalignment_rad =
      doc.number(obj, ptr, "beam_misalignment_urad", set.beam_misalignment_rad * 1e6) / 1e6;
  set.reflector_offset_mm = doc.number(obj, ptr, "reflector_offset_mm", set.reflector_offset_mm);
  set.probe_lobing_mm = doc.number(obj, ptr, "probe_lobing_um", set.probe_lobing_mm * 1e3) / 1e3;
  set.probe_lobes = integer(doc, obj, ptr, "probe_lobes", set.probe_lobes, 1, 100);
  std::string why;
  if (!set.isValid(&why)) doc.fail(ptr, why);
}

void readStructure(const JsonDoc& doc,
                   const json& obj,
                   const std::string& ptr,
                   sim::StructureEnvironment& st) {
  doc.onlyKeys(obj, ptr, {"enabled", "correlated_sigma_um", "correlation_s", "white_sigma_um"});
  st.enabled = boolean(doc, obj, ptr, "enabled", true);
  st.correlated_sigma_mm =
      doc.number(obj, ptr, "correlated_sigma_um", st.correlated_sigma_mm * 1e3) / 1e3;
  st.correlation_s = doc.number(obj, ptr, "correlation_s", st.correlation_s);
  st.white_sigma_mm = doc.number(obj, ptr, "white_sigma_um", st.white_sigma_mm * 1e3) / 1e3;
  std::string why;
  if (!st.isValid(&why)) doc.fail(ptr, why);
}

sim::Environment preset(const JsonDoc& doc, const std::string& name, const std::string& ptr) {
  const auto e = sim::environmentPreset(name);
  if (!e) {
    std::string known;
    for (const auto n : sim::environmentPresetNames())
      known += (known.empty() ? "" : ", ") + std::string(n);
    doc.fail(ptr, "unknown environment '" + name + "' (known: " + known + ")");
  }
  return *e;
}

}  // namespace

sim::Environment readEnvironment(const JsonDoc& doc, const json& obj, const std::string& ptr) {
  if (obj.is_string()) return preset(doc, obj.get<std::string>(), ptr);
  doc.onlyKeys(
      obj,
      ptr,
      {"preset", "duration_h", "air", "thermal", "setup", "structure", "compliance", "geometry"});
  sim::Environment e = preset(doc, doc.string(obj, ptr, "preset", "ideal"), ptr + "/preset");
  e.name = "custom";
  e.duration_h = doc.number(obj, ptr, "duration_h", e.duration_h);
  if (obj.contains("air")) readAir(doc, obj["air"], ptr + "/air", e.air);
  if (obj.contains("thermal")) readThermal(doc, obj["thermal"], ptr + "/thermal", e.thermal);
  if (obj.contains("setup")) readSetup(doc, obj["setup"], ptr + "/setup", e.setup);
  if (obj.contains("structure"))
    readStructure(doc, obj["structure"], ptr + "/structure", e.structure);
  if (obj.contains("compliance"))
    readCompliance(doc, obj["compliance"], ptr + "/compliance", e.compliance);
  if (obj.contains("geometry")) readGeometry(doc, obj["geometry"], ptr + "/geometry", e.geometry);
  std::string why;
  if (!e.isValid(&why)) doc.fail(ptr, why);
  return e;
}

}  // namespace pkm::io::detail
