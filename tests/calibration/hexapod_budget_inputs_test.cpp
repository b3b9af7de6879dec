// The inputs of a hexapod calibration's budgets beyond the instrument (hexapod_budget.hpp): the
// prior's own uncertainty, the machine's strut readings, and the model's remainder at the tool.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "constrained_samples.hpp"
#include "pkm/calibration/hexapod_budget.hpp"
#include "pkm/core/error.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"
#include "pkm/simulation/compliance.hpp"
#include "support/sample_models.hpp"
#include "support/tolerances.hpp"

namespace pkm::calibration {
namespace PKM_TEST_NS {

using kinematics::HexapodModel;

/// Dial-gauge data (24 stations) of the milling hexapod with ±0.5 mm parameter errors.
HexapodCalibrationData gaugeData(const HexapodModel& nominal) {
  const HexapodModel truth = test::perturbedModel(nominal, test::kSeed + 7, 0.5);
  HexapodCalibrationData data;
  data.constrained.push_back(
      test::constrainedData(nominal, truth, 200.0, 24, test::kSeed + 8, 150.0, 0.2));
  return data;
}

/// Options of a gauge fit with a prior of σ_θ = `prior` mm and 2 µm readings.
HexapodCalibrationOptions priorOptions(double prior) {
  HexapodCalibrationOptions options;
  options.measurement_sigma = 0.002;
  options.parameter_prior_sigma = prior;
  return options;
}

/// Sources with perfect dial gauges and perfect strut readings: what a test adds is all there is.
metrology::UncertaintySources nothingButWhatIsAdded() {
  metrology::UncertaintySources s;
  s.dial_gauge.accuracy_mm = s.dial_gauge.resolution_mm = 0.0;
  s.actuators.resolution_mm = s.actuators.backlash_mm = s.actuators.repeatability_mm = 0.0;
  return s;
}

TEST(HexapodParameterUncertainty, WhereTheDataSeeNothingThePriorsSigmaIsTheUncertainty) {
  // Dial gauges see the platform's height and tilt only: 4 combinations of the base joints are
  // not identifiable. The estimate there is the machine file's value, and its uncertainty is the
  // prior's σ_θ, not the gauges' few micrometres.
  constexpr double kPriorSigma = 2.0;  ///< mm
  const HexapodModel nominal = test::millingModel();
  const HexapodCalibrationData data = gaugeData(nominal);
  const HexapodCalibrationOptions options = priorOptions(kPriorSigma);
  const HexapodCalibrationSummary fit = calibrateHexapod(nominal, data, options);
  ASSERT_LT(fit.identifiability.rank, kHexapodParameters);
  const HexapodParameterUncertainty u =
      hexapodParameterUncertainty(nominal, data, fit, options, {});
  const Eigen::MatrixXd& N = fit.identifiability.null_space;
  ASSERT_EQ(N.cols(), kHexapodParameters - fit.identifiability.rank);
  for (Eigen::Index j = 0; j < N.cols(); ++j) {
    const Eigen::VectorXd v = N.col(j).normalized();
    EXPECT_NEAR(std::sqrt(v.dot(u.covariance * v)), kPriorSigma, 0.01 * kPriorSigma) << j;
  }
  // The budget of the data alone claims almost no uncertainty in those directions (they are
  // outside its identifiable subspace, up to rounding).
  const HexapodParameterUncertainty none = hexapodParameterUncertainty(nominal, data, fit, {}, {});
  EXPECT_LT(std::sqrt(N.col(0).normalized().dot(none.covariance * N.col(0).normalized())),
            0.05 * kPriorSigma);
}

TEST(HexapodParameterUncertainty, StatedPriorUncertaintyReplacesThePriorsWeight) {
  // A prior regularising at 2 mm while the budget states the machine file to 8 mm: in the
  // directions the data do not see, U follows the stated 8 mm.
  const HexapodModel nominal = test::millingModel();
  const HexapodCalibrationData data = gaugeData(nominal);
  HexapodCalibrationOptions options = priorOptions(2.0);
  options.prior_uncertainty = 8.0;
  const HexapodCalibrationSummary fit = calibrateHexapod(nominal, data, options);
  const HexapodParameterUncertainty u =
      hexapodParameterUncertainty(nominal, data, fit, options, {});
  const Eigen::VectorXd v = fit.identifiability.null_space.col(0).normalized();
  EXPECT_NEAR(std::sqrt(v.dot(u.covariance * v)), 8.0, 0.08);
  options.prior_uncertainty = -1.0;
  EXPECT_THROW(options.validate(), InvalidArgument);
  options.prior_uncertainty = 1.0;
  options.parameter_prior_sigma = 0.0;
  EXPECT_THROW(options.validate(), InvalidArgument);
}

TEST(HexapodParameterUncertainty, StrutReadingsAreInputsAndTheirBacklashUnlessEstimated) {
  // The gauges' fit turns every strut reading (the reference station's too) into the
  // parameters; the GUM S1 re-fits on perturbed readings agree with the linear propagation.
  const HexapodModel nominal = test::millingModel();
  const HexapodCalibrationData data = gaugeData(nominal);
  const HexapodCalibrationOptions options = priorOptions(2.0);
  const HexapodCalibrationSummary fit = calibrateHexapod(nominal, data, options);
  metrology::UncertaintySources only_struts;
  only_struts.dial_gauge.accuracy_mm = only_struts.dial_gauge.resolution_mm = 0.0;
  only_struts.actuators.resolution_mm = only_struts.actuators.backlash_mm = 0.0;
  const HexapodParameterUncertainty u =
      hexapodParameterUncertainty(nominal, data, fit, options, only_struts);
  const metrology::UncertaintyBudget& b = u.linear.budgets.front();
  ASSERT_GE(b.contributors.size(), 1u);
  EXPECT_NE(b.contributors.front().name.find("repeatability"), std::string::npos);
  BudgetMonteCarloOptions mc;
  mc.batch = 50;
  mc.max_trials = 200;
  const BudgetMonteCarloResult m =
      hexapodBudgetMonteCarlo(nominal, data, fit, options, only_struts, u, mc);
  constexpr double kAgreement = 0.25;  ///< 200 trials: u to about ±10 % (1σ)
  for (std::size_t k = 0; k < u.linear.budgets.size(); ++k) {
    const double linear = u.linear.budgets[k].combinedStandardUncertainty();
    EXPECT_NEAR(m.unknowns[k].standard_uncertainty, linear, kAgreement * linear)
        << u.linear.budgets[k].quantity;
  }
  // The default actuators also carry the encoder's resolution and the backlash (an input only
  // while the fit does not estimate it: hexapodCoordinateSources).
  const HexapodParameterUncertainty all =
      hexapodParameterUncertainty(nominal, data, fit, options, {});
  std::string names;
  for (const metrology::UncertaintyContributor& c : all.linear.budgets.front().contributors)
    names += c.name + ";";
  EXPECT_NE(names.find("backlash"), std::string::npos) << names;
  EXPECT_NE(names.find("resolution"), std::string::npos) << names;
}

/// `data` with every reading r of strut k moved by `shift(r)`.
template <class Shift>
HexapodCalibrationData withStrutShift(HexapodCalibrationData data, int k, Shift shift) {
  for (ConstrainedMotionData& set : data.constrained) {
    set.reference.readings(k) += shift(set.reference.readings(k));
    for (GaugeStation& s : set.stations) s.readings(k) += shift(s.readings(k));
  }
  return data;
}

/// The standard uncertainty a budget lists for its contributor whose name contains `part`.
double contribution(const metrology::UncertaintyBudget& b, const std::string& part) {
  for (const metrology::UncertaintyContributor& c : b.contributors)
    if (c.name.find(part) != std::string::npos)
      return std::abs(c.sensitivity) * c.standardUncertainty();
  return std::numeric_limits<double>::quiet_NaN();
}

TEST(HexapodParameterUncertainty, TheScrewsLeadErrorIsOneSlopePerStrutAndAWaveOfUnknownPhase) {
  // Independent check by re-fitting: a slope s on strut k moves the estimate by δθ_k(s); the
  // budget's lead-error term must be √(Σ_k δθ_k(e_p)²)/√3 (rectangular slopes in ±e_p), and its
  // wave term √(Σ_k δθ_k(A·sin)² + δθ_k(A·cos)²)/√2 (U-shaped parts of amplitude A). The fit is
  // linear over such shifts: named tolerance 2 % of the term plus 1e-6 mm.
  const HexapodModel nominal = test::millingModel();
  const HexapodCalibrationData data = gaugeData(nominal);
  const HexapodCalibrationOptions options = priorOptions(2.0);
  const HexapodCalibrationSummary fit = calibrateHexapod(nominal, data, options);
  metrology::UncertaintySources lead = nothingButWhatIsAdded();
  lead.actuators.lead_error_mm_per_m = 0.1;
  lead.actuators.lead_wave_mm = 0.01;
  lead.actuators.lead_wave_length_mm = 300.0;
  const HexapodParameterUncertainty u =
      hexapodParameterUncertainty(nominal, data, fit, options, lead);
  kinematics::HexapodData work(nominal);
  const kinematics::StrutVector home = kinematics::inverseKinematics(nominal, work, nominal.home);
  const double slope = 1e-4, wave = 0.01, omega = 2.0 * M_PI / 300.0;
  Eigen::VectorXd slope_var = Eigen::VectorXd::Zero(kHexapodParameters);
  Eigen::VectorXd wave_var = Eigen::VectorXd::Zero(kHexapodParameters);
  const auto shiftOf = [&](const HexapodCalibrationData& d) -> HexapodParameterVector {
    return calibrateHexapod(nominal, d, options).parameters - fit.parameters;
  };
  for (int k = 0; k < 6; ++k) {
    const auto r0 = home(k);
    slope_var += shiftOf(withStrutShift(data, k, [&](double r) { return slope * (r - r0); }))
                     .array()
                     .square()
                     .matrix() /
                 3.0;
    wave_var +=
        shiftOf(withStrutShift(data, k, [&](double r) { return wave * std::sin(omega * r); }))
            .array()
            .square()
            .matrix() /
        2.0;
    wave_var +=
        shiftOf(withStrutShift(data, k, [&](double r) { return wave * std::cos(omega * r); }))
            .array()
            .square()
            .matrix() /
        2.0;
  }
  int checked = 0;
  for (std::size_t b = 0; b < u.linear.budgets.size(); ++b) {
    const int k = u.parameter_indices[b];
    if (k < 0) continue;
    const metrology::UncertaintyBudget& budget = u.linear.budgets[b];
    const double expected_slope = std::sqrt(slope_var(k)), expected_wave = std::sqrt(wave_var(k));
    EXPECT_NEAR(contribution(budget, "lead error"), expected_slope, 0.02 * expected_slope + 1e-6)
        << budget.quantity;
    EXPECT_NEAR(contribution(budget, "lead wave"), expected_wave, 0.02 * expected_wave + 1e-6)
        << budget.quantity;
    checked += expected_slope > 1e-3 ? 1 : 0;
  }
  EXPECT_GE(checked, 6);  // the strut offsets at least, which the slopes move by ~0.1 mm
}

TEST(HexapodBudgetMonteCarlo, DrawsOneLeadSlopePerStrutForAllOfItsReadings) {
  // The Monte Carlo draws one slope per strut for all of its readings: it agrees with the linear
  // propagation (200 trials: u to about ±10 %, 1σ). Named tolerance: 25 %.
  const HexapodModel nominal = test::millingModel();
  const HexapodCalibrationData data = gaugeData(nominal);
  const HexapodCalibrationOptions options = priorOptions(2.0);
  const HexapodCalibrationSummary fit = calibrateHexapod(nominal, data, options);
  metrology::UncertaintySources lead = nothingButWhatIsAdded();
  lead.actuators.lead_error_mm_per_m = 0.1;
  const HexapodParameterUncertainty only_slope =
      hexapodParameterUncertainty(nominal, data, fit, options, lead);
  BudgetMonteCarloOptions mc;
  mc.batch = 50;
  mc.max_trials = 200;
  const BudgetMonteCarloResult m =
      hexapodBudgetMonteCarlo(nominal, data, fit, options, lead, only_slope, mc);
  for (std::size_t b = 0; b < only_slope.linear.budgets.size(); ++b) {
    const double linear = only_slope.linear.budgets[b].combinedStandardUncertainty();
    if (linear < 1e-3) continue;
    EXPECT_NEAR(m.unknowns[b].standard_uncertainty, linear, 0.25 * linear)
        << only_slope.linear.budgets[b].quantity;
  }
}

TEST(HexapodParameterUncertainty, ThePlatformsWeightIsTheDeflectionTheStaticsGive) {
  // The weight term is the parameters' shift that the struts' deflection causes, stated as a
  // standard uncertainty (GUM F.2.4.5). Independent check by re-fitting readings deflected by the
  // simulator's statics at each station's pose (FK of its readings). The gauge fit leans on its
  // prior in four directions and re-converges there only to about 1e-3 mm, so terms are compared
  // with the largest shift (0.29 mm); measured: every term within 0.9 % of it. Named tolerance:
  // 5 % of the largest shift.
  const HexapodModel nominal = test::millingModel();
  const HexapodCalibrationData data = gaugeData(nominal);
  const HexapodCalibrationOptions options = priorOptions(2.0);
  const HexapodCalibrationSummary fit = calibrateHexapod(nominal, data, options);
  metrology::UncertaintySources weight = nothingButWhatIsAdded();
  weight.hexapod_platform.mass_kg = 150.0;
  weight.hexapod_platform.com_z_mm = -100.0;
  weight.hexapod_platform.strut_mass_kg = 20.0;
  weight.hexapod_platform.joint_clearance_mm = 0.004;
  const HexapodParameterUncertainty u =
      hexapodParameterUncertainty(nominal, data, fit, options, weight);
  simulation::HexapodCompliance c;
  c.platform_mass_kg = 150.0;
  c.platform_com_mm = Eigen::Vector3d(0, 0, -100);
  c.strut_mass_kg = 20.0;
  c.joint_clearance_mm = 0.004;
  kinematics::HexapodData work(nominal);
  const auto deflect = [&](kinematics::StrutVector& q) {
    ASSERT_TRUE(kinematics::forwardKinematics(nominal, work, q, nominal.home).ok());
    (void)kinematics::inverseKinematics(nominal, work, kinematics::PoseRpy(work.pose));
    const kinematics::StrutVector loads = simulation::hexapodStrutLoads(nominal, work, c);
    for (int k = 0; k < 6; ++k) {
      int side = 1;
      q(k) += simulation::legDeflection(
          loads(k), c.strut_stiffness_n_per_um, c.joint_clearance_mm, side);
    }
  };
  HexapodCalibrationData deflected = data;
  for (ConstrainedMotionData& set : deflected.constrained) {
    deflect(set.reference.readings);
    for (GaugeStation& st : set.stations) deflect(st.readings);
  }
  const HexapodParameterVector shift =
      calibrateHexapod(nominal, deflected, options).parameters - fit.parameters;
  const double largest = shift.cwiseAbs().maxCoeff();
  ASSERT_GT(largest, 0.1);
  int moved = 0;
  double worst = 0.0;
  for (std::size_t b = 0; b < u.linear.budgets.size(); ++b) {
    const int k = u.parameter_indices[b];
    if (k < 0) continue;
    const double expected = std::abs(shift(k));
    worst = std::max(worst, std::abs(contribution(u.linear.budgets[b], "weight") - expected));
    EXPECT_NEAR(contribution(u.linear.budgets[b], "weight"), expected, 0.05 * largest)
        << u.linear.budgets[b].quantity;
    moved += expected > 0.1 * largest ? 1 : 0;
  }
  RecordProperty("largest_shift_mm", std::to_string(largest));
  RecordProperty("worst_over_largest", std::to_string(worst / largest));
  EXPECT_GE(moved, 6);
  // The statics are the mm model's: an inch machine is refused by name.
  HexapodModel inch = nominal;
  inch.unit = LengthUnit::kInch;
  EXPECT_THROW((void)hexapodParameterUncertainty(inch, data, fit, options, weight),
               InvalidArgument);
}

TEST(HexapodTcpUncertainty, TheModelsRemainderAddsInQuadrature) {
  TcpUncertainty tcp;
  tcp.expanded = {0.03, std::numeric_limits<double>::quiet_NaN(), 0.04};
  tcp.poses = 2;
  const double rms = 0.05 * std::sqrt(3.0);  // R = k·rms/√3 = 0.1 at k = 2
  addTcpRemainder(tcp, rms, 2.0);
  EXPECT_NEAR(tcp.expanded[0], std::hypot(0.03, 0.1), 1e-15);
  EXPECT_TRUE(std::isnan(tcp.expanded[1]));
  EXPECT_NEAR(tcp.max, std::hypot(0.04, 0.1), 1e-15);
  EXPECT_NEAR(tcp.mean, 0.5 * (std::hypot(0.03, 0.1) + std::hypot(0.04, 0.1)), 1e-15);
  EXPECT_NEAR(tcp.remainder, 0.1, 1e-15);
  EXPECT_THROW(addTcpRemainder(tcp, -1.0, 2.0), InvalidArgument);
  EXPECT_THROW(addTcpRemainder(tcp, 0.1, 0.0), InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::calibration
