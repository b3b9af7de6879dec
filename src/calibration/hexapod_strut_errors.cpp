// The struts' ball-screw lead errors and the platform's weight as inputs of a hexapod
// calibration's budgets, and the columns of a source with shared (grouped) errors
// (detail/hexapod_errors.hpp).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "detail/contributor.hpp"
#include "detail/hexapod_errors.hpp"
#include "pkm/core/error.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"
#include "pkm/simulation/compliance.hpp"

namespace pkm::calibration::detail {
namespace {

constexpr double kLeadSqrt3 = 1.7320508075688772;
constexpr double kLeadSqrt2 = 1.4142135623730951;
constexpr double kLeadPi = 3.141592653589793;

/// The strut (0–5) of a strut-reading coordinate (6–17).
int strutOf(const MeasuredCoordinate& c) {
  return c.coordinate < 12 ? c.coordinate - 6 : c.coordinate - 12;
}

}  // namespace

kinematics::StrutVector homeReadings(const kinematics::HexapodModel& model) {
  kinematics::HexapodData work(model);
  return kinematics::inverseKinematics(model, work, model.home);
}

double strutReading(const HexapodCalibrationData& data, const MeasuredCoordinate& c) {
  const std::size_t i = c.ref.index;
  const int k = strutOf(c);
  switch (c.ref.kind) {
    case ObservationRef::Kind::kPose:
      return data.poses[i].readings(k);
    case ObservationRef::Kind::kPoint:
      return data.points[i].readings(k);
    case ObservationRef::Kind::kGauge: {
      const ConstrainedMotionData& set = data.constrained[c.ref.set];
      return c.coordinate < 12 ? set.stations[i].readings(k) : set.reference.readings(k);
    }
    case ObservationRef::Kind::kDistance:
      return c.coordinate < 12 ? data.distances[i].readings(k)
                               : (*data.distances[i].readings_from)(k);
  }
  return 0.0;
}

void addLeadSources(std::vector<CoordinateSource>& out,
                    const HexapodCalibrationData& data,
                    const metrology::ActuatorReadings& actuators,
                    LengthUnit unit,
                    const kinematics::StrutVector& reference) {
  const double per_mm = 1.0 / millimetresPer(unit);
  const std::string u(toString(unit));
  const std::vector<MeasuredCoordinate> readings = strutReadings(data);
  if (readings.empty()) return;
  // The slope s_k of strut k, rectangular in ±e_p, moves reading r by s_k·(r − r0_k): one error
  // per strut shared by its readings, u = (e_p/√3)·|r − r0_k| on each.
  const double slope = actuators.lead_error_mm_per_m * 1e-3;  // mm per mm of travel
  if (slope > 0.0) {
    CoordinateSource s;
    double longest = 0.0;
    for (MeasuredCoordinate c : readings) {
      const int k = strutOf(c);
      const double travel = strutReading(data, c) - reference(k);
      c.u = slope / kLeadSqrt3 * travel;
      c.group = k;
      longest = std::max(longest, std::abs(travel));
      s.coordinates.push_back(c);
    }
    s.contributor = makeContributor(
        fmt::format("{} lead error (±{:g} mm/m)", actuators.name, actuators.lead_error_mm_per_m),
        slope * longest,
        u,
        metrology::Distribution::kRectangular,
        fmt::format("ISO 3408-3 e_p: one slope per strut within ±{:g} mm/m, zero at the home "
                    "strut lengths; value at the longest travel from home, {:.1f} {}",
                    actuators.lead_error_mm_per_m,
                    longest,
                    u));
    if (s.contributor.value > 0.0) out.push_back(std::move(s));
  }
  // The long wave A·sin(2π·r/λ + φ), φ unknown: its sine and cosine parts are two errors per
  // strut (groups k and 6 + k), each U-shaped in ±A (u = A/√2), on every reading of the strut.
  const double wave = actuators.lead_wave_mm * per_mm;
  if (wave > 0.0) {
    CoordinateSource s;
    const double omega = 2.0 * kLeadPi / (actuators.lead_wave_length_mm * per_mm);
    for (const MeasuredCoordinate& reading : readings) {
      const double r = strutReading(data, reading);
      MeasuredCoordinate c = reading;
      c.group = strutOf(c);
      c.u = wave / kLeadSqrt2 * std::sin(omega * r);
      s.coordinates.push_back(c);
      c.group = 6 + strutOf(c);
      c.u = wave / kLeadSqrt2 * std::cos(omega * r);
      s.coordinates.push_back(c);
    }
    s.contributor = makeContributor(
        fmt::format("{} lead wave", actuators.name),
        wave,
        u,
        metrology::Distribution::kUShaped,
        fmt::format(
            "ISO 3408-3 V_300p / 2: a wave of {:g} mm wavelength and unknown phase per strut",
            actuators.lead_wave_length_mm));
    out.push_back(std::move(s));
  }
  const double periodic = actuators.lead_periodic_mm * per_mm;
  if (periodic > 0.0) {
    CoordinateSource s;
    s.coordinates = readings;
    for (MeasuredCoordinate& c : s.coordinates) c.u = periodic / kLeadSqrt2;
    s.contributor = makeContributor(fmt::format("{} lead variation per revolution", actuators.name),
                                    periodic,
                                    u,
                                    metrology::Distribution::kUShaped,
                                    "ISO 3408-3 V_2πp / 2, per strut reading");
    out.push_back(std::move(s));
  }
}

namespace {

/// All six readings of the observation side that the strut-reading coordinate `c` belongs to.
kinematics::StrutVector readingsOf(const HexapodCalibrationData& data,
                                   const MeasuredCoordinate& c) {
  kinematics::StrutVector q;
  MeasuredCoordinate each = c;
  const int first = c.coordinate < 12 ? 6 : 12;
  for (int k = 0; k < 6; ++k) {
    each.coordinate = first + k;
    q(k) = strutReading(data, each);
  }
  return q;
}

/// The change of each strut's joint distance under the weights at the FK pose of `q`, mm; zero
/// where the FK does not converge or the struts cannot hold the platform.
kinematics::StrutVector weightDeflection(const kinematics::HexapodModel& model,
                                         kinematics::HexapodData& work,
                                         const kinematics::StrutVector& q,
                                         const simulation::HexapodCompliance& compliance) {
  kinematics::StrutVector d = kinematics::StrutVector::Zero();
  if (!kinematics::forwardKinematics(model, work, q, model.home).ok()) return d;
  try {
    (void)kinematics::inverseKinematics(model, work, kinematics::PoseRpy(work.pose));
    const kinematics::StrutVector loads = simulation::hexapodStrutLoads(model, work, compliance);
    for (int k = 0; k < 6; ++k) {
      int side = 1;
      d(k) = simulation::legDeflection(
          loads(k), compliance.strut_stiffness_n_per_um, compliance.joint_clearance_mm, side);
    }
  } catch (const InvalidArgument&) {
    return kinematics::StrutVector::Zero();
  }
  return d;
}

}  // namespace

void addWeightSource(std::vector<CoordinateSource>& out,
                     const HexapodCalibrationData& data,
                     const metrology::HexapodPlatform& platform,
                     const kinematics::HexapodModel& model) {
  if (!(platform.mass_kg > 0.0)) return;
  PKM_CHECK(model.unit == LengthUnit::kMillimetre,
            "the hexapod platform's weight needs a machine in mm, this one is in {}",
            toString(model.unit));
  simulation::HexapodCompliance compliance;
  compliance.platform_mass_kg = platform.mass_kg;
  compliance.platform_com_mm =
      Eigen::Vector3d(platform.com_x_mm, platform.com_y_mm, platform.com_z_mm);
  compliance.strut_mass_kg = platform.strut_mass_kg;
  compliance.strut_com_fraction = platform.strut_com_fraction;
  compliance.strut_stiffness_n_per_um = platform.strut_stiffness_n_per_um;
  compliance.joint_clearance_mm = platform.joint_clearance_mm;
  kinematics::HexapodData work(model);
  CoordinateSource s;
  double largest = 0.0;
  kinematics::StrutVector q = kinematics::StrutVector::Constant(std::nan("")), d;
  for (MeasuredCoordinate c : strutReadings(data)) {
    if (const kinematics::StrutVector here = readingsOf(data, c); here != q) {
      q = here;
      d = weightDeflection(model, work, q, compliance);
    }
    c.u = d(strutOf(c));
    c.group = 0;
    largest = std::max(largest, std::abs(c.u));
    s.coordinates.push_back(c);
  }
  s.contributor = makeContributor(
      fmt::format("{} ({:g} kg)", platform.name, platform.mass_kg),
      largest,
      "mm",
      metrology::Distribution::kNormal,
      "the struts' deflection under the weights, not corrected (GUM F.2.4.5): standard "
      "uncertainty the largest deflection, scaling every reading's");
  if (largest > 0.0) out.push_back(std::move(s));
}

SourceColumns sourceColumns(const CoordinateSource& source) {
  SourceColumns out;
  std::map<int, Eigen::Index> groups;
  for (const MeasuredCoordinate& c : source.coordinates) {
    if (c.group < 0) {
      out.column.push_back(out.count++);
      continue;
    }
    const auto [it, added] = groups.emplace(c.group, out.count);
    if (added) ++out.count;
    out.column.push_back(it->second);
  }
  return out;
}

}  // namespace pkm::calibration::detail
