/// @file
/// @brief Internal: the measured coordinates of hexapod calibration data that an error source
/// acts on, shared by the linear budgets (hexapod_budget.cpp) and their Monte Carlo
/// (hexapod_budget_monte_carlo.cpp), so that both propagate exactly the same inputs.
#pragma once

#include <vector>

#include "calibration/detail/observations.hpp"
#include "pkm/metrology/uncertainty_budget.hpp"
#include "pkm/metrology/uncertainty_sources.hpp"

namespace pkm::calibration::detail {

/// One measured coordinate of one observation. `coordinate`: pose 0–2 position, 3–5 rotation
/// vector (left perturbation, measurement axes), 6–11 strut readings; point 0–2 position, 6–11
/// strut readings; gauge station 0–2 its gauges, 3–5 the reference station's gauges (of
/// ref.set), 6–11 its strut readings, 12–17 the reference station's strut readings, 18 all six
/// of the reference station's strut readings together; distance 0
/// the distance, 6–11 the strut readings at its end (12–17 at its other end on the machine).
struct MeasuredCoordinate {
  ObservationRef ref;
  int coordinate = 0;
  double u = 0.0;  ///< standard uncertainty of the error on it (model unit or rad)
  /// −1: an error of its own. ≥ 0: one error shared by every coordinate of the source with this
  /// group (a screw's lead error on all of its strut's readings), drawn with unit standard
  /// uncertainty and scaled by `u` on each coordinate.
  int group = -1;
};

/// An independent error source: its contributor (value = the reference spread) and every
/// coordinate it acts on, each with an independent error of that distribution.
struct CoordinateSource {
  metrology::UncertaintyContributor contributor;
  std::vector<MeasuredCoordinate> coordinates;
};

/// The instrument and set-up sources of `data` (docs/calibration.md, "Uncertainty budgets"):
/// tracker a + b·L on pose and point positions, 6-DOF probe orientation, dial-gauge accuracy and
/// resolution on every gauge reading, the distance instrument, set-up repeatability when > 0, and
/// the machine's strut readings (encoder resolution, repeatability, and backlash unless
/// `backlash_estimated`). Lengths of `sources` (mm) are converted to `unit`. Sources that act on
/// nothing are left out.
/// `model`: the machine file's, for the screws' lead reference (its home strut lengths) and the
/// platform's statics (addWeightSource).
[[nodiscard]] std::vector<CoordinateSource> hexapodCoordinateSources(
    const HexapodCalibrationData& data,
    const metrology::UncertaintySources& sources,
    const kinematics::HexapodModel& model,
    bool backlash_estimated);

/// The strut lengths of `model` at its home pose (where the encoders are referenced).
[[nodiscard]] kinematics::StrutVector homeReadings(const kinematics::HexapodModel& model);

/// Every strut reading of `data` (coordinates 6–17 of MeasuredCoordinate; the reference station's
/// once per constrained set), u = 1.
[[nodiscard]] std::vector<MeasuredCoordinate> strutReadings(const HexapodCalibrationData& data);

/// The value of the strut reading `c` (coordinate 6–17) in `data`.
[[nodiscard]] double strutReading(const HexapodCalibrationData& data, const MeasuredCoordinate& c);

/// The screws' lead errors as inputs (ActuatorReadings::lead_error_mm_per_m and
/// lead_variation_mm): one rectangular slope per strut acting on each of its readings in
/// proportion to its distance from `reference` (grouped), and a rectangular variation per
/// reading. Sources that act on nothing are left out.
void addLeadSources(std::vector<CoordinateSource>& out,
                    const HexapodCalibrationData& data,
                    const metrology::ActuatorReadings& actuators,
                    LengthUnit unit,
                    const kinematics::StrutVector& reference);

/// The platform's and struts' weight as an input (HexapodPlatform, when its mass is stated): one
/// normal error shared by every strut reading, u on each the deflection the statics predict at
/// its observation's pose (simulation::hexapodStrutLoads at the FK of its readings with `model`,
/// simulation::legDeflection); its value the largest. Throws pkm::InvalidArgument for a model
/// not in mm.
void addWeightSource(std::vector<CoordinateSource>& out,
                     const HexapodCalibrationData& data,
                     const metrology::HexapodPlatform& platform,
                     const kinematics::HexapodModel& model);

/// The expanded sizes of a source's effect: column of each coordinate (grouped coordinates share
/// one) and the number of columns.
struct SourceColumns {
  std::vector<Eigen::Index> column;
  Eigen::Index count = 0;
};
[[nodiscard]] SourceColumns sourceColumns(const CoordinateSource& source);

/// Whether the coordinate `c` belongs to a whole constrained-motion set (the reference station's
/// gauges or strut readings) rather than to its own observation.
[[nodiscard]] bool actsOnWholeSet(const MeasuredCoordinate& c);

/// The residual-space coordinates of every observation (pose readings, point positions, station
/// gauges, distances), each with standard uncertainty `sigma`: the Type A scatter's inputs.
[[nodiscard]] std::vector<MeasuredCoordinate> residualCoordinates(
    const HexapodCalibrationData& data, double sigma);

/// Adds `delta` to the measured coordinate `c` of `data`.
void perturbMeasurement(HexapodCalibrationData& data, const MeasuredCoordinate& c, double delta);

/// Undoes perturbMeasurement of `c` on `data`: copies the observation `c` belongs to (for a
/// gauge station also its set's reference station) back from `original`, which `data` was
/// copied from.
void restoreMeasurement(HexapodCalibrationData& data,
                        const HexapodCalibrationData& original,
                        const MeasuredCoordinate& c);

/// One draw of an error of `distribution` with standard uncertainty `u` from a uniform variate
/// source `uniform` (values in (0, 1)) and a normal variate source `normal`.
template <class Uniform, class Normal>
double drawError(metrology::Distribution distribution, double u, Uniform& uniform, Normal& normal) {
  constexpr double kSqrt3 = 1.7320508075688772, kSqrt6 = 2.449489742783178;
  switch (distribution) {
    case metrology::Distribution::kNormal:
      return u * normal();
    case metrology::Distribution::kRectangular:
      return u * kSqrt3 * (2.0 * uniform() - 1.0);
    case metrology::Distribution::kTriangular:
      return u * kSqrt6 * (uniform() + uniform() - 1.0);
    case metrology::Distribution::kUShaped:
      return u * 1.4142135623730951 * std::sin(6.283185307179586 * uniform());
  }
  return 0.0;
}

}  // namespace pkm::calibration::detail
