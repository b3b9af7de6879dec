#include "pkm/calibration/exechon_budget.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "pkm/core/error.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/simulation/compliance.hpp"
#include "pkm/simulation/exechon_tracker.hpp"
#include "pkm/simulation/hybrid_tripod_errors.hpp"
#include "support/tolerances.hpp"

namespace pkm::calibration {
namespace PKM_TEST_NS {

using kinematics::ExechonModel;

constexpr double kNoise = 0.005;  ///< mm: simulated tracker noise per coordinate
constexpr double kDeg = M_PI / 180.0;

/// A world-frame calibration of the mxt700s-like Exechon with a few assembly errors (base
/// placement known), as in exechon_uncertainty_test.cpp.
struct Problem {
  ExechonModel initial = io::loadExechonMachine("mxt700s-like").model;
  ExechonCalibrationData data;
  ExechonCalibrationOptions options;
  ExechonCalibrationSummary fit;
  std::vector<kinematics::ExechonJoints> check;
  Problem() {
    simulation::ExechonTripodErrors e;
    e.dA = 1.2;
    e.pA = 0.6;
    e.length_offset = Eigen::Vector3d(0.8, -1.1, 0.5);
    e.c0 = 0.8e-3;
    e.tool_length = 0.3;
    const ExechonModel truth = simulation::perturbedExechon(initial, e);
    simulation::ExechonTrackerSetup s;
    s.name = "budget";
    s.count = 25;
    s.box_min = Eigen::Vector3d(-300, -300, -100);
    s.box_max = Eigen::Vector3d(300, 300, 300);
    s.max_tilt = 30 * kDeg;
    s.smr_offset = Eigen::Vector3d(40, 0, 20);
    s.noise.range_sigma = kNoise;
    s.noise.angle_sigma = kNoise / 2000.0;
    simulation::RandomStream rng(test::kSeed, s.name);
    data.target_offset = s.smr_offset;
    for (const auto& r : simulation::simulateExechonTracker(initial, truth, {}, s, rng)) {
      ExechonObservation o;
      o.joints = r.joints;
      o.point = r.measured;
      data.observations.push_back(o);
      check.push_back(r.joints);
    }
    for (int k = kExechonBaseParameter; k < kExechonParameters; ++k)
      options.free[static_cast<std::size_t>(k)] = false;
    options.measurement_sigma = kNoise;
    fit = calibrateExechon(initial, data, options);
  }
};

const Problem& problem() {
  static const Problem p;
  return p;
}

/// A tracker of ±half_width per coordinate and perfect leg readings.
metrology::UncertaintySources tracker(double half_width_mm) {
  metrology::UncertaintySources s;
  s.tracker.accuracy_mm = half_width_mm;
  s.tracker.accuracy_mm_per_m = 0.0;
  s.actuators.resolution_mm = s.actuators.repeatability_mm = s.actuators.backlash_mm = 0.0;
  return s;
}

/// The standard uncertainty a budget lists for its contributor whose name contains `part`.
double contribution(const metrology::UncertaintyBudget& b, const std::string& part) {
  for (const metrology::UncertaintyContributor& c : b.contributors)
    if (c.name.find(part) != std::string::npos)
      return std::abs(c.sensitivity) * c.standardUncertainty();
  return std::nan("");
}

/// The change of the estimate when every observation's joints become `change(joints)`.
template <class Change>
ExechonParameterVector shiftOf(const Problem& p, Change change) {
  ExechonCalibrationData d = p.data;
  for (ExechonObservation& o : d.observations) o.joints = change(o.joints);
  return calibrateExechon(p.initial, d, p.options).parameters - p.fit.parameters;
}

TEST(ExechonParameterUncertainty, TheFitScatterAloneIsTheFitCovariance) {
  const Problem& p = problem();
  const ExechonParameterUncertainty u =
      exechonParameterUncertainty(p.initial, p.data, p.fit, p.options, tracker(0.0));
  ASSERT_EQ(u.linear.budgets.size(), p.fit.free_indices.size());
  EXPECT_DOUBLE_EQ(u.linear.fit_sigma, kNoise);
  for (std::size_t b = 0; b < u.linear.budgets.size(); ++b) {
    const int k = u.parameter_indices[b];
    ASSERT_GE(k, 0);
    EXPECT_NEAR(std::sqrt(u.covariance(k, k)),
                p.fit.standard_deviation(k),
                1e-3 * p.fit.standard_deviation(k))
        << exechonParameterName(k);
  }
}

TEST(ExechonParameterUncertainty, AnInstrumentThatExplainsTheScatterReplacesTheTypeA) {
  // A tracker of ±√3·σ rectangular has u = σ per coordinate: it explains the residual σ entirely,
  // so no Type A remains and the budgets equal the fit covariance, now from the instrument.
  const Problem& p = problem();
  const ExechonParameterUncertainty u = exechonParameterUncertainty(
      p.initial, p.data, p.fit, p.options, tracker(std::sqrt(3.0) * kNoise));
  EXPECT_NEAR(u.linear.instrument_sigma, kNoise, 1e-12);
  EXPECT_EQ(u.linear.fit_sigma, 0.0);
  for (std::size_t b = 0; b < u.linear.budgets.size(); ++b) {
    const metrology::UncertaintyBudget& budget = u.linear.budgets[b];
    ASSERT_EQ(budget.contributors.size(), 1u) << budget.quantity;
    EXPECT_EQ(budget.contributors[0].distribution, metrology::Distribution::kRectangular);
    const int k = u.parameter_indices[b];
    EXPECT_NEAR(budget.combinedStandardUncertainty(),
                p.fit.standard_deviation(k),
                1e-3 * p.fit.standard_deviation(k));
    EXPECT_EQ(budget.unit, exechonParameterIsLength(k) ? "mm" : "rad");
  }
  metrology::UncertaintySources bad = tracker(1.0);
  bad.coverage_factor = 0.0;
  EXPECT_THROW((void)exechonParameterUncertainty(p.initial, p.data, p.fit, p.options, bad),
               InvalidArgument);
}

TEST(ExechonParameterUncertainty, TheHeadsWeightIsTheDeflectionTheSimulatorsStaticsGive) {
  // The budget's head-weight term is the parameters' shift that the legs' deflection causes,
  // stated as a standard uncertainty (GUM F.2.4.5). Independent check: the simulator's own
  // statics (simulation::exechonDeflectedJoints, the virtual machine's compliance) deflect the
  // readings, and the re-fit's shift is that term. The re-fit is checked at a tenth of the
  // deflection (ten times as stiff, a tenth of the clearance) and scaled by ten: at the full
  // deflection it departs from its linearisation by up to 6 % in the two worst-conditioned
  // parameters (l12A, pC), which is the fit's nonlinearity, not the propagation's error. Named
  // tolerance: 2 % plus 1e-6 (mm or rad).
  const Problem& p = problem();
  metrology::UncertaintySources src = tracker(0.0);
  src.exechon_head.mass_kg = 250.0;
  src.exechon_head.com_z_mm = 200.0;
  src.exechon_head.leg_stiffness_n_per_um = 50.0;
  src.exechon_head.joint_clearance_mm = 0.004;
  const ExechonParameterUncertainty u =
      exechonParameterUncertainty(p.initial, p.data, p.fit, p.options, src);
  const ExechonModel estimate =
      withExechonParameters(p.initial, p.fit.parameters, p.initial.world_T_zoppi);
  simulation::ExechonCompliance head;
  head.head_mass_kg = 250.0;
  head.head_com_mm = Eigen::Vector3d(0, 0, 200);
  head.leg_stiffness_n_per_um = 500.0;
  head.joint_clearance_mm = 0.0004;
  const ExechonParameterVector shift =
      10.0 * shiftOf(p, [&](const kinematics::ExechonJoints& q) {
        return simulation::exechonDeflectedJoints(estimate, q, estimate.home, p.options.fk, head);
      });
  int moved = 0;
  for (std::size_t b = 0; b < u.linear.budgets.size(); ++b) {
    const int k = u.parameter_indices[b];
    if (k < 0) continue;
    const double expected = std::abs(shift(k));
    EXPECT_NEAR(contribution(u.linear.budgets[b], "head"), expected, 0.02 * expected + 1e-6)
        << exechonParameterName(k);
    moved += expected > 1e-3 ? 1 : 0;
  }
  EXPECT_GE(moved, 3);
}

TEST(ExechonParameterUncertainty, TheLegsLeadErrorIsOneSlopePerLegFromMidStroke) {
  // As the hexapod's: a slope s on leg l, zero at mid-stroke, shifts the estimate by δθ_l(s); the
  // budget's term is √(Σ_l δθ_l(e_p)²)/√3. Named tolerance: 2 % plus 1e-6.
  const Problem& p = problem();
  metrology::UncertaintySources src = tracker(0.0);
  src.actuators.lead_error_mm_per_m = 0.1;
  const ExechonParameterUncertainty u =
      exechonParameterUncertainty(p.initial, p.data, p.fit, p.options, src);
  ExechonParameterVector variance = ExechonParameterVector::Zero();
  for (int l = 0; l < 3; ++l) {
    const kinematics::ExechonLeg& leg = p.initial.legs[static_cast<std::size_t>(l)];
    ASSERT_TRUE(std::isfinite(leg.min_reading) && std::isfinite(leg.max_reading));
    const double mid = 0.5 * (leg.min_reading + leg.max_reading);
    const ExechonParameterVector shift = shiftOf(p, [&](kinematics::ExechonJoints q) {
      q.readings(l) += 1e-4 * (q.readings(l) - mid);
      return q;
    });
    variance += shift.array().square().matrix() / 3.0;
  }
  for (std::size_t b = 0; b < u.linear.budgets.size(); ++b) {
    const int k = u.parameter_indices[b];
    if (k < 0) continue;
    const double expected = std::sqrt(variance(k));
    EXPECT_NEAR(contribution(u.linear.budgets[b], "lead error"), expected, 0.02 * expected + 1e-6)
        << exechonParameterName(k);
  }
}

TEST(ExechonBudgetMonteCarlo, AgreesWithTheLinearPropagationOnANearLinearCalibration) {
  // A ±10 µm tracker on a 600 mm workspace: the calibration is linear over such errors, so the
  // GUM Supplement 1 standard uncertainties equal the linear ones within sampling error (a
  // standard deviation from M samples scatters by 1/√(2M): 7 % at M = 100). Measured: mean ratio
  // 0.98 at 200 trials. Named tolerance: the mean ratio within 10 %, each within 30 %.
  const Problem& p = problem();
  const metrology::UncertaintySources src = tracker(0.01);
  const ExechonParameterUncertainty lin =
      exechonParameterUncertainty(p.initial, p.data, p.fit, p.options, src);
  BudgetMonteCarloOptions mc;
  mc.batch = 20;
  mc.max_trials = 100;
  mc.threads = 2;
  const BudgetMonteCarloResult a =
      exechonBudgetMonteCarlo(p.initial, p.data, p.fit, p.options, src, lin, mc);
  EXPECT_EQ(a.failures, 0);
  EXPECT_GE(a.trials, 2 * mc.batch);
  ASSERT_EQ(a.unknowns.size(), lin.linear.budgets.size());
  double ratio = 0.0;
  for (std::size_t k = 0; k < a.unknowns.size(); ++k) {
    const double r =
        a.unknowns[k].standard_uncertainty / lin.linear.budgets[k].combinedStandardUncertainty();
    EXPECT_NEAR(r, 1.0, 0.3) << lin.linear.budgets[k].quantity;
    ratio += r;
    // The trials scatter about the estimate (the data are its own prediction plus errors).
    EXPECT_NEAR(a.unknowns[k].mean,
                lin.linear.budgets[k].value,
                4.0 * a.unknowns[k].standard_uncertainty / std::sqrt(a.trials))
        << lin.linear.budgets[k].quantity;
  }
  ratio /= static_cast<double>(a.unknowns.size());
  RecordProperty("mc_over_linear", std::to_string(ratio));
  EXPECT_NEAR(ratio, 1.0, 0.10);
  // The same trials on one thread: bitwise the same result.
  mc.threads = 1;
  const BudgetMonteCarloResult b =
      exechonBudgetMonteCarlo(p.initial, p.data, p.fit, p.options, src, lin, mc);
  EXPECT_EQ(a.trials, b.trials);
  EXPECT_EQ(a.unknowns[2].standard_uncertainty, b.unknowns[2].standard_uncertainty);
  mc.batch = 5;
  EXPECT_THROW((void)exechonBudgetMonteCarlo(p.initial, p.data, p.fit, p.options, src, lin, mc),
               InvalidArgument);
}

TEST(ExechonToolUncertainty, LiesBetweenTheTraceBoundsOfTheLinearisedTargetUncertainty) {
  // k·√λ_max of a 3 × 3 covariance lies between k·√(trace/3) and k·√trace
  // (exechonTargetUncertainty gives √trace).
  const Problem& p = problem();
  const ExechonModel estimate =
      withExechonParameters(p.initial, p.fit.parameters, p.initial.world_T_zoppi);
  const Eigen::MatrixXd cov =
      p.fit.covariance.topLeftCorner(kExechonParameters, kExechonParameters);
  const TcpUncertainty t =
      exechonToolUncertainty(estimate, cov, p.check, p.data.target_offset, p.options.fk, 2.0);
  ASSERT_EQ(t.poses, static_cast<int>(p.check.size()));
  for (std::size_t i = 0; i < p.check.size(); ++i) {
    const auto trace = exechonTargetUncertainty(
        estimate, cov, p.check[i], p.data.target_offset, estimate.home, p.options.fk);
    ASSERT_TRUE(trace.has_value());
    EXPECT_LE(t.expanded[i], 2.0 * *trace * (1 + 1e-9));
    EXPECT_GE(t.expanded[i], 2.0 * *trace / std::sqrt(3.0) * (1 - 1e-9));
  }
  EXPECT_THROW((void)exechonToolUncertainty(
                   estimate, Eigen::MatrixXd::Zero(2, 2), p.check, p.data.target_offset),
               InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::calibration
