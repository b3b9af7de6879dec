#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "io/detail/joint_rates_json.hpp"
#include "io/detail/json_doc.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/hexapod_machine.hpp"
#include "pkm/io/number_format.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"

namespace pkm::io {

using nlohmann::json;
namespace kin = pkm::kinematics;

namespace {

/// Reads {"axis": [..], "max_angle_deg": ..}; returns whether an axis was given.
bool readCone(const detail::JsonDoc& doc,
              const json& v,
              const std::string& ptr,
              kin::JointCone& cone) {
  doc.onlyKeys(v, ptr, {"axis", "max_angle_deg"});
  cone.max_angle = degToRad(doc.number(v, ptr, "max_angle_deg", 0.0));
  if (cone.max_angle < 0.0) doc.fail(ptr + "/max_angle_deg", "must be >= 0 (0 = unlimited)");
  if (!v.contains("axis")) return false;
  const Eigen::Vector3d axis = doc.vec3(v["axis"], ptr + "/axis");
  if (axis.norm() < 1e-12) doc.fail(ptr + "/axis", "axis has zero length");
  cone.axis = axis.normalized();
  return true;
}

void writeVec(std::string& out, const Eigen::Vector3d& v) {
  out += '[';
  for (int i = 0; i < 3; ++i) {
    if (i > 0) out += ", ";
    appendNumber(out, v[i]);
  }
  out += ']';
}

/// Which struts were given their joint-cone axes.
using AxisGiven = std::array<bool, kin::kStruts>;

/// Reads "home": {"x", "y", "z", "a", "b", "c"} (length unit, degrees) into `model`.
void readHome(const detail::JsonDoc& doc, const json& root, kin::HexapodModel& model) {
  if (!root.contains("home")) return;
  const json& h = root["home"];
  doc.onlyKeys(h, "/home", {"x", "y", "z", "a", "b", "c"});
  model.home.position = {doc.number(h, "/home", "x", 0),
                         doc.number(h, "/home", "y", 0),
                         doc.number(h, "/home", "z", 0)};
  model.home.rpy = {degToRad(doc.number(h, "/home", "a", 0)),
                    degToRad(doc.number(h, "/home", "b", 0)),
                    degToRad(doc.number(h, "/home", "c", 0))};
}

/// Reads the offsets, strut diameter, condition limit, forward-kinematics options and joint rates.
void readSettings(const detail::JsonDoc& doc, const json& root, HexapodMachine& m) {
  kin::HexapodModel& model = m.model;
  if (root.contains("tool_offset"))
    model.tool_offset = doc.vec3(root["tool_offset"], "/tool_offset");
  model.spindle_offset = doc.number(root, "", "spindle_offset", 0.0);
  model.linuxcnc_tool_offset = doc.number(root, "", "linuxcnc_tool_offset", 0.0);
  model.strut_diameter = doc.number(root, "", "strut_diameter", 0.0);
  if (model.strut_diameter < 0.0) doc.fail("/strut_diameter", "must be >= 0");
  model.max_condition = doc.number(root, "", "max_condition", model.max_condition);
  if (!(model.max_condition > 1.0)) doc.fail("/max_condition", "must be > 1");
  if (root.contains("forward_kinematics"))
    detail::readFkOptions(doc, root["forward_kinematics"], m.fk);
  if (root.contains("joint_rates"))
    m.joint_rates = detail::readJointRates(doc, root["joint_rates"], "/joint_rates", false);
}

/// Reads strut `i` (at `ptr`) into `model`, noting which joint-cone axes were given.
void readStrut(const detail::JsonDoc& doc,
               const json& s,
               std::size_t i,
               const std::string& ptr,
               kin::HexapodModel& model,
               AxisGiven& base_axis_given,
               AxisGiven& platform_axis_given) {
  doc.onlyKeys(
      s, ptr, {"base", "platform", "length_offset", "stroke", "base_joint", "platform_joint"});
  kin::Strut& strut = model.struts[i];
  if (!s.contains("base")) doc.fail(ptr, "missing key 'base'");
  if (!s.contains("platform")) doc.fail(ptr, "missing key 'platform'");
  strut.world_p_base = doc.vec3(s["base"], ptr + "/base");
  strut.platform_p_joint = doc.vec3(s["platform"], ptr + "/platform");
  strut.length_offset = doc.number(s, ptr, "length_offset", 0.0);
  if (s.contains("stroke")) {
    const json& st = s["stroke"];
    if (!st.is_array() || st.size() != 2) doc.fail(ptr + "/stroke", "expected [min, max]");
    // null = unbounded on that side
    if (!st[0].is_null()) strut.min_reading = doc.number(st[0], ptr + "/stroke/0");
    if (!st[1].is_null()) strut.max_reading = doc.number(st[1], ptr + "/stroke/1");
    if (strut.min_reading > strut.max_reading) doc.fail(ptr + "/stroke", "min is larger than max");
  }
  if (s.contains("base_joint"))
    base_axis_given[i] = readCone(doc, s["base_joint"], ptr + "/base_joint", strut.base_cone);
  if (s.contains("platform_joint"))
    platform_axis_given[i] =
        readCone(doc, s["platform_joint"], ptr + "/platform_joint", strut.platform_cone);
}

/// Default cone axes (the strut direction at home) where none was given, then the model's
/// validation; its errors are located at /struts.
void finishModel(const detail::JsonDoc& doc,
                 kin::HexapodModel& model,
                 const AxisGiven& base_axis_given,
                 const AxisGiven& platform_axis_given) {
  try {
    kin::HexapodData data(model);
    kin::inverseKinematics(model, data, model.home);
    for (std::size_t i = 0; i < kin::kStruts; ++i) {
      const Eigen::Vector3d u = data.unit_leg[i];
      if (u.norm() == 0.0) continue;  // validate() reports the zero-length strut
      if (!base_axis_given[i]) model.struts[i].base_cone.axis = u;
      if (!platform_axis_given[i])
        model.struts[i].platform_cone.axis = data.world_R_platform.transpose() * u;
    }
    model.validate();
  } catch (const InvalidArgument& e) {
    doc.fail("/struts", e.what());
  }
}

}  // namespace

std::string readTextFile(const std::string& path, std::size_t max_bytes) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(locate(path, 0, "cannot open file"));
  std::string text;
  char buf[1 << 16];
  while (in.read(buf, sizeof buf) || in.gcount() > 0) {
    text.append(buf, static_cast<std::size_t>(in.gcount()));
    if (text.size() > max_bytes)
      throw IoError(locate(path, 0, fmt::format("file larger than {} bytes", max_bytes)));
  }
  if (in.bad()) throw IoError(locate(path, 0, "read error"));
  return text;
}

HexapodMachine parseHexapodJson(const std::string& text, const std::string& source) {
  const json root = detail::parseJson(text, source);
  const detail::JsonDoc doc(text, source);
  if (!root.is_object()) doc.fail("", "expected an object");
  if (doc.string(root, "", "type", "hexapod") != "hexapod")
    doc.fail("/type", "this reader handles \"type\": \"hexapod\" machines");
  doc.onlyKeys(root,
               "",
               {"schema",
                "type",
                "name",
                "description",
                "units",
                "home",
                "tool_offset",
                "spindle_offset",
                "linuxcnc_tool_offset",
                "strut_diameter",
                "max_condition",
                "forward_kinematics",
                "joint_rates",
                "world_frame",
                "struts"});
  HexapodMachine m;
  m.source = source;
  kin::HexapodModel& model = m.model;
  model.name = doc.string(root, "", "name", "hexapod");
  m.description = doc.string(root, "", "description", "");
  const std::string frame = doc.string(root, "", "world_frame", "machine");
  if (frame != "machine" && frame != "unregistered")
    doc.fail("/world_frame", "expected \"machine\" or \"unregistered\"");
  m.world_frame_unregistered = frame == "unregistered";
  model.unit = detail::readSchemaAndUnits(doc, root, "pkm.machine/1");
  readHome(doc, root, model);
  readSettings(doc, root, m);

  if (!root.contains("struts")) doc.fail("", "missing key 'struts'");
  const json& struts = root["struts"];
  if (!struts.is_array() || struts.size() != kin::kStruts)
    doc.fail("/struts", fmt::format("expected an array of {} struts", kin::kStruts));
  AxisGiven base_axis_given{}, platform_axis_given{};
  for (std::size_t i = 0; i < struts.size(); ++i)
    readStrut(doc,
              struts[i],
              i,
              fmt::format("/struts/{}", i),
              model,
              base_axis_given,
              platform_axis_given);
  finishModel(doc, model, base_axis_given, platform_axis_given);
  return m;
}

HexapodMachine readHexapodJson(const std::string& path) {
  return parseHexapodJson(readTextFile(path), path);
}

std::string writeHexapodJson(const HexapodMachine& machine) {
  const kin::HexapodModel& model = machine.model;
  std::string out = "{\n  \"schema\": \"pkm.machine/1\",\n  \"type\": \"hexapod\",\n";
  out += fmt::format("  \"name\": {},\n", json(model.name).dump());
  out += fmt::format("  \"description\": {},\n", json(machine.description).dump());
  out += fmt::format("  \"units\": \"{}\",\n", toString(model.unit));
  if (machine.world_frame_unregistered) out += "  \"world_frame\": \"unregistered\",\n";
  out += "  \"home\": {";
  const char* names[] = {"x", "y", "z", "a", "b", "c"};
  for (int i = 0; i < 6; ++i) {
    out += fmt::format("{}\"{}\": ", i ? ", " : "", names[i]);
    appendNumber(out, i < 3 ? model.home.position[i] : radToDeg(model.home.rpy[i - 3]));
  }
  out += "},\n  \"tool_offset\": ";
  writeVec(out, model.tool_offset);
  out += ",\n  \"spindle_offset\": " + formatNumber(model.spindle_offset);
  out += ",\n  \"linuxcnc_tool_offset\": " + formatNumber(model.linuxcnc_tool_offset);
  out += ",\n  \"strut_diameter\": " + formatNumber(model.strut_diameter);
  out += ",\n  \"max_condition\": " + formatNumber(model.max_condition);
  out += ",\n  \"forward_kinematics\": {\"tolerance\": " + formatNumber(machine.fk.tolerance) +
         ", \"max_iterations\": " + std::to_string(machine.fk.max_iterations) + "},\n";
  if (machine.joint_rates) out += "  " + jointRatesJson(*machine.joint_rates, false) + ",\n";
  out += "  \"struts\": [\n";
  for (int i = 0; i < kin::kStruts; ++i) {
    const kin::Strut& s = model.struts[static_cast<std::size_t>(i)];
    out += "    {\"base\": ";
    writeVec(out, s.world_p_base);
    out += ", \"platform\": ";
    writeVec(out, s.platform_p_joint);
    out += ", \"length_offset\": " + formatNumber(s.length_offset);
    if (std::isfinite(s.min_reading) || std::isfinite(s.max_reading)) {
      const auto bound = [](double v) {
        return std::isfinite(v) ? formatNumber(v) : std::string("null");
      };
      out += ", \"stroke\": [" + bound(s.min_reading) + ", " + bound(s.max_reading) + "]";
    }
    for (const auto& [key, cone] :
         {std::pair{"base_joint", &s.base_cone}, std::pair{"platform_joint", &s.platform_cone}}) {
      out += fmt::format(",\n     \"{}\": {{\"axis\": ", key);
      writeVec(out, cone->axis);
      out += ", \"max_angle_deg\": " + formatNumber(radToDeg(cone->max_angle)) + "}";
    }
    out += i + 1 < kin::kStruts ? "},\n" : "}\n";
  }
  out += "  ]\n}\n";
  return out;
}

void requireRegisteredFrame(const HexapodMachine& machine, const std::string& what) {
  if (!machine.world_frame_unregistered) return;
  throw InvalidArgument(fmt::format(
      "{}: refused: {} is a calibration from laser-tracker readings in the tracker's own frame "
      "without a registration (\"world_frame\": \"unregistered\"): its geometry is right but "
      "its world frame is where the fit put it, tilted and shifted against the machine's table "
      "(G54 cannot correct a tilt). Measure fiducial nests on the table with the tracker from "
      "the same placement (their table coordinates and the tracker's readings: a "
      "pkm.tracker-registration/1 file, docs/formats.md) and calibrate again with "
      "--registration FILE; nothing was written",
      what,
      machine.source));
}

}  // namespace pkm::io
