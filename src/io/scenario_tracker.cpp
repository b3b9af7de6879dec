// Laser-tracker measurements and the Cartesian actuation in scenario files (docs/formats.md,
// "Scenario files"), and their truth.json members.
#include "io/scenario_tracker.hpp"

#include <fmt/format.h>

#include "io/scenario_detail.hpp"
#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/geometry/error_motion.hpp"
#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/geometry/so3.hpp"
#include "pkm/io/number_format.hpp"
#include "pkm/kinematics/pose_rpy.hpp"

namespace pkm::io::detail {

namespace sim = pkm::simulation;

namespace {

constexpr int kMaxPoses = 1000000;

/// [x, y, z, a, b, c] in mm and degrees, as a command in mm and radians.
Eigen::VectorXd poseCommand(const JsonDoc& doc, const json& v, const std::string& ptr) {
  if (!v.is_array() || v.size() != 6) doc.fail(ptr, "expected [x, y, z, a, b, c] (mm, deg)");
  Eigen::VectorXd c(6);
  for (std::size_t i = 0; i < 6; ++i) {
    const double x = doc.number(v[i], fmt::format("{}/{}", ptr, i));
    c[static_cast<Eigen::Index>(i)] = i < 3 ? x : degToRad(x);
  }
  return c;
}

sim::TrackerNoise trackerNoise(const JsonDoc& doc, const json& v, const std::string& ptr) {
  if (v.is_string()) {
    const auto preset = sim::trackerNoise(v.get<std::string>());
    if (!preset)
      doc.fail(ptr,
               fmt::format("unknown tracker noise '{}' (known: {})",
                           v.get<std::string>(),
                           fmt::join(sim::trackerNoiseNames(), ", ")));
    return *preset;
  }
  doc.onlyKeys(v, ptr, {"range_sigma", "range_ppm", "angle_sigma_urad", "orientation_sigma_urad"});
  sim::TrackerNoise n{doc.number(v, ptr, "range_sigma", 0.0),
                      doc.number(v, ptr, "range_ppm", 0.0),
                      doc.number(v, ptr, "angle_sigma_urad", 0.0) / kUradPerRad,
                      doc.number(v, ptr, "orientation_sigma_urad", 0.0) / kUradPerRad};
  try {
    n.validate();
  } catch (const InvalidArgument& e) {
    doc.fail(ptr, e.what());
  }
  return n;
}

Eigen::Vector3d threeNumbers(const JsonDoc& doc, const json& v, const std::string& ptr) {
  if (v.is_number()) return Eigen::Vector3d::Constant(doc.number(v, ptr));
  if (!v.is_array()) doc.fail(ptr, "expected a number or [x, y, z]");
  return doc.vec3(v, ptr);
}

std::string array(const Eigen::VectorXd& v) {
  std::string out = "[";
  for (Eigen::Index i = 0; i < v.size(); ++i) out += (i ? ", " : "") + formatNumber(v[i]);
  return out + "]";
}

/// {"position": [x, y, z] mm, "rpy_deg": [r, p, y]} as world_T_tracker.
geometry::RigidTransform trackerFrame(const JsonDoc& doc, const json& f, const std::string& fp) {
  doc.onlyKeys(f, fp, {"position", "rpy_deg"});
  const Eigen::Vector3d p = doc.vec3(doc.required(f, fp, "position"), fp + "/position");
  Eigen::Vector3d rpy = Eigen::Vector3d::Zero();
  if (f.contains("rpy_deg")) rpy = doc.vec3(f["rpy_deg"], fp + "/rpy_deg");
  return kinematics::toRigidTransform(
      {p, Eigen::Vector3d(degToRad(rpy[0]), degToRad(rpy[1]), degToRad(rpy[2]))});
}

std::string placementJson(const geometry::RigidTransform& T) {
  const Eigen::Vector3d rpy = geometry::rpyFromRotation(T.linear());
  std::string rows;
  for (Eigen::Index r = 0; r < 4; ++r)
    rows += (r ? ", " : "") + array(T.matrix().row(r).transpose());
  return fmt::format("{{\"position\": {}, \"rpy_deg\": {}, \"matrix\": [{}]}}",
                     array(T.translation()),
                     array(Eigen::Vector3d(radToDeg(rpy[0]), radToDeg(rpy[1]), radToDeg(rpy[2]))),
                     rows);
}

std::string exechonTrackerTruth(const sim::ExechonTrackerSetup& t) {
  return fmt::format(
      "    {{\"name\": \"{}\", \"world_T_tracker\": {}, \"smr_offset\": {},\n"
      "     \"noise\": {{\"range_sigma\": {}, \"range_ppm\": {}, \"angle_sigma_urad\": {}}}}}",
      t.name,
      placementJson(t.world_T_tracker),
      array(t.smr_offset),
      formatNumber(t.noise.range_sigma),
      formatNumber(t.noise.range_ppm),
      formatNumber(t.noise.angle_sigma * kUradPerRad));
}

std::string trackerTruth(const sim::TrackerSetup& t) {
  const geometry::RigidTransform& T = t.world_T_tracker;
  const Eigen::Vector3d rpy = geometry::rpyFromRotation(T.linear());
  std::string rows;
  for (Eigen::Index r = 0; r < 4; ++r)
    rows += (r ? ", " : "") + array(T.matrix().row(r).transpose());
  return fmt::format(
      "    {{\"name\": {}, \"mode\": \"{}\",\n"
      "     \"world_T_tracker\": {{\"position\": {}, \"rpy_deg\": {}, \"matrix\": [{}]}},\n"
      "     \"smr_offset\": {},\n"
      "     \"noise\": {{\"range_sigma\": {}, \"range_ppm\": {}, \"angle_sigma_urad\": {}, "
      "\"orientation_sigma_urad\": {}}}}}",
      nlohmann::json(t.name).dump(),
      sim::toString(t.mode),
      array(T.translation()),
      array(Eigen::Vector3d(radToDeg(rpy[0]), radToDeg(rpy[1]), radToDeg(rpy[2]))),
      rows,
      array(t.smr_offset),
      formatNumber(t.noise.range_sigma),
      formatNumber(t.noise.range_ppm),
      formatNumber(t.noise.angle_sigma * kUradPerRad),
      formatNumber(t.noise.orientation_sigma * kUradPerRad));
}

}  // namespace

sim::TrackerSetup readTracker(const JsonDoc& doc, const json& obj, const std::string& ptr) {
  doc.onlyKeys(obj,
               ptr,
               {"name",
                "instrument",
                "mode",
                "poses",
                "random_poses",
                "smr_offset",
                "tracker_frame",
                "registration_nests",
                "noise"});
  sim::TrackerSetup s;
  s.name = measurementName(doc, obj, ptr);
  const std::string mode = doc.string(obj, ptr, "mode", "pose");
  if (mode == "point")
    s.mode = sim::TrackerMode::kPoint;
  else if (mode != "pose")
    doc.fail(ptr + "/mode", "must be \"pose\" (6-DOF probe) or \"point\" (SMR)");
  if (obj.contains("poses")) {
    const json& p = obj["poses"];
    if (!p.is_array()) doc.fail(ptr + "/poses", "expected an array of [x, y, z, a, b, c]");
    for (std::size_t j = 0; j < p.size(); ++j)
      s.poses.push_back(poseCommand(doc, p[j], fmt::format("{}/poses/{}", ptr, j)));
  }
  if (obj.contains("random_poses")) {
    const json& r = obj["random_poses"];
    const std::string rp = ptr + "/random_poses";
    doc.onlyKeys(r, rp, {"count", "x", "y", "z", "a", "b", "c"});
    s.random_count = integer(doc, r, rp, "count", 0, 1, kMaxPoses);
    const char* axes[] = {"x", "y", "z", "a", "b", "c"};
    for (std::size_t k = 0; k < 6; ++k) {
      const auto ki = static_cast<Eigen::Index>(k);
      const double scale = k < 3 ? 1.0 : degToRad(1.0);
      if (k < 3 && !r.contains(axes[k]))
        doc.fail(rp, fmt::format("missing key '{}' ([min, max] mm)", axes[k]));
      if (!r.contains(axes[k])) continue;  // an angle without a range stays 0
      const json& range = r[axes[k]];
      const std::string at = rp + "/" + axes[k];
      if (!range.is_array() || range.size() != 2) doc.fail(at, "expected [min, max]");
      s.random_box.lo[ki] = scale * doc.number(range[0], at + "/0");
      s.random_box.hi[ki] = scale * doc.number(range[1], at + "/1");
      if (s.random_box.lo[ki] > s.random_box.hi[ki]) doc.fail(at, "min is larger than max");
    }
  }
  if (s.poses.empty() && s.random_count == 0)
    doc.fail(ptr, "give \"poses\" or \"random_poses\" (or both)");
  if (obj.contains("smr_offset")) s.smr_offset = doc.vec3(obj["smr_offset"], ptr + "/smr_offset");
  if (obj.contains("tracker_frame"))
    s.world_T_tracker = trackerFrame(doc, obj["tracker_frame"], ptr + "/tracker_frame");
  if (obj.contains("registration_nests")) {
    const json& n = obj["registration_nests"];
    const std::string np = ptr + "/registration_nests";
    if (!n.is_array()) doc.fail(np, "expected an array of [x, y, z] (mm, world frame)");
    s.registration_nests.clear();
    for (std::size_t j = 0; j < n.size(); ++j)
      s.registration_nests.push_back(doc.vec3(n[j], fmt::format("{}/{}", np, j)));
  }
  if (obj.contains("noise")) s.noise = trackerNoise(doc, obj["noise"], ptr + "/noise");
  try {
    s.validate();
  } catch (const InvalidArgument& e) {
    doc.fail(ptr, e.what());
  }
  return s;
}

namespace {

/// [min, max] at obj[key] (mm).
Eigen::Vector2d range(const JsonDoc& doc,
                      const json& obj,
                      const std::string& ptr,
                      const char* key) {
  const std::string at = ptr + "/" + key;
  const json& r = doc.required(obj, ptr, key);
  if (!r.is_array() || r.size() != 2) doc.fail(at, "expected [min, max] (mm)");
  const Eigen::Vector2d v(doc.number(r[0], at + "/0"), doc.number(r[1], at + "/1"));
  if (v(0) > v(1)) doc.fail(at, "min is larger than max");
  return v;
}

}  // namespace

sim::HybridTrackerSetup readHybridTracker(const JsonDoc& doc,
                                          const json& obj,
                                          const std::string& ptr) {
  doc.onlyKeys(obj,
               ptr,
               {"name",
                "instrument",
                "mode",
                "count",
                "x2",
                "y2",
                "box",
                "smr_offset",
                "tracker_frame",
                "noise"});
  sim::HybridTrackerSetup s;
  s.name = measurementName(doc, obj, ptr);
  s.count = integer(doc, obj, ptr, "count", 0, 1, kMaxPoses);
  s.x2 = range(doc, obj, ptr, "x2");
  s.y2 = range(doc, obj, ptr, "y2");
  const json& box = doc.required(obj, ptr, "box");
  const std::string bp = ptr + "/box";
  doc.onlyKeys(box, bp, {"x", "y", "z"});
  const char* axes[] = {"x", "y", "z"};
  for (Eigen::Index k = 0; k < 3; ++k) {
    const Eigen::Vector2d r = range(doc, box, bp, axes[k]);
    s.pkm_min[k] = r(0);
    s.pkm_max[k] = r(1);
  }
  if (obj.contains("smr_offset")) s.smr_offset = doc.vec3(obj["smr_offset"], ptr + "/smr_offset");
  if (obj.contains("tracker_frame"))
    s.work_T_tracker = trackerFrame(doc, obj["tracker_frame"], ptr + "/tracker_frame");
  if (obj.contains("noise")) s.noise = trackerNoise(doc, obj["noise"], ptr + "/noise");
  try {
    s.validate();
  } catch (const InvalidArgument& e) {
    doc.fail(ptr, e.what());
  }
  return s;
}

namespace {

std::string hybridTrackerTruth(const sim::HybridTrackerSetup& t) {
  return fmt::format(
      "    {{\"name\": \"{}\", \"work_T_tracker\": {}, \"smr_offset\": {},\n"
      "     \"noise\": {{\"range_sigma\": {}, \"range_ppm\": {}, \"angle_sigma_urad\": {}}}}}",
      t.name,
      placementJson(t.work_T_tracker),
      array(t.smr_offset),
      formatNumber(t.noise.range_sigma),
      formatNumber(t.noise.range_ppm),
      formatNumber(t.noise.angle_sigma * kUradPerRad));
}

}  // namespace

sim::ExechonTrackerSetup readExechonTracker(const JsonDoc& doc,
                                            const json& obj,
                                            const std::string& ptr) {
  doc.onlyKeys(obj,
               ptr,
               {"name",
                "instrument",
                "mode",
                "count",
                "box",
                "direction",
                "max_tilt_deg",
                "smr_offset",
                "tracker_frame",
                "noise"});
  sim::ExechonTrackerSetup s;
  s.name = measurementName(doc, obj, ptr);
  s.count = integer(doc, obj, ptr, "count", 0, 1, kMaxPoses);
  const json& box = doc.required(obj, ptr, "box");
  const std::string bp = ptr + "/box";
  doc.onlyKeys(box, bp, {"x", "y", "z"});
  const char* axes[] = {"x", "y", "z"};
  for (Eigen::Index k = 0; k < 3; ++k) {
    const std::string at = bp + "/" + axes[k];
    const json& range = doc.required(box, bp, axes[k]);
    if (!range.is_array() || range.size() != 2) doc.fail(at, "expected [min, max] (mm)");
    s.box_min[k] = doc.number(range[0], at + "/0");
    s.box_max[k] = doc.number(range[1], at + "/1");
    if (s.box_min[k] > s.box_max[k]) doc.fail(at, "min is larger than max");
  }
  if (obj.contains("direction")) s.direction = doc.vec3(obj["direction"], ptr + "/direction");
  s.max_tilt = degToRad(doc.number(obj, ptr, "max_tilt_deg", 0.0));
  if (obj.contains("smr_offset")) s.smr_offset = doc.vec3(obj["smr_offset"], ptr + "/smr_offset");
  if (obj.contains("tracker_frame"))
    s.world_T_tracker = trackerFrame(doc, obj["tracker_frame"], ptr + "/tracker_frame");
  if (obj.contains("noise")) s.noise = trackerNoise(doc, obj["noise"], ptr + "/noise");
  try {
    s.validate();
  } catch (const InvalidArgument& e) {
    doc.fail(ptr, e.what());
  }
  return s;
}

sim::CartesianActuation readCartesianActuation(const JsonDoc& doc,
                                               const json& obj,
                                               const std::string& ptr) {
  doc.onlyKeys(obj, ptr, {"backlash", "repeatability_sigma"});
  sim::CartesianActuation a;
  if (obj.contains("backlash")) a.backlash = threeNumbers(doc, obj["backlash"], ptr + "/backlash");
  if (obj.contains("repeatability_sigma"))
    a.repeatability_sigma =
        threeNumbers(doc, obj["repeatability_sigma"], ptr + "/repeatability_sigma");
  try {
    a.validate();
  } catch (const InvalidArgument& e) {
    doc.fail(ptr, e.what());
  }
  return a;
}

std::string extraTruthJson(const sim::Campaign& campaign) {
  std::string out;
  if (const auto* c = dynamic_cast<const sim::CartesianMachine*>(campaign.machine.get()))
    out += fmt::format(",\n  \"actuation\": {{\"backlash\": {}, \"repeatability_sigma\": {}}}",
                       array(c->actuation().backlash),
                       array(c->actuation().repeatability_sigma));
  if (!campaign.trackers.empty()) {
    out += ",\n  \"laser_trackers\": [\n";
    for (std::size_t i = 0; i < campaign.trackers.size(); ++i)
      out += (i ? ",\n" : "") + trackerTruth(campaign.trackers[i]);
    out += "\n  ]";
  }
  if (!campaign.hybrid_trackers.empty()) {
    out += ",\n  \"hybrid_trackers\": [\n";
    for (std::size_t i = 0; i < campaign.hybrid_trackers.size(); ++i)
      out += (i ? ",\n" : "") + hybridTrackerTruth(campaign.hybrid_trackers[i]);
    out += "\n  ]";
  }
  if (!campaign.exechon_trackers.empty()) {
    out += ",\n  \"exechon_trackers\": [\n";
    for (std::size_t i = 0; i < campaign.exechon_trackers.size(); ++i)
      out += (i ? ",\n" : "") + exechonTrackerTruth(campaign.exechon_trackers[i]);
    out += "\n  ]";
  }
  return out;
}

}  // namespace pkm::io::detail
