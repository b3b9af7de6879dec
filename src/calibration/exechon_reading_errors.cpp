// The errors of an Exechon calibration's leg readings (detail/exechon_reading_errors.hpp).
#include "detail/exechon_reading_errors.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "detail/contributor.hpp"
#include "pkm/core/error.hpp"
#include "pkm/simulation/compliance.hpp"

namespace pkm::calibration::detail {
namespace {

using metrology::Distribution;

void addLegSource(std::vector<LegReadingSource>& out, LegReadingSource s) {
  if (s.contributor.value > 0.0 && s.readings.size() > 0) out.push_back(std::move(s));
}

/// The travel of every reading from its leg's lead reference (mid-stroke, or the mean).
Eigen::VectorXd travels(const kinematics::ExechonModel& model, const ExechonCalibrationData& data) {
  const auto n = static_cast<Eigen::Index>(data.observations.size());
  Eigen::VectorXd t(3 * n);
  for (int l = 0; l < 3; ++l) {
    const kinematics::ExechonLeg& leg = model.legs[static_cast<std::size_t>(l)];
    double reference = 0.0;
    if (std::isfinite(leg.min_reading) && std::isfinite(leg.max_reading)) {
      reference = 0.5 * (leg.min_reading + leg.max_reading);
    } else {
      for (const ExechonObservation& o : data.observations) reference += o.joints.readings(l);
      reference /= static_cast<double>(std::max<Eigen::Index>(n, 1));
    }
    for (Eigen::Index i = 0; i < n; ++i)
      t(3 * i + l) = data.observations[static_cast<std::size_t>(i)].joints.readings(l) - reference;
  }
  return t;
}

/// The change of every leg reading that the head's weight causes, mm: the simulator's statics
/// (simulation::exechonDeflectedJoints: loads by virtual work, axial stiffness, clearance); zero
/// where an FK does not converge.
Eigen::VectorXd headDeflections(const kinematics::ExechonModel& model,
                                const ExechonCalibrationData& data,
                                const metrology::ExechonHead& head,
                                const kinematics::FkOptions& fk) {
  PKM_CHECK(model.unit == LengthUnit::kMillimetre,
            "the Exechon head's weight needs a machine in mm, this one is in {}",
            toString(model.unit));
  simulation::ExechonCompliance c;
  c.head_mass_kg = head.mass_kg;
  c.head_com_mm = Eigen::Vector3d(head.com_x_mm, head.com_y_mm, head.com_z_mm);
  c.leg_stiffness_n_per_um = head.leg_stiffness_n_per_um;
  c.joint_clearance_mm = head.joint_clearance_mm;
  const auto n = static_cast<Eigen::Index>(data.observations.size());
  Eigen::VectorXd d = Eigen::VectorXd::Zero(3 * n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const kinematics::ExechonJoints& q = data.observations[static_cast<std::size_t>(i)].joints;
    try {
      d.segment<3>(3 * i) =
          simulation::exechonDeflectedJoints(model, q, model.home, fk, c).readings - q.readings;
    } catch (const InvalidArgument&) {
      continue;  // no converging FK: this observation's deflection is unknown, left at zero
    }
  }
  return d;
}

/// The screws' lead slope (one per leg) and long wave (a sine and a cosine part per leg).
void addLeadLegSources(std::vector<LegReadingSource>& out,
                       const kinematics::ExechonModel& model,
                       const ExechonCalibrationData& data,
                       const metrology::ActuatorReadings& a) {
  const double per_mm = 1.0 / millimetresPer(model.unit);
  const std::string u(toString(model.unit));
  const Eigen::Index m = 3 * static_cast<Eigen::Index>(data.observations.size());
  const double slope = a.lead_error_mm_per_m * 1e-3;
  if (slope > 0.0 && m > 0) {
    // One slope per leg: reading i of leg l moves by s_l·t_i; the column at u_ref = e_p·D/√3
    // (D the longest travel) is t_i/D.
    const Eigen::VectorXd t = travels(model, data);
    const double longest = t.cwiseAbs().maxCoeff();
    Eigen::MatrixXd cols = Eigen::MatrixXd::Zero(m, 3);
    for (Eigen::Index r = 0; r < m && longest > 0.0; ++r) cols(r, r % 3) = t(r) / longest;
    addLegSource(
        out,
        {makeContributor(fmt::format("{} lead error (±{:g} mm/m)", a.name, a.lead_error_mm_per_m),
                         slope * longest,
                         u,
                         Distribution::kRectangular,
                         fmt::format("ISO 3408-3 e_p: one slope per leg within ±{:g} mm/m, zero at "
                                     "mid-stroke; value at the longest travel from it, {:.1f} {}",
                                     a.lead_error_mm_per_m,
                                     longest,
                                     u)),
         cols});
  }
  const double wave = a.lead_wave_mm * per_mm;
  if (wave > 0.0 && m > 0) {
    // A·sin(ω·t + φ), φ unknown: per leg a sine and a cosine part, U-shaped in ±A (u = A/√2).
    const Eigen::VectorXd t = travels(model, data);
    const double omega = 2.0 * 3.141592653589793 / (a.lead_wave_length_mm * per_mm);
    Eigen::MatrixXd cols = Eigen::MatrixXd::Zero(m, 6);
    for (Eigen::Index r = 0; r < m; ++r) {
      cols(r, r % 3) = std::sin(omega * t(r));
      cols(r, 3 + r % 3) = std::cos(omega * t(r));
    }
    addLegSource(out,
                 {makeContributor(fmt::format("{} lead wave", a.name),
                                  wave,
                                  u,
                                  Distribution::kUShaped,
                                  fmt::format("ISO 3408-3 V_300p / 2: a wave of {:g} mm wavelength "
                                              "and unknown phase per leg",
                                              a.lead_wave_length_mm)),
                  cols});
  }
}

}  // namespace

std::vector<LegReadingSource> exechonLegReadingSources(const kinematics::ExechonModel& model,
                                                       const ExechonCalibrationData& data,
                                                       const metrology::UncertaintySources& sources,
                                                       const kinematics::FkOptions& fk) {
  std::string why;
  PKM_CHECK(sources.isValid(&why), "{}", why);
  const double per_mm = 1.0 / millimetresPer(model.unit);
  const std::string u(toString(model.unit));
  const metrology::ActuatorReadings& a = sources.actuators;
  const Eigen::Index m = 3 * static_cast<Eigen::Index>(data.observations.size());
  const Eigen::MatrixXd each = Eigen::VectorXd::Ones(m);
  std::vector<LegReadingSource> out;
  // The errors of each reading on its own: encoder, repeatability, backlash, the screw's
  // variation within a revolution (name suffix, value, distribution, where it comes from).
  struct PerReading {
    const char* what;
    double value;
    Distribution distribution;
    const char* source;
  };
  const PerReading per_reading[] = {{"resolution",
                                     0.5 * a.resolution_mm,
                                     Distribution::kRectangular,
                                     "half an encoder count, per leg reading"},
                                    {"repeatability",
                                     a.repeatability_mm,
                                     Distribution::kNormal,
                                     "one standard deviation, per leg reading"},
                                    {"backlash",
                                     0.5 * a.backlash_mm,
                                     Distribution::kUShaped,
                                     "half the lost motion at a reversal, per leg reading"},
                                    {"lead variation per revolution",
                                     a.lead_periodic_mm,
                                     Distribution::kUShaped,
                                     "ISO 3408-3 V_2πp / 2, per leg reading"}};
  for (const PerReading& e : per_reading)
    addLegSource(
        out,
        {makeContributor(
             fmt::format("{} {}", a.name, e.what), e.value * per_mm, u, e.distribution, e.source),
         each,
         true});
  addLeadLegSources(out, model, data, a);
  if (sources.exechon_head.mass_kg > 0.0 && m > 0) {
    const Eigen::VectorXd d = headDeflections(model, data, sources.exechon_head, fk);
    const double largest = d.cwiseAbs().maxCoeff();
    if (largest > 0.0)
      addLegSource(
          out,
          {makeContributor(
               fmt::format("{} ({:g} kg)", sources.exechon_head.name, sources.exechon_head.mass_kg),
               largest,
               u,
               Distribution::kNormal,
               "the legs' deflection under the head's weight, not corrected (GUM F.2.4.5): "
               "standard uncertainty the largest deflection, scaling every reading's"),
           d / largest});
  }
  return out;
}

std::vector<Eigen::Matrix3d> exechonTargetLegJacobian(const kinematics::ExechonModel& model,
                                                      const ExechonCalibrationData& data,
                                                      const kinematics::FkOptions& fk) {
  constexpr double h = 1e-3;  // model length unit, as exechonTargetJacobian's length steps
  std::vector<Eigen::Matrix3d> J(data.observations.size(), Eigen::Matrix3d::Zero());
  for (std::size_t i = 0; i < J.size(); ++i) {
    const ExechonObservation& o = data.observations[i];
    for (int l = 0; l < 3; ++l) {
      kinematics::ExechonJoints plus = o.joints, minus = o.joints;
      plus.readings(l) += h;
      minus.readings(l) -= h;
      const auto pp = exechonTarget(model, plus, data.target_offset, model.home, fk);
      const auto pm = exechonTarget(model, minus, data.target_offset, model.home, fk);
      if (pp && pm) J[i].col(l) = (*pp - *pm) / (2.0 * h);
    }
  }
  return J;
}

Eigen::MatrixXd legEffect(const std::vector<Eigen::Matrix3d>& J_target_legs,
                          const LegReadingSource& source) {
  const auto m = static_cast<Eigen::Index>(3 * J_target_legs.size());
  Eigen::MatrixXd E = Eigen::MatrixXd::Zero(m, source.errors());
  for (Eigen::Index i = 0; i < m / 3; ++i) {
    const Eigen::Matrix3d& J = J_target_legs[static_cast<std::size_t>(i)];
    if (source.each) {
      // Reading 3i + l moves only its own observation's residuals.
      for (Eigen::Index l = 0; l < 3; ++l)
        E.block<3, 1>(3 * i, 3 * i + l) = -J.col(l) * source.readings(3 * i + l, 0);
    } else {
      E.middleRows<3>(3 * i) = -J * source.readings.middleRows<3>(3 * i);
    }
  }
  return E;
}

}  // namespace pkm::calibration::detail
