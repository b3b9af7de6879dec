// An environment's "compliance" (docs/formats.md, "Scenario files"; docs/simulation-errors.md,
// "Structure: compliance (gravity sag) and joint clearance"): gravity deflection and joint
// clearance.
#include <string>

#include "io/scenario_detail.hpp"
#include "pkm/simulation/environment.hpp"

namespace pkm::io::detail {

namespace sim = pkm::simulation;

namespace {

void check(const JsonDoc& doc, bool ok, const std::string& ptr, const std::string& why) {
  if (!ok) doc.fail(ptr, why);
}

void readSag(const JsonDoc& doc, const json& obj, const std::string& ptr, sim::AxisSag& s) {
  doc.onlyKeys(obj, ptr, {"kind", "sag_um", "length_mm", "zero_mm", "sense"});
  const std::string kind = doc.string(obj,
                                      ptr,
                                      "kind",
                                      s.kind == sim::AxisSag::Kind::kSpan         ? "span"
                                      : s.kind == sim::AxisSag::Kind::kCantilever ? "cantilever"
                                                                                  : "none");
  if (kind == "none")
    s.kind = sim::AxisSag::Kind::kNone;
  else if (kind == "cantilever")
    s.kind = sim::AxisSag::Kind::kCantilever;
  else if (kind == "span")
    s.kind = sim::AxisSag::Kind::kSpan;
  else
    doc.fail(ptr + "/kind", "must be \"none\", \"cantilever\" or \"span\"");
  s.sag_mm = doc.number(obj, ptr, "sag_um", s.sag_mm * 1e3) / 1e3;
  s.length_mm = doc.number(obj, ptr, "length_mm", s.length_mm);
  s.zero_mm = doc.number(obj, ptr, "zero_mm", s.zero_mm);
  s.sense = doc.number(obj, ptr, "sense", s.sense);
  std::string why;
  check(doc, s.isValid(&why), ptr, why);
}

void readHexapod(const JsonDoc& doc,
                 const json& obj,
                 const std::string& ptr,
                 sim::HexapodCompliance& h) {
  doc.onlyKeys(obj,
               ptr,
               {"platform_mass_kg",
                "platform_com_mm",
                "strut_mass_kg",
                "strut_com_fraction",
                "strut_stiffness_n_per_um",
                "joint_clearance_um"});
  h.platform_mass_kg = doc.number(obj, ptr, "platform_mass_kg", h.platform_mass_kg);
  if (obj.contains("platform_com_mm"))
    h.platform_com_mm = doc.vec3(obj["platform_com_mm"], ptr + "/platform_com_mm");
  h.strut_mass_kg = doc.number(obj, ptr, "strut_mass_kg", h.strut_mass_kg);
  h.strut_com_fraction = doc.number(obj, ptr, "strut_com_fraction", h.strut_com_fraction);
  h.strut_stiffness_n_per_um =
      doc.number(obj, ptr, "strut_stiffness_n_per_um", h.strut_stiffness_n_per_um);
  h.joint_clearance_mm =
      doc.number(obj, ptr, "joint_clearance_um", h.joint_clearance_mm * 1e3) / 1e3;
  std::string why;
  check(doc, h.isValid(&why), ptr, why);
}

void readExechon(const JsonDoc& doc,
                 const json& obj,
                 const std::string& ptr,
                 sim::ExechonCompliance& e) {
  doc.onlyKeys(
      obj, ptr, {"head_mass_kg", "head_com_mm", "leg_stiffness_n_per_um", "joint_clearance_um"});
  e.head_mass_kg = doc.number(obj, ptr, "head_mass_kg", e.head_mass_kg);
  if (obj.contains("head_com_mm"))
    e.head_com_mm = doc.vec3(obj["head_com_mm"], ptr + "/head_com_mm");
  e.leg_stiffness_n_per_um =
      doc.number(obj, ptr, "leg_stiffness_n_per_um", e.leg_stiffness_n_per_um);
  e.joint_clearance_mm =
      doc.number(obj, ptr, "joint_clearance_um", e.joint_clearance_mm * 1e3) / 1e3;
  std::string why;
  check(doc, e.isValid(&why), ptr, why);
}

}  // namespace

void readCompliance(const JsonDoc& doc,
                    const json& obj,
                    const std::string& ptr,
                    sim::ComplianceEnvironment& c) {
  doc.onlyKeys(obj, ptr, {"enabled", "hexapod", "exechon", "cartesian", "x2", "y2"});
  if (obj.contains("enabled") && !obj["enabled"].is_boolean())
    doc.fail(ptr + "/enabled", "expected true or false");
  c.enabled = obj.value("enabled", true);
  if (obj.contains("hexapod")) readHexapod(doc, obj["hexapod"], ptr + "/hexapod", c.hexapod);
  if (obj.contains("exechon")) readExechon(doc, obj["exechon"], ptr + "/exechon", c.exechon);
  if (obj.contains("cartesian")) {
    const json& cart = obj["cartesian"];
    const std::string p = ptr + "/cartesian";
    doc.onlyKeys(cart, p, {"x", "y", "z"});
    const char* keys[] = {"x", "y", "z"};
    for (std::size_t k = 0; k < 3; ++k)
      if (cart.contains(keys[k])) readSag(doc, cart[keys[k]], p + "/" + keys[k], c.cartesian[k]);
  }
  if (obj.contains("x2")) readSag(doc, obj["x2"], ptr + "/x2", c.x2);
  if (obj.contains("y2")) readSag(doc, obj["y2"], ptr + "/y2", c.y2);
}

}  // namespace pkm::io::detail
