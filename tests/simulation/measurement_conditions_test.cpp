// MeasurementConditions: the laser's reading in drifting air compensated by sensors with errors,
// against the analytic sizes (Δ·(n_t − n_s)/n_s, dead path L·Δn/n), the AR(1) fluctuation's
// standard deviation, determinism per seed.
#include "pkm/simulation/measurement_conditions.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "pkm/core/air_refractive_index.hpp"
#include "pkm/core/error.hpp"
#include "pkm/geometry/rigid_transform.hpp"

namespace PKM_TEST_NS {

namespace sim = pkm::simulation;

sim::Environment airOnly() {
  sim::Environment e;
  e.name = "custom";
  e.duration_h = 1.0;
  e.air.enabled = true;
  return e;
}

TEST(MeasurementConditions, IdealEnvironmentReadsTheDisplacement) {
  const sim::Environment e;
  sim::MeasurementConditions c(e, 0.0, 60.0, 3, 1);
  c.zero();
  c.next();
  EXPECT_EQ(c.laserDisplacement(123.456), 123.456);
}

TEST(MeasurementConditions, SensorOffsetGivesTheIndexDifferenceTimesTheLength) {
  sim::Environment e = airOnly();
  e.air.temperature_sensor.offset = 0.2;  // K: the sensor reads 0.2 K warm
  e.air.pressure_sensor.offset = -100.0;  // Pa
  sim::MeasurementConditions c(e, 0.0, 600.0, 2, 1);
  c.zero();
  c.next();
  const pkm::AirConditions truth{20.0, 101325.0, 50.0};
  const double n_t = pkm::refractiveIndexEdlen(truth);
  const double n_s = pkm::refractiveIndexEdlen({20.2, 101225.0, 50.0});
  const double L = 1000.0;  // mm
  EXPECT_NEAR(c.laserDisplacement(L) - L, L * (n_t - n_s) / n_s, 1e-12);
  // By the sensitivities: (0.93e-6·0.2 + 2.7e-9·100)·1000 mm ≈ 0.46 µm, the reading too long.
  const pkm::AirIndexSensitivity k = pkm::edlenSensitivity(truth);
  EXPECT_NEAR(c.laserDisplacement(L) - L, -L * (0.2 * k.per_kelvin - 100.0 * k.per_pascal), 1e-6);
  EXPECT_GT(c.laserDisplacement(L) - L, 0.4e-3);
}

TEST(MeasurementConditions, DeadPathSeesTheIndexChangeSinceZeroing) {
  sim::Environment e = airOnly();
  e.air.temperature_c = {20.0, 1.0, 0.0, 600.0};  // +1 K over the hour
  e.air.dead_path_mm = 500.0;
  sim::MeasurementConditions c(e, 0.0, 3600.0, 4, 1);  // the whole hour, 4 readings
  c.zero();
  for (int i = 0; i < 4; ++i) c.next();
  EXPECT_DOUBLE_EQ(c.timeS(), 3600.0);
  EXPECT_DOUBLE_EQ(c.trueAir().temperature_c, 21.0);
  // Perfect sensors: the measured displacement is exact; the dead path is not compensated.
  const double n0 = pkm::refractiveIndexEdlen({20.0, 101325.0, 50.0});
  const double n1 = pkm::refractiveIndexEdlen({21.0, 101325.0, 50.0});
  EXPECT_NEAR(c.laserDisplacement(0.0), 500.0 * (n1 - n0) / n1, 1e-13);
  // By the sensitivity at the mid temperature (−0.95 ppm/K at 50 %RH): about −0.48 µm.
  const double per_kelvin = pkm::edlenSensitivity({20.5, 101325.0, 50.0}).per_kelvin;
  EXPECT_NEAR(c.laserDisplacement(0.0), 500.0 * per_kelvin, 1e-3 * 500.0 * std::abs(per_kelvin));
  EXPECT_NEAR(c.laserDisplacement(300.0) - 300.0, 500.0 * (n1 - n0) / n1, 1e-12);
}

TEST(MeasurementConditions, FluctuationHasItsStandardDeviationAndSeedsRepeat) {
  sim::Environment e = airOnly();
  e.duration_h = 100.0;
  e.air.temperature_c = {20.0, 0.0, 0.1, 60.0};
  const auto series = [&](std::uint64_t seed) {
    sim::MeasurementConditions c(e, 0.0, 100.0 * 3600.0, 6000, seed);  // 60 s steps
    c.zero();
    std::vector<double> t;
    for (int i = 0; i < 6000; ++i) {
      c.next();
      t.push_back(c.trueAir().temperature_c);
    }
    return t;
  };
  const std::vector<double> a = series(5);
  EXPECT_EQ(a, series(5));
  EXPECT_NE(a, series(6));
  double sum = 0.0, sum2 = 0.0, lag = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    sum += a[i] - 20.0;
    sum2 += (a[i] - 20.0) * (a[i] - 20.0);
    if (i > 0) lag += (a[i] - 20.0) * (a[i - 1] - 20.0);
  }
  const double n = static_cast<double>(a.size());
  EXPECT_NEAR(std::sqrt(sum2 / n), 0.1, 0.01);
  // Correlated: lag-one correlation exp(−60/60) = 0.37, not 0 as white noise would give.
  EXPECT_NEAR(lag / sum2, std::exp(-1.0), 0.05);
  EXPECT_NEAR(sum / n, 0.0, 0.02);
}

TEST(MeasurementConditions, SensorNoiseScattersTheCompensation) {
  sim::Environment e = airOnly();
  e.air.temperature_sensor.noise = 0.05;  // K per reading
  sim::MeasurementConditions c(e, 0.0, 3600.0, 4000, 3);
  c.zero();
  double sum2 = 0.0;
  for (int i = 0; i < 4000; ++i) {
    c.next();
    const double err = c.laserDisplacement(1000.0) - 1000.0;
    sum2 += err * err;
  }
  // 1000 mm × 0.93e-6/K × 0.05 K = 0.047 µm.
  EXPECT_NEAR(std::sqrt(sum2 / 4000.0), 1000.0 * 0.93e-6 * 0.05, 0.004e-3);
}

sim::Environment thermalOnly(double temperature_c) {
  sim::Environment e;
  e.name = "custom";
  e.duration_h = 1.0;
  e.thermal.enabled = true;
  e.thermal.material_temperature_c = {temperature_c, 0.0, 0.0, 3600.0};
  return e;
}

TEST(MeasurementConditions, TheLaserNormalisesTheMachinesExpansionToTwentyDegrees) {
  sim::Environment e = thermalOnly(22.0);
  sim::MeasurementConditions c(e, 0.0, 600.0, 2, 1);
  c.zero();
  c.next();
  pkm::geometry::RigidTransform p = pkm::geometry::RigidTransform::Identity();
  p.translation() = Eigen::Vector3d(500.0, 100.0, 0.0);
  // The machine 2 K warm: its positions scale by 1 + 11.5e-6 × 2 about the origin.
  EXPECT_NEAR((c.actualPose(p).translation() - p.translation() * (1 + 23e-6)).norm(), 0.0, 1e-12);
  // Same α entered and a perfect sensor: the normalisation removes the expansion exactly.
  EXPECT_NEAR(c.laserDisplacement(500.0 * (1 + 23e-6)), 500.0, 1e-12);
  // The operator enters steel for a cast-iron machine: Δ·(α_m − α_a)·ΔT = −1 ppm/K × 2 K.
  e.thermal.machine_cte_per_k = 10.5e-6;
  const double expanded = 1000.0 * (1 + 10.5e-6 * 2.0);
  EXPECT_NEAR(c.laserDisplacement(expanded) - 1000.0, -2e-3, 1e-7);
  // A material sensor reading 0.1 K warm: −α·0.1 K = −1.15 µm per metre.
  e.thermal.machine_cte_per_k = 11.5e-6;
  e.thermal.material_sensor.offset = 0.1;
  sim::MeasurementConditions d(e, 0.0, 600.0, 2, 1);
  d.zero();
  d.next();
  EXPECT_NEAR(d.sensedMaterialTemperature(), 22.1, 1e-12);
  EXPECT_NEAR(d.laserDisplacement(1000.0 * (1 + 23e-6)) - 1000.0, -1.15e-3, 1e-7);
}

TEST(MeasurementConditions, WarmUpDriftApproachesItsFinalValueExponentially) {
  sim::Environment e = thermalOnly(20.0);
  e.duration_h = 4.0;
  e.thermal.warmup_drift_mm = {0.005, 0.0, -0.030};
  e.thermal.warmup_time_constant_h = 1.0;
  sim::MeasurementConditions c(e, 0.0, 7200.0, 2, 1);  // readings at 1 h and 2 h
  c.zero();
  const pkm::geometry::RigidTransform origin = pkm::geometry::RigidTransform::Identity();
  EXPECT_NEAR(c.actualPose(origin).translation().norm(), 0.0, 1e-15);
  c.next();
  const double one = 1.0 - std::exp(-1.0);  // 63 % after one time constant
  EXPECT_NEAR(c.actualPose(origin).translation().z(), -0.030 * one, 1e-15);
  EXPECT_NEAR(c.actualPose(origin).translation().x(), 0.005 * one, 1e-15);
  c.next();
  EXPECT_NEAR(c.actualPose(origin).translation().z(), -0.030 * (1.0 - std::exp(-2.0)), 1e-15);
  // The struts: α·ΔT·(1 − exp(−τ/τ_w)).
  e.thermal.strut_warmup_k = 2.0;
  EXPECT_NEAR(e.strutGrowth(3600.0), 11.5e-6 * 2.0 * one, 1e-18);
  EXPECT_EQ(sim::Environment{}.strutGrowth(3600.0), 0.0);
}

TEST(MeasurementConditions, TheBeamIsTiltedByTheMisalignmentAndTheReflectorOffsetDrawn) {
  sim::Environment e;
  e.name = "custom";
  e.setup.enabled = true;
  e.setup.beam_misalignment_rad = 1e-3;
  e.setup.reflector_offset_mm = 5.0;
  const Eigen::Vector3d b = Eigen::Vector3d(1.0, 2.0, 2.0) / 3.0;
  double sum2 = 0.0;
  for (std::uint64_t seed = 1; seed <= 400; ++seed) {
    const sim::MeasurementConditions c(e, 0.0, 60.0, 1, seed);
    const Eigen::Vector3d t = c.laserBeam(b);
    EXPECT_NEAR(t.norm(), 1.0, 1e-15);
    EXPECT_NEAR(std::acos(std::min(1.0, t.dot(b))), 1e-3, 1e-9);  // the cosine error's angle
    sum2 += c.reflectorOffset().squaredNorm();
  }
  EXPECT_NEAR(std::sqrt(sum2 / 1200.0), 5.0, 0.3);  // σ per component
  const sim::MeasurementConditions again(e, 0.0, 60.0, 1, 7);
  EXPECT_EQ(again.reflectorOffset(),
            sim::MeasurementConditions(e, 0.0, 60.0, 1, 7).reflectorOffset());
  const sim::Environment ideal;  // kept by reference: must outlive the conditions
  const sim::MeasurementConditions off(ideal, 0.0, 60.0, 1, 7);
  EXPECT_EQ(off.laserBeam(b), b);
  EXPECT_EQ(off.reflectorOffset(), Eigen::Vector3d::Zero());
}

TEST(MeasurementConditions, NonRepeatableErrorsHaveTheirVarianceAndSpectrum) {
  sim::Environment e;
  e.name = "custom";
  e.duration_h = 100.0;
  e.structure.enabled = true;
  e.structure.correlated_sigma_mm = 1e-3;
  e.structure.correlation_s = 60.0;
  e.structure.white_sigma_mm = 0.5e-3;
  const int n = 20000;
  sim::MeasurementConditions c(e, 0.0, 60.0 * n, n, 11);  // 60 s steps
  c.zero();
  const pkm::geometry::RigidTransform origin = pkm::geometry::RigidTransform::Identity();
  std::vector<double> x;
  for (int i = 0; i < n; ++i) {
    c.next();
    x.push_back(c.actualPose(origin).translation().x());
  }
  double sum2 = 0.0, lag = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sum2 += x[i] * x[i];
    if (i > 0) lag += x[i] * x[i - 1];
  }
  // Variance σ_c² + σ_w² = 1.25 µm²; lag-one covariance φ·σ_c², φ = exp(−1): correlation 0.29.
  EXPECT_NEAR(std::sqrt(sum2 / n), std::sqrt(1.25) * 1e-3, 0.05e-3);
  EXPECT_NEAR(lag / sum2, std::exp(-1.0) / 1.25, 0.04);
  sim::MeasurementConditions again(e, 0.0, 60.0 * n, n, 11);
  again.zero();
  again.next();
  EXPECT_EQ(again.actualPose(origin).translation().x(), x.front());
}

TEST(MeasurementConditions, RejectsBadArguments) {
  const sim::Environment e;
  EXPECT_THROW(sim::MeasurementConditions(e, -1.0, 60.0, 1, 1), pkm::InvalidArgument);
  EXPECT_THROW(sim::MeasurementConditions(e, 0.0, 0.0, 1, 1), pkm::InvalidArgument);
  EXPECT_THROW(sim::MeasurementConditions(e, 0.0, 60.0, 0, 1), pkm::InvalidArgument);
  sim::Environment bad = airOnly();
  bad.air.temperature_c.correlation_s = 0.0;
  EXPECT_THROW(sim::MeasurementConditions(bad, 0.0, 60.0, 1, 1), pkm::InvalidArgument);
}

}  // namespace PKM_TEST_NS
