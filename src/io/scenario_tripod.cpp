// Scenario files (docs/formats.md, "Scenario files"): the "tripod_errors" of a hybrid machine and
// their truth.json form.
#include <array>
#include <nlohmann/json.hpp>
#include <string>

#include "io/detail/json_doc.hpp"
#include "io/scenario_detail.hpp"
#include "pkm/core/units.hpp"
#include "pkm/simulation/hybrid_tripod_errors.hpp"

namespace pkm::io::detail {

namespace {

/// The length errors (mm) by key, in the order truth.json writes them.
std::array<std::pair<const char*, double simulation::ExechonTripodErrors::*>, 15> lengthKeys() {
  using E = simulation::ExechonTripodErrors;
  return {{{"dA", &E::dA},
           {"dB", &E::dB},
           {"dC", &E::dC},
           {"l12A", &E::l12A},
           {"l12C", &E::l12C},
           {"l12B", &E::l12B},
           {"l23B", &E::l23B},
           {"pA", &E::pA},
           {"pB", &E::pB},
           {"pC", &E::pC},
           {"hA", &E::hA},
           {"hC", &E::hC},
           {"hx", &E::hx},
           {"hz", &E::hz},
           {"tool_length", &E::tool_length}}};
}

}  // namespace

simulation::ExechonTripodErrors readTripodErrors(const JsonDoc& doc,
                                                 const json& obj,
                                                 const std::string& ptr) {
  doc.onlyKeys(obj,
               ptr,
               {"dA",
                "dB",
                "dC",
                "l12A",
                "l12C",
                "l12B",
                "l23B",
                "pA",
                "pB",
                "pC",
                "hA",
                "hC",
                "hx",
                "hz",
                "tool_length",
                "length_offset",
                "c0_urad",
                "a0_urad"});
  simulation::ExechonTripodErrors e;
  for (const auto& [key, member] : lengthKeys()) e.*member = doc.number(obj, ptr, key, 0.0);
  if (obj.contains("length_offset"))
    e.length_offset = doc.vec3(obj["length_offset"], ptr + "/length_offset");
  e.c0 = doc.number(obj, ptr, "c0_urad", 0.0) / kUradPerRad;
  e.a0 = doc.number(obj, ptr, "a0_urad", 0.0) / kUradPerRad;
  return e;
}

std::string tripodErrorsJson(const simulation::ExechonTripodErrors& errors) {
  nlohmann::ordered_json j;
  for (const auto& [key, member] : lengthKeys()) j[key] = errors.*member;
  j["length_offset"] = {errors.length_offset[0], errors.length_offset[1], errors.length_offset[2]};
  j["c0_urad"] = errors.c0 * kUradPerRad;
  j["a0_urad"] = errors.a0 * kUradPerRad;
  return j.dump();
}

}  // namespace pkm::io::detail
