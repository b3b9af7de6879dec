#include "pkm/simulation/laser_tracker.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/geometry/error_motion.hpp"
#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/geometry/so3.hpp"

namespace pkm::simulation {

namespace {
constexpr double kPpm = 1e-6;
constexpr double kRigidTolerance = 1e-9;  // |RᵀR − I| of a placement
}  // namespace

const char* toString(TrackerMode mode) { return mode == TrackerMode::kPoint ? "point" : "pose"; }

void TrackerNoise::validate() const {
  for (const double v : {range_sigma, range_ppm, angle_sigma, orientation_sigma})
    PKM_CHECK(std::isfinite(v) && v >= 0.0, "tracker noise {} must be finite and >= 0", v);
}

double TrackerNoise::rangeSigma(double range) const {
  return std::hypot(range_sigma, range_ppm * kPpm * range);
}

bool TrackerNoise::ideal() const {
  return range_sigma == 0.0 && range_ppm == 0.0 && angle_sigma == 0.0 && orientation_sigma == 0.0;
}

Eigen::Vector3d TrackerNoise::point(const Eigen::Vector3d& p, RandomStream& rng) const {
  if (range_sigma == 0.0 && range_ppm == 0.0 && angle_sigma == 0.0) return p;
  const double r = p.norm();
  PKM_CHECK(r > 0.0, "the target is at the tracker's centre");
  // Spherical coordinates: azimuth about the tracker's z axis, elevation from its xy plane.
  const double range = r + rng.normal(rangeSigma(r));
  const double azimuth = std::atan2(p.y(), p.x()) + rng.normal(angle_sigma);
  const double elevation = std::asin(std::clamp(p.z() / r, -1.0, 1.0)) + rng.normal(angle_sigma);
  if (perfect) return p;
  return range * Eigen::Vector3d(std::cos(elevation) * std::cos(azimuth),
                                 std::cos(elevation) * std::sin(azimuth),
                                 std::sin(elevation));
}

Eigen::Matrix3d TrackerNoise::rotation(const Eigen::Matrix3d& R, RandomStream& rng) const {
  if (orientation_sigma == 0.0) return R;
  Eigen::Vector3d n;
  for (Eigen::Index k = 0; k < 3; ++k) n[k] = rng.normal(orientation_sigma);
  if (perfect) return R;
  return geometry::so3Exp(n) * R;
}

std::optional<TrackerNoise> trackerNoise(std::string_view name) {
  if (name == "ideal") return TrackerNoise{};
  // U(k = 2) = 15 µm + 6 µm/m halved; 6-DOF probe ±0.01° halved. Quotients give the nearest
  // doubles.
  if (name == "laser-tracker") return TrackerNoise{7.5 / 1e3, 3.0, 3.0 / 1e6, degToRad(0.005)};
  return std::nullopt;
}

std::vector<std::string_view> trackerNoiseNames() { return {"ideal", "laser-tracker"}; }

const std::vector<Eigen::Vector3d>& defaultRegistrationNests() {
  static const std::vector<Eigen::Vector3d> nests = {
      {-500, -500, 0}, {500, -500, 0}, {500, 500, 0}, {-500, 500, 0}, {0, 0, 0}, {0, -700, 0}};
  return nests;
}

bool TrackerSetup::placed() const { return !world_T_tracker.matrix().isIdentity(0.0); }

void TrackerSetup::validate() const {
  PKM_CHECK(!name.empty(), "a tracker measurement needs a name");
  PKM_CHECK(random_count >= 0, "{}: random pose count {} must be >= 0", name, random_count);
  PKM_CHECK(!poses.empty() || random_count > 0, "{}: no poses to measure", name);
  for (const Eigen::VectorXd& c : poses)
    PKM_CHECK(c.size() == 6 && c.allFinite(), "{}: a pose must be 6 finite values", name);
  if (random_count > 0) random_box.validate();
  PKM_CHECK(smr_offset.allFinite(), "{}: the SMR offset is not finite", name);
  const Eigen::Matrix3d R = world_T_tracker.linear();
  PKM_CHECK(world_T_tracker.matrix().allFinite() &&
                (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() < kRigidTolerance &&
                R.determinant() > 0.0,
            "{}: the tracker placement is not a rigid transform",
            name);
  for (const Eigen::Vector3d& n : registration_nests)
    PKM_CHECK(n.allFinite(), "{}: a registration nest is not finite", name);
  noise.validate();
}

std::vector<NestReading> simulateTrackerRegistration(const TrackerSetup& setup, RandomStream& rng) {
  setup.validate();
  const geometry::RigidTransform tracker_T_world = setup.world_T_tracker.inverse();
  std::vector<NestReading> out;
  out.reserve(setup.registration_nests.size());
  for (const Eigen::Vector3d& nest : setup.registration_nests)
    out.push_back({nest, setup.noise.point(tracker_T_world * nest, rng)});
  return out;
}

std::vector<TrackerReading> simulateLaserTracker(HexapodVirtualMachine& machine,
                                                 const TrackerSetup& setup,
                                                 RandomStream& rng) {
  setup.validate();
  std::vector<Eigen::VectorXd> commands = setup.poses;
  if (setup.random_count > 0)
    for (Eigen::VectorXd& c :
         sampleHexapodWorkspace(machine.nominal(), setup.random_box, setup.random_count, rng))
      commands.push_back(std::move(c));
  machine.reset(rng.bits());
  const geometry::RigidTransform tracker_T_world = setup.world_T_tracker.inverse();
  const geometry::RigidTransform tool_T_target = geometry::translationTransform(setup.smr_offset);
  std::vector<TrackerReading> out;
  out.reserve(commands.size());
  for (const Eigen::VectorXd& c : commands) {
    TrackerReading r;
    r.command = c;
    r.truth = tracker_T_world * machine.moveTo(c) * tool_T_target;
    r.lengths = machine.commandedReadings();
    r.measured.translation() = setup.noise.point(r.truth.translation(), rng);
    if (setup.mode == TrackerMode::kPose)
      r.measured.linear() = setup.noise.rotation(r.truth.linear(), rng);
    out.push_back(std::move(r));
  }
  return out;
}

}  // namespace pkm::simulation
