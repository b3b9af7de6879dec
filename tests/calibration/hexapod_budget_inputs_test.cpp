// The inputs of a hexapod calibration's budgets beyond the instrument (hexapod_budget.hpp): the
// prior's own uncertainty, the machine's strut readings, and the model's remainder at the tool.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "constrained_samples.hpp"
#include "pkm/calibration/hexapod_budget.hpp"
#include "pkm/core/error.hpp"
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
