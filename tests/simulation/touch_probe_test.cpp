#include "pkm/simulation/touch_probe.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "pkm/core/error.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/metrology/circle_fit.hpp"
#include "pkm/metrology/min_zone_circle.hpp"
#include "pkm/metrology/probe_offset.hpp"
#include "support/tolerances.hpp"

namespace pkm::simulation {
namespace PKM_TEST_NS {

using test::kSeed;
constexpr double kTolNominal = 1e-9;  ///< zero noise: touch geometry and recovered offset, mm
/// Eq. 9 small-angle error for the paper's offset on the 40.001 mm ring with a 3 mm ball, mm.
constexpr double kTolEq9 = 3e-3;
constexpr double kRmp600Sigma = 0.125e-3;  ///< RMP600: 0.25 µm 2σ (datasheet), mm

TouchProbeSetup paperSetup(double sigma) {
  TouchProbeSetup s;
  s.machine = std::make_shared<const kinematics::ExechonModel>(
      io::loadExechonMachine("mxt700s-like").model);
  s.noise.sigma = sigma;
  return s;
}

std::vector<metrology::ProbeTouch> probeTouches(const TouchProbeSetup& s,
                                                const std::vector<TouchRecord>& records) {
  std::vector<metrology::ProbeTouch> t;
  for (const TouchRecord& r : records) t.push_back({planeTurn(s, r), r.position.head<2>()});
  return t;
}

std::vector<metrology::Point2> surface(const TouchProbeSetup& s,
                                       const std::vector<TouchRecord>& records) {
  std::vector<metrology::Point2> p;
  for (const TouchRecord& r : records) p.push_back(reportedSurfacePoint(s, r));
  return p;
}

TEST(TouchProbe, DeterministicPerSeed) {
  const TouchProbeSetup s = paperSetup(kRmp600Sigma);
  RandomStream a(kSeed, s.name), b(kSeed, s.name), c(kSeed + 1, s.name);
  const TouchProbeResult ra = simulateTouchProbe(s, a);
  const TouchProbeResult rb = simulateTouchProbe(s, b);
  const TouchProbeResult rc = simulateTouchProbe(s, c);
  ASSERT_EQ(ra.circle_compensated.size(), 180u);
  ASSERT_EQ(ra.offset.size(), 40u);
  for (std::size_t k = 0; k < ra.offset.size(); ++k)
    EXPECT_EQ(ra.offset[k].position, rb.offset[k].position);
  for (std::size_t k = 0; k < ra.circle_uncompensated.size(); ++k)
    EXPECT_EQ(ra.circle_uncompensated[k].position, rb.circle_uncompensated[k].position);
  EXPECT_NE(ra.circle_compensated[0].position, rc.circle_compensated[0].position);
}

TEST(TouchProbe, ZeroNoiseTouchesLieExactlyOnTheRing) {
  const TouchProbeSetup s = paperSetup(0.0);
  RandomStream rng(kSeed, s.name);
  const TouchProbeResult r = simulateTouchProbe(s, rng);
  const double rho = s.ring_diameter / 2.0 - s.ball_radius;
  for (const TouchRecord& t : r.offset) {
    EXPECT_NEAR((t.ball - s.offset_ring_center.head<2>()).norm(), rho, kTolNominal);
    // The recorded position is the true ball centre minus the turned offset.
    EXPECT_NEAR(
        (metrology::ballCentre({planeTurn(s, t), t.position.head<2>()}, s.stylus_offset) - t.ball)
            .norm(),
        0.0,
        kTolNominal);
  }
  // The least-squares offset is the injected one, exactly.
  const metrology::ProbeOffsetFit fit = metrology::fitProbeOffset(probeTouches(s, r.offset));
  EXPECT_NEAR((fit.offset - s.stylus_offset).norm(), 0.0, kTolNominal);
  EXPECT_NEAR(metrology::effectiveStylusRadius(s.ring_diameter, fit.ball_path_radius),
              s.ball_radius,
              kTolNominal);
  // Correcting the circle touches with the true turn of the stylus gives the ring exactly.
  for (const auto* circle : {&r.circle_uncompensated, &r.circle_compensated}) {
    const auto pts = metrology::correctedSurfacePoints(
        probeTouches(s, *circle), s.stylus_offset, s.ball_radius, s.circle_ring_center.head<2>());
    const metrology::CircleFit c = metrology::fitCircle(pts);
    EXPECT_NEAR(c.circle.radius, s.ring_diameter / 2.0, kTolNominal);
    EXPECT_LT(c.roundness, kTolNominal);
  }
}

TEST(TouchProbe, Eq9OnTheSimulatedTouchesGivesThePapersOffset) {
  const TouchProbeSetup s = paperSetup(0.0);
  RandomStream rng(kSeed, s.name);
  const TouchProbeResult r = simulateTouchProbe(s, rng);
  // Run 1: touches 0..3 at spindle 0 (+x, -x, +y, -y), 4..7 reversed.
  const auto& o = r.offset;
  const double x1 = 0.5 * (o[0].position.x() + o[1].position.x());
  const double y1 = 0.5 * (o[2].position.y() + o[3].position.y());
  const double R = s.ring_diameter / 2.0;
  const Eigen::Vector2d eq9 =
      metrology::probeOffsetEq9(x1, y1, o[4].position.x(), o[6].position.y(), R, s.ball_radius);
  const Eigen::Vector2d eq8 =
      metrology::probeOffsetEq8(x1, y1, o[4].position.x(), o[6].position.y(), R, s.ball_radius);
  // Seed 003 Table 3: o_probe = (0.210, 0.160) = −d.
  EXPECT_NEAR(eq9.x(), 0.210, kTolEq9);
  EXPECT_NEAR(eq9.y(), 0.160, kTolEq9);
  EXPECT_NEAR(eq8.x(), 0.210, kTolNominal);
  EXPECT_NEAR(eq8.y(), 0.160, kTolNominal);
}

TEST(TouchProbe, RecoversTheOffsetWithinTheProbeNoise) {
  const TouchProbeSetup s = paperSetup(kRmp600Sigma);
  RandomStream rng(kSeed, s.name);
  const TouchProbeResult r = simulateTouchProbe(s, rng);
  const metrology::ProbeOffsetFit fit = metrology::fitProbeOffset(probeTouches(s, r.offset));
  // 40 touches, 5 parameters: each offset component has a standard error of about σ/√5.
  EXPECT_NEAR((fit.offset - s.stylus_offset).norm(), 0.0, 5.0 * kRmp600Sigma);
  EXPECT_NEAR(fit.rms, kRmp600Sigma, kRmp600Sigma);
}

TEST(TouchProbe, DrmCompensationReducesTheRoundness) {
  const TouchProbeSetup s = paperSetup(kRmp600Sigma);
  RandomStream rng(kSeed, s.name);
  const TouchProbeResult r = simulateTouchProbe(s, rng);
  const auto without = surface(s, r.circle_uncompensated);
  const auto with = surface(s, r.circle_compensated);
  const double rw = metrology::fitMinimumZoneCircle(without).roundness;
  const double rc = metrology::fitMinimumZoneCircle(with).roundness;
  const double lw = metrology::fitCircle(without).roundness;
  const double lc = metrology::fitCircle(with).roundness;
  RecordProperty("roundness_mzc_without_um", std::to_string(rw * 1e3));
  RecordProperty("roundness_mzc_with_um", std::to_string(rc * 1e3));
  std::printf("roundness LSC without %.4f um, with %.4f um; MZC without %.4f um, with %.4f um\n",
              lw * 1e3,
              lc * 1e3,
              rw * 1e3,
              rc * 1e3);
  std::printf("LSC diameter without %.6f mm, with %.6f mm\n",
              2.0 * metrology::fitCircle(without).circle.radius,
              2.0 * metrology::fitCircle(with).circle.radius);
  EXPECT_LT(rc, 0.5 * rw);
  // First-order size of the uncompensated error: the stylus turned by ψ moves the ball by
  // (Rot(ψ) − I)·d, |.| = 2|d|·|sin(ψ/2)|; its spread bounds the roundness.
  double lo = 1e9, hi = -1e9;
  for (const TouchRecord& t : r.circle_uncompensated) {
    lo = std::min(lo, planeTurn(s, t));
    hi = std::max(hi, planeTurn(s, t));
  }
  EXPECT_LT(rw, 2.0 * s.stylus_offset.norm() * (hi - lo) + 10.0 * kRmp600Sigma);
}

TEST(TouchProbe, AWarmRingIsLargerByItsExpansionAndTheStylusSeemsSmaller) {
  // A steel ring 0.5 K above 20 °C: the true diameter D(1 + α·0.5 K); the touches lie on it, so
  // the effective stylus radius from the certified D comes out smaller by D·e/2 (0.115 µm) while
  // the offset stays exact.
  TouchProbeSetup s = paperSetup(0.0);
  s.ring_expansion = 11.5e-6 * 0.5;
  RandomStream rng(kSeed, s.name);
  const TouchProbeResult r = simulateTouchProbe(s, rng);
  const double rho = s.ring_diameter * (1.0 + s.ring_expansion) / 2.0 - s.ball_radius;
  for (const TouchRecord& t : r.offset)
    EXPECT_NEAR((t.ball - s.offset_ring_center.head<2>()).norm(), rho, kTolNominal);
  const metrology::ProbeOffsetFit fit = metrology::fitProbeOffset(probeTouches(s, r.offset));
  EXPECT_NEAR((fit.offset - s.stylus_offset).norm(), 0.0, kTolNominal);
  EXPECT_NEAR(metrology::effectiveStylusRadius(s.ring_diameter, fit.ball_path_radius),
              s.ball_radius - s.ring_diameter * s.ring_expansion / 2.0,
              kTolNominal);
  s.ring_expansion = -1.0;
  EXPECT_THROW(s.validate(), InvalidArgument);
}

TEST(TouchProbe, PreTravelLobingShiftsEachTouchByItsDirectionalSize) {
  const TouchProbeSetup plain = paperSetup(0.0);
  TouchProbeSetup lobed = plain;
  lobed.lobing = 0.25e-3;  // ±0.25 µm, three lobes
  RandomStream a(kSeed), b(kSeed);
  const TouchProbeResult p = simulateTouchProbe(plain, a);
  const TouchProbeResult l = simulateTouchProbe(lobed, b);
  ASSERT_EQ(p.circle_compensated.size(), l.circle_compensated.size());
  double largest = 0.0;
  for (std::size_t i = 0; i < p.circle_compensated.size(); ++i) {
    const TouchRecord& r = l.circle_compensated[i];
    const Eigen::Vector2d u(std::cos(r.approach), std::sin(r.approach));
    const double shift = u.dot((r.position - p.circle_compensated[i].position).head<2>());
    EXPECT_NEAR(shift, 0.25e-3 * std::cos(3.0 * (r.approach - planeTurn(lobed, r))), 1e-12) << i;
    largest = std::max(largest, std::abs(shift));
  }
  EXPECT_GT(largest, 0.2e-3);
  lobed.lobes = 0;
  EXPECT_THROW(lobed.validate(), InvalidArgument);
}

TEST(TouchProbe, AnOvalRingShowsItsCertifiedFormInTheRoundness) {
  // A ring certified to 2 µm of form (Lee et al. 2019, Table 4): every touch meets the oval, and
  // the compensated circle's roundness is that form (an oval sampled evenly: its peak to valley).
  constexpr double kForm = 2e-3;
  TouchProbeSetup s = paperSetup(0.0);
  s.ring_form = kForm;
  RandomStream rng(kSeed, s.name);
  const TouchProbeResult r = simulateTouchProbe(s, rng);
  for (const TouchRecord& t : r.circle_compensated) {
    const Eigen::Vector2d b = t.ball - s.circle_ring_center.head<2>();
    const double R = s.ring_diameter / 2.0 + 0.5 * kForm * std::cos(2.0 * std::atan2(b.y(), b.x()));
    EXPECT_NEAR(b.norm(), R - s.ball_radius, kTolNominal);
  }
  const auto pts = metrology::correctedSurfacePoints(probeTouches(s, r.circle_compensated),
                                                     s.stylus_offset,
                                                     s.ball_radius,
                                                     s.circle_ring_center.head<2>());
  EXPECT_NEAR(metrology::fitCircle(pts).roundness, kForm, 0.02 * kForm);
  s.ring_form = -1e-3;
  EXPECT_THROW(s.validate(), InvalidArgument);
}

TEST(TouchProbe, TheMachinesOwnErrorsMoveTheToolAtEveryTouch) {
  // An uncalibrated tripod: at each touch the ball is where the true tool puts the stylus, on the
  // ring, while the OMM records the command; the machine's error then shows in the circle.
  TouchProbeSetup s = paperSetup(0.0);
  ExechonTripodErrors e;
  e.dA = 1.2;
  e.dB = -0.8;
  e.length_offset = Eigen::Vector3d(0.8, -1.1, 0.5);
  s.tripod = std::make_shared<const HybridTripod>(*s.machine, e);
  RandomStream rng(kSeed, s.name);
  const TouchProbeResult r = simulateTouchProbe(s, rng);
  const double rho = s.ring_diameter / 2.0 - s.ball_radius;
  const Eigen::Vector3d d(s.stylus_offset.x(), s.stylus_offset.y(), 0.0);
  double largest = 0.0;
  for (const TouchRecord& t : r.circle_uncompensated) {
    EXPECT_NEAR((t.ball - s.circle_ring_center.head<2>()).norm(), rho, kTolNominal);
    const geometry::RigidTransform E = s.tripod->errorMotion(t.position);
    const Eigen::Vector3d stylus = Eigen::AngleAxisd(planeTurn(s, t), Eigen::Vector3d::UnitZ()) * d;
    const Eigen::Vector3d expected = t.position + E.translation() + E.linear() * stylus;
    EXPECT_NEAR((expected.head<2>() - t.ball).norm(), 0.0, 1e-6);
    largest = std::max(largest, E.translation().head<2>().norm());
  }
  EXPECT_GT(largest, 0.1);  // mm: the tool misses its command by tenths of a millimetre
  const auto pts = metrology::correctedSurfacePoints(probeTouches(s, r.circle_compensated),
                                                     s.stylus_offset,
                                                     s.ball_radius,
                                                     s.circle_ring_center.head<2>());
  EXPECT_GT(metrology::fitCircle(pts).roundness, 1e-3);  // the error's gradient over 40 mm
}

TEST(TouchProbe, RejectsBadSetups) {
  TouchProbeSetup s = paperSetup(0.0);
  s.direction = Eigen::Vector3d(1.0, 0.0, 0.0);
  EXPECT_THROW(s.validate(), InvalidArgument);
  s = paperSetup(0.0);
  s.ball_radius = 25.0;
  EXPECT_THROW(s.validate(), InvalidArgument);
  s = paperSetup(0.0);
  s.machine.reset();
  EXPECT_THROW(s.validate(), InvalidArgument);
  s = paperSetup(0.0);
  s.stylus_offset = Eigen::Vector2d(10.0, 0.0);  // reversed, the ball would not fit in the ring
  RandomStream rng(kSeed, s.name);
  EXPECT_THROW((void)simulateTouchProbe(s, rng), InvalidArgument);
  s = paperSetup(0.0);
  s.circle_points = 3;
  EXPECT_THROW(s.validate(), InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::simulation
