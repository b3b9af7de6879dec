// Instrument and environment descriptions as JSON (io/uncertainty_sources.hpp).
#include "pkm/io/uncertainty_sources.hpp"

#include <string>
#include <utility>
#include <vector>

#include "io/detail/json_doc.hpp"

namespace pkm::io {
namespace {

using detail::JsonDoc;
using Json = nlohmann::ordered_json;

/// A number field of one section: its JSON key and where it lives.
struct Field {
  const char* key;
  double* value;
};

/// The sections and their number fields (one table for reading and writing).
struct Section {
  const char* key;
  std::string* name;  ///< the instrument's "name" (nullptr: none)
  std::vector<Field> fields;
};

/// The sections stating the weights the struts and legs carry.
std::vector<Section> weightSections(metrology::UncertaintySources& s) {
  return {{"hexapod_platform",
           &s.hexapod_platform.name,
           {{"mass_kg", &s.hexapod_platform.mass_kg},
            {"com_x_mm", &s.hexapod_platform.com_x_mm},
            {"com_y_mm", &s.hexapod_platform.com_y_mm},
            {"com_z_mm", &s.hexapod_platform.com_z_mm},
            {"strut_mass_kg", &s.hexapod_platform.strut_mass_kg},
            {"strut_com_fraction", &s.hexapod_platform.strut_com_fraction},
            {"strut_stiffness_n_per_um", &s.hexapod_platform.strut_stiffness_n_per_um},
            {"joint_clearance_mm", &s.hexapod_platform.joint_clearance_mm}}},
          {"exechon_head",
           &s.exechon_head.name,
           {{"mass_kg", &s.exechon_head.mass_kg},
            {"com_x_mm", &s.exechon_head.com_x_mm},
            {"com_y_mm", &s.exechon_head.com_y_mm},
            {"com_z_mm", &s.exechon_head.com_z_mm},
            {"leg_stiffness_n_per_um", &s.exechon_head.leg_stiffness_n_per_um},
            {"joint_clearance_mm", &s.exechon_head.joint_clearance_mm}}}};
}

std::vector<Section> sections(metrology::UncertaintySources& s) {
  metrology::LaserInterferometer& l = s.laser;
  metrology::MeasurementEnvironment& e = s.environment;
  std::vector<Section> out{
      {"laser",
       &l.name,
       {{"vacuum_wavelength_um", &l.vacuum_wavelength_um},
        {"wavelength_accuracy_ppm", &l.wavelength_accuracy_ppm},
        {"resolution_mm", &l.resolution_mm},
        {"reading_noise_mm", &l.reading_noise_mm},
        {"air_temperature_accuracy_k", &l.air_temperature_accuracy_k},
        {"air_pressure_accuracy_pa", &l.air_pressure_accuracy_pa},
        {"air_humidity_accuracy_percent", &l.air_humidity_accuracy_percent},
        {"material_temperature_accuracy_k", &l.material_temperature_accuracy_k},
        {"straightness_accuracy_mm", &l.straightness_accuracy_mm},
        {"straightness_relative", &l.straightness_relative},
        {"straightness_length_mm_per_m2", &l.straightness_length_mm_per_m2},
        {"angular_accuracy_rad", &l.angular_accuracy_rad},
        {"angular_accuracy_rad_per_m", &l.angular_accuracy_rad_per_m}}},
      {"probe",
       &s.probe.name,
       {{"repeatability_2sigma_mm", &s.probe.repeatability_2sigma_mm},
        {"form_2d_mm", &s.probe.form_2d_mm},
        {"stylus_radius_uncertainty_mm", &s.probe.stylus_radius_uncertainty_mm},
        {"ring_diameter_uncertainty_mm", &s.probe.ring_diameter_uncertainty_mm},
        {"ring_form_mm", &s.probe.ring_form_mm}}},
      {"dial_gauge",
       &s.dial_gauge.name,
       {{"accuracy_mm", &s.dial_gauge.accuracy_mm},
        {"resolution_mm", &s.dial_gauge.resolution_mm}}},
      {"tracker",
       &s.tracker.name,
       {{"accuracy_mm", &s.tracker.accuracy_mm},
        {"accuracy_mm_per_m", &s.tracker.accuracy_mm_per_m},
        {"range_mm", &s.tracker.range_mm},
        {"orientation_accuracy_rad", &s.tracker.orientation_accuracy_rad}}},
      {"actuators",
       &s.actuators.name,
       {{"resolution_mm", &s.actuators.resolution_mm},
        {"repeatability_mm", &s.actuators.repeatability_mm},
        {"backlash_mm", &s.actuators.backlash_mm},
        {"lead_error_mm_per_m", &s.actuators.lead_error_mm_per_m},
        {"lead_wave_mm", &s.actuators.lead_wave_mm},
        {"lead_wave_length_mm", &s.actuators.lead_wave_length_mm},
        {"lead_periodic_mm", &s.actuators.lead_periodic_mm}}},
      {"ballbar",
       &s.ballbar.name,
       {{"sensor_accuracy_mm", &s.ballbar.sensor_accuracy_mm},
        {"resolution_mm", &s.ballbar.resolution_mm},
        {"length_uncertainty_mm", &s.ballbar.length_uncertainty_mm}}},
      {"environment",
       nullptr,
       {{"material_temperature_c", &e.material_temperature_c},
        {"expansion_coefficient_per_k", &e.expansion_coefficient_per_k},
        {"expansion_coefficient_accuracy_per_k", &e.expansion_coefficient_accuracy_per_k},
        {"air_temperature_variation_k", &e.air_temperature_variation_k},
        {"dead_path_mm", &e.dead_path_mm},
        {"misalignment_rad", &e.misalignment_rad},
        {"abbe_offset_mm", &e.abbe_offset_mm},
        {"angular_error_range_rad", &e.angular_error_range_rad},
        {"setup_repeatability_mm", &e.setup_repeatability_mm},
        {"environmental_variation_mm", &e.environmental_variation_mm}}},
  };
  // The weights after the actuators that carry them (the file's order).
  const std::vector<Section> weights = weightSections(s);
  out.insert(out.begin() + 5, weights.begin(), weights.end());
  return out;
}

std::vector<Field> airFields(metrology::AirConditions& air) {
  return {{"temperature_c", &air.temperature_c},
          {"pressure_pa", &air.pressure_pa},
          {"relative_humidity", &air.relative_humidity}};
}

void readFields(const JsonDoc& doc,
                const detail::json& obj,
                const std::string& ptr,
                const std::vector<Field>& fields,
                std::vector<std::string> extra_keys) {
  if (!obj.is_object()) doc.fail(ptr, "expected an object");
  for (const auto& item : obj.items()) {
    bool known = false;
    for (const Field& f : fields) known = known || item.key() == f.key;
    for (const std::string& k : extra_keys) known = known || item.key() == k;
    if (!known) doc.fail(ptr + "/" + item.key(), fmt::format("unknown key '{}'", item.key()));
  }
  for (const Field& f : fields) *f.value = doc.number(obj, ptr, f.key, *f.value);
}

/// The conditions `env` (the file's "environment" object, checked) states, marked kStated.
void markStated(const detail::json& env, metrology::ConditionOrigins& o) {
  constexpr auto kStated = metrology::ConditionOrigin::kStated;
  const auto has = [&](const char* key) { return env.contains(key); };
  if (has("material_temperature_c")) o.material_temperature = kStated;
  if (has("air_temperature_variation_k")) o.air_temperature_variation = kStated;
  if (has("dead_path_mm")) o.dead_path = kStated;
  if (has("misalignment_rad")) o.misalignment = kStated;
  if (has("abbe_offset_mm") && has("angular_error_range_rad")) o.abbe = kStated;
  if (!has("air")) return;
  const detail::json& air = env["air"];
  if (air.contains("temperature_c")) o.air_temperature = kStated;
  if (air.contains("pressure_pa")) o.air_pressure = kStated;
  if (air.contains("relative_humidity")) o.air_humidity = kStated;
}

}  // namespace

metrology::UncertaintySources readUncertaintySources(const NamedText& text) {
  const detail::json root = detail::parseJson(text.text, text.name);
  const JsonDoc doc(text.text, text.name);
  doc.onlyKeys(root,
               "",
               {"schema",
                "laser",
                "probe",
                "dial_gauge",
                "tracker",
                "actuators",
                "hexapod_platform",
                "exechon_head",
                "ballbar",
                "environment",
                "coverage_factor"});
  if (const std::string s = doc.string(root, "", "schema", kUncertaintySourcesSchema);
      s != kUncertaintySourcesSchema)
    doc.fail(
        "/schema",
        fmt::format(
            "unsupported schema \"{}\" (this version reads \"{}\")", s, kUncertaintySourcesSchema));
  metrology::UncertaintySources out;
  for (const Section& section : sections(out)) {
    if (!root.contains(section.key)) continue;
    const std::string ptr = std::string("/") + section.key;
    const detail::json& obj = root[section.key];
    std::vector<std::string> extra;
    if (section.name) extra.emplace_back("name");
    if (section.name == nullptr) extra.emplace_back("air");
    readFields(doc, obj, ptr, section.fields, extra);
    if (section.name) *section.name = doc.string(obj, ptr, "name", *section.name);
    if (section.name == nullptr && obj.contains("air"))
      readFields(doc, obj["air"], ptr + "/air", airFields(out.environment.air), {});
  }
  out.coverage_factor = doc.number(root, "", "coverage_factor", out.coverage_factor);
  if (root.contains("environment")) markStated(root["environment"], out.environment.origin);
  std::string why;
  if (!out.isValid(&why)) doc.fail("", why);
  return out;
}

std::string uncertaintySourcesJson(const metrology::UncertaintySources& sources) {
  metrology::UncertaintySources copy = sources;
  Json root{{"schema", kUncertaintySourcesSchema}};
  for (const Section& section : sections(copy)) {
    Json obj = Json::object();
    if (section.name) obj["name"] = *section.name;
    for (const Field& f : section.fields) obj[f.key] = *f.value;
    if (section.name == nullptr) {
      Json air = Json::object();
      for (const Field& f : airFields(copy.environment.air)) air[f.key] = *f.value;
      obj["air"] = std::move(air);
    }
    root[section.key] = std::move(obj);
  }
  root["coverage_factor"] = copy.coverage_factor;
  return root.dump(2) + "\n";
}

}  // namespace pkm::io
