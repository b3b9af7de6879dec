/// @file
/// @brief A touch-trigger probe with a stylus offset on an Exechon, probing a master ring
/// (Lee et al. 2019, secs. 3-4; H. H. Lee, D. M. Lee, S. H. Yang, JKSPE 36(5):463-469): the
/// spindle-reversal touches that give the offset (Figs. 4-5, eqs. 8-9) and a circle measurement
/// without and with compensation of the dependent rotational motion (DRM) by the spindle angle
/// (sec. 3.3, Fig. 9).
///
/// Model. The tool moves with a fixed direction t (±z). A touch starts with the spindle axis at a
/// start point and moves it along an approach direction u in the xy plane until the ball centre
/// b = s + Rot(t, C + φ_DRM(s))·(d, 0) reaches the circle of radius R − r about the ring centre:
/// s the spindle-axis (tool-point) position, d the stylus offset (spindle axis -> ball centre, xy
/// of the world frame, with the spindle at C = 0 and the tool at the reference pose), C the spindle
/// angle and φ_DRM the DRM relative to the reference pose (kinematics/exechon_drm.hpp), both about
/// t. The trigger is recorded with noise along u. The reference pose is the tool at the centre of
/// the offset ring with direction t. With a `tripod` the machine's own errors move the tool: at
/// spindle-axis command s the tool stands at s + e(s), turned by E(s) (HybridTripod::errorMotion:
/// the true Exechon's tool pose for the nominal IK's joints), so b = s + e(s) + E(s)·Rot(…)·d;
/// the OMM still records the command s. A ring with a form error has the radius
/// R + (ring_form/2)·cos(2θ) at the angle θ about its centre (an oval).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "pkm/kinematics/exechon_model.hpp"
#include "pkm/simulation/hybrid_tripod_errors.hpp"
#include "pkm/simulation/noise.hpp"
#include "pkm/simulation/random.hpp"

namespace pkm::simulation {

/// The set-up of a touch-probe measurement on a master ring (defaults: Lee et al. 2019, sec. 4).
struct TouchProbeSetup {
  std::string name = "touch-probe";  ///< names the random stream and the files
  /// Centre of the ring for the offset measurement, world frame of the Exechon model, mm
  /// (Lee et al. 2019, sec. 4: {−0.625, 200.914, −168}); also the DRM reference.
  Eigen::Vector3d offset_ring_center{-0.625, 200.914, -168.0};
  /// Centre of the ring for the circle measurement, mm
  /// (Lee et al. 2019: {−316.081, 247.037, −166.817}).
  Eigen::Vector3d circle_ring_center{-316.081, 247.037, -166.817};
  double ring_diameter = 40.001;  ///< master ring diameter, mm (Lee et al. 2019, Table 2)
  double ball_radius = 3.0;       ///< stylus-ball radius, mm (> 0, < ring radius)
  /// Stylus offset d: spindle axis -> ball centre at spindle 0, world xy, mm. Lee et al. (2019),
  /// Table 3 reports o_probe = (0.210, 0.160) in the sense of its eq. 8, which is −d.
  Eigen::Vector2d stylus_offset{-0.210, -0.160};
  Eigen::Vector3d direction = -Eigen::Vector3d::UnitZ();  ///< tool direction, ±z
  int circle_points = 36;    ///< touches per circle run (Lee et al. 2019: every 10°), >= 4
  int runs = 5;              ///< repetitions of each sequence (Lee et al. 2019: 5), >= 1
  double start_angle = 0.0;  ///< approach angle of the first circle touch, rad
  NoiseModel noise;          ///< trigger noise along the approach, mm
  /// Pre-travel variation with direction (lobing): the probe triggers
  /// lobing·cos(lobes·ψ) further along the approach, ψ = approach − planeTurn the direction in
  /// the probe's frame, mm (≥ 0; 0: none). Set from the environment by applyProbeEnvironment.
  double lobing = 0.0;
  int lobes = 3;  ///< number of lobes, ≥ 1 (3: a kinematic probe's three seats)
  /// The ring's thermal expansion α_ring·(T_ring − 20 °C) (relative, > −1): its true diameter is
  /// ring_diameter·(1 + ring_expansion) while ring_diameter stays its certified value at 20 °C,
  /// the one an analysis uses. Set from the environment by applyProbeEnvironment.
  double ring_expansion = 0.0;
  /// The ring's form deviation, peak to valley, mm (≥ 0; 0: round): its radius is
  /// R + (ring_form/2)·cos(2θ) at the angle θ from +x about its centre, an oval, the commonest
  /// form of a setting ring. Its certificate states it (Lee et al. 2019, Table 4: 2 µm).
  double ring_form = 0.0;
  /// The Exechon whose tool IK gives φ_DRM (the machine of the scenario); required.
  std::shared_ptr<const kinematics::ExechonModel> machine;
  /// The true tripod of the machine (its tool position and orientation errors at each touch);
  /// none: the tool is where it is commanded.
  std::shared_ptr<const HybridTripod> tripod;
  /// Throws pkm::InvalidArgument (naming the measurement) for non-finite values, a direction that
  /// is not ±z, a ball that does not fit, an offset the ring cannot hold, or too few points/runs.
  void validate() const;
};

/// One touch.
struct TouchRecord {
  std::string touch;      ///< offset sequence: "+x", "-x", "+y", "-y"; circle: "circle"
  int run = 1;            ///< from 1
  double approach = 0.0;  ///< approach direction in the plane, rad (counter-clockwise from +x)
  double spindle = 0.0;   ///< commanded spindle angle C about t, rad
  double drm = 0.0;       ///< φ_DRM at the touch about t relative to the reference pose, rad
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< spindle axis at the trigger, mm
  Eigen::Vector2d ball = Eigen::Vector2d::Zero();      ///< true ball centre (x, y), mm
};

/// Results of a touch-probe measurement.
struct TouchProbeResult {
  /// Offset sequence per run (DRM compensated): at spindle 0 the ±x touches from the ring centre,
  /// then the ±y touches from the x-centred point; the centred point p1 is their midpoint; then
  /// at spindle 180° the ±x and ±y touches from p1 (Lee et al. 2019, Figs. 4-5).
  std::vector<TouchRecord> offset;
  std::vector<TouchRecord> circle_uncompensated;  ///< spindle at 0 (the DRM turns the stylus)
  std::vector<TouchRecord> circle_compensated;    ///< spindle at −φ_DRM of the target point
};

/// The turn of the stylus in the xy plane (counter-clockwise about +z), rad: t_z·(C + φ_DRM).
[[nodiscard]] double planeTurn(const TouchProbeSetup& setup, const TouchRecord& touch);

/// The measured surface point of a circle touch as the OMM reports it with the calibrated
/// (constant, spindle-0) offset: s + d + r·u (spindle-axis position, offset, ball radius along the
/// approach direction u), x and y, mm.
[[nodiscard]] Eigen::Vector2d reportedSurfacePoint(const TouchProbeSetup& setup,
                                                   const TouchRecord& touch);

/// Simulates the measurement on setup.machine (DRM by its tool IK). Draws only from `rng`.
/// Throws pkm::InvalidArgument for an invalid set-up or a pose the tool IK cannot reach.
[[nodiscard]] TouchProbeResult simulateTouchProbe(const TouchProbeSetup& setup, RandomStream& rng);

/// One measurement of a campaign and its result.
struct TouchProbeRun {
  const TouchProbeSetup* setup = nullptr;  ///< points into the caller's vector
  TouchProbeResult result;                 ///< the touches
};

/// Runs every set-up, each from RandomStream(seed, setup.name), so the numbers of one do not depend
/// on the others. Throws pkm::InvalidArgument (simulateTouchProbe).
[[nodiscard]] std::vector<TouchProbeRun> runTouchProbes(const std::vector<TouchProbeSetup>& setups,
                                                        std::uint64_t seed);

}  // namespace pkm::simulation
