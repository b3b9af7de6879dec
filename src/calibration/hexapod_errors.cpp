// The measured coordinates that the error sources of a hexapod calibration act on
// (detail/hexapod_errors.hpp).
#include "detail/hexapod_errors.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "detail/contributor.hpp"
#include "pkm/geometry/so3.hpp"
#include "pkm/kinematics/pose_rpy.hpp"

namespace pkm::calibration::detail {
namespace {

using metrology::Distribution;
using metrology::UncertaintyContributor;

constexpr double kSqrt3 = 1.7320508075688772;

/// The tracker's a + b·L on every pose and point position (3 coordinates each).
CoordinateSource trackerSource(const HexapodCalibrationData& data,
                               const metrology::LaserTrackerSpec& t,
                               LengthUnit unit) {
  const double per_mm = 1.0 / millimetresPer(unit);
  const bool tracker_frame = data.measurement_frame.has_value();
  // Range in mm of a reading: its distance from the tracker (readings in the tracker frame) or
  // the stated typical range.
  const auto range_mm = [&](const Eigen::Vector3d& y) {
    return tracker_frame ? y.norm() / per_mm : t.range_mm;
  };
  const auto half_width = [&](double L_mm) {
    return (t.accuracy_mm + t.accuracy_mm_per_m * L_mm * 1e-3) * per_mm;
  };
  CoordinateSource s;
  double longest = 0.0;
  std::vector<std::pair<ObservationRef, double>> items;
  for (const ObservationRef& ref : observations(data)) {
    if (ref.kind == ObservationRef::Kind::kPose)
      items.emplace_back(ref, range_mm(data.poses[ref.index].pose.position));
    else if (ref.kind == ObservationRef::Kind::kPoint)
      items.emplace_back(ref, range_mm(data.points[ref.index].point));
    else
      continue;
    longest = std::max(longest, items.back().second);
  }
  for (const auto& [ref, L] : items)
    for (int c = 0; c < 3; ++c) s.coordinates.push_back({ref, c, half_width(L) / kSqrt3});
  s.contributor = makeContributor(
      fmt::format("{} (±(a + b·L), L = {:.0f} mm)", t.name, longest),
      half_width(longest),
      std::string(toString(unit)),
      Distribution::kRectangular,
      fmt::format("specification a = {:g} mm, b = {:g} mm/m, per coordinate of each reading, "
                  "L the {} range",
                  t.accuracy_mm,
                  t.accuracy_mm_per_m,
                  tracker_frame ? "measured" : "stated typical"));
  return s;
}

void add(std::vector<CoordinateSource>& out, CoordinateSource s) {
  if (!s.coordinates.empty() && s.contributor.value > 0.0) out.push_back(std::move(s));
}

/// The machine's strut readings as inputs: encoder resolution (rectangular ±res/2), repeatability
/// (normal) and backlash (U-shaped ±b/2, independent per reading) unless the fit estimates it.
void addActuatorSources(std::vector<CoordinateSource>& out,
                        const HexapodCalibrationData& data,
                        const metrology::ActuatorReadings& a,
                        LengthUnit unit,
                        bool backlash_estimated) {
  const double per_mm = 1.0 / millimetresPer(unit);
  const std::string u(toString(unit));
  const std::vector<MeasuredCoordinate> readings = strutReadings(data);
  const auto with = [&](double sd) {
    std::vector<MeasuredCoordinate> c = readings;
    for (MeasuredCoordinate& m : c) m.u = sd;
    return c;
  };
  const double half_count = 0.5 * a.resolution_mm * per_mm;
  add(out,
      {makeContributor(fmt::format("{} resolution", a.name),
                       half_count,
                       u,
                       Distribution::kRectangular,
                       "half an encoder count, per strut reading"),
       with(half_count / kSqrt3)});
  const double repeat = a.repeatability_mm * per_mm;
  add(out,
      {makeContributor(fmt::format("{} repeatability", a.name),
                       repeat,
                       u,
                       Distribution::kNormal,
                       "one standard deviation, per strut reading"),
       with(repeat)});
  if (backlash_estimated) return;
  // Lost motion depends on the approach direction, unknown per reading. A constrained-motion
  // set's reference is the datum of every station and is reached in one move, in which the six
  // struts take up their lost motion together: there it also acts as one shift of all six
  // (coordinate 18), the coherent case the independent terms would average away.
  const double half_lost = 0.5 * a.backlash_mm * per_mm;
  std::vector<MeasuredCoordinate> lost = with(half_lost / std::sqrt(2.0));
  for (std::size_t s = 0; s < data.constrained.size(); ++s)
    if (!data.constrained[s].stations.empty())
      lost.push_back({{ObservationRef::Kind::kGauge, 0, s}, 18, half_lost / std::sqrt(2.0)});
  add(out,
      {makeContributor(
           fmt::format("{} backlash", a.name),
           half_lost,
           u,
           Distribution::kUShaped,
           "half the lost motion at a reversal, per strut reading, and at a gauge set's "
           "reference for its six struts together"),
       lost});
}

/// The distance instrument: the laser's resolution and wavelength accuracy over each distance.
CoordinateSource distanceSource(const HexapodCalibrationData& data,
                                const std::vector<ObservationRef>& refs,
                                const metrology::LaserInterferometer& laser,
                                LengthUnit unit) {
  const double per_mm = 1.0 / millimetresPer(unit);
  std::vector<MeasuredCoordinate> distances;
  double longest = 0.0;
  for (const ObservationRef& ref : refs)
    if (ref.kind == ObservationRef::Kind::kDistance) {
      const double d = data.distances[ref.index].distance;
      const double a =
          0.5 * laser.resolution_mm * per_mm + laser.wavelength_accuracy_ppm * 1e-6 * d;
      distances.push_back({ref, 0, a / kSqrt3});
      longest = std::max(longest, a);
    }
  return {makeContributor("distance instrument (laser resolution and wavelength)",
                          longest,
                          std::string(toString(unit)),
                          Distribution::kRectangular,
                          "±(res/2 + wavelength accuracy × d) per distance; value at the longest"),
          distances};
}

}  // namespace

std::vector<MeasuredCoordinate> strutReadings(const HexapodCalibrationData& data) {
  std::vector<MeasuredCoordinate> c;
  for (const ObservationRef& ref : observations(data)) {
    const bool two_ends = ref.kind == ObservationRef::Kind::kDistance &&
                          data.distances[ref.index].readings_from.has_value();
    for (int k = 6; k < 12; ++k) c.push_back({ref, k, 1.0});
    if (two_ends)
      for (int k = 12; k < 18; ++k) c.push_back({ref, k, 1.0});
  }
  for (std::size_t s = 0; s < data.constrained.size(); ++s)
    if (!data.constrained[s].stations.empty())
      for (int k = 12; k < 18; ++k) c.push_back({{ObservationRef::Kind::kGauge, 0, s}, k, 1.0});
  return c;
}

bool actsOnWholeSet(const MeasuredCoordinate& c) {
  return c.ref.kind == ObservationRef::Kind::kGauge &&
         ((c.coordinate >= 3 && c.coordinate < 6) || c.coordinate >= 12);
}

std::vector<CoordinateSource> hexapodCoordinateSources(const HexapodCalibrationData& data,
                                                       const metrology::UncertaintySources& sources,
                                                       const kinematics::HexapodModel& model,
                                                       bool backlash_estimated) {
  const LengthUnit unit = model.unit;
  const double per_mm = 1.0 / millimetresPer(unit);
  const std::string u(toString(unit));
  std::vector<CoordinateSource> out;
  add(out, trackerSource(data, sources.tracker, unit));
  const std::vector<ObservationRef> refs = observations(data);
  const auto every = [&](ObservationRef::Kind kind, std::initializer_list<int> coords, double sd) {
    std::vector<MeasuredCoordinate> c;
    for (const ObservationRef& ref : refs)
      if (ref.kind == kind)
        for (const int k : coords) c.push_back({ref, k, sd});
    return c;
  };
  const double angle = sources.tracker.orientation_accuracy_rad;
  add(out,
      {makeContributor("6-DOF probe orientation",
                       angle,
                       "rad",
                       Distribution::kRectangular,
                       "tracker specification, per rotation axis of each pose reading"),
       every(ObservationRef::Kind::kPose, {3, 4, 5}, angle / kSqrt3)});
  // Every gauge reading (station and reference) has its own error.
  const double gauge = sources.dial_gauge.accuracy_mm * per_mm;
  const double resolution = 0.5 * sources.dial_gauge.resolution_mm * per_mm;
  std::vector<MeasuredCoordinate> gauges = every(ObservationRef::Kind::kGauge, {0, 1, 2}, 1.0);
  for (std::size_t s = 0; s < data.constrained.size(); ++s)
    if (!data.constrained[s].stations.empty())
      for (int k = 3; k < 6; ++k) gauges.push_back({{ObservationRef::Kind::kGauge, 0, s}, k, 1.0});
  for (MeasuredCoordinate& c : gauges) c.u = gauge / kSqrt3;
  add(out,
      {makeContributor(fmt::format("{} accuracy", sources.dial_gauge.name),
                       gauge,
                       u,
                       Distribution::kRectangular,
                       "maximum permissible error, per gauge reading (stations and reference)"),
       gauges});
  for (MeasuredCoordinate& c : gauges) c.u = resolution / kSqrt3;
  add(out,
      {makeContributor(fmt::format("{} resolution", sources.dial_gauge.name),
                       resolution,
                       u,
                       Distribution::kRectangular,
                       "half the display resolution, per gauge reading"),
       gauges});
  add(out, distanceSource(data, refs, sources.laser, unit));
  const double setup = sources.environment.setup_repeatability_mm * per_mm;
  std::vector<MeasuredCoordinate> positions = every(ObservationRef::Kind::kPose, {0, 1, 2}, setup);
  const std::vector<MeasuredCoordinate> points =
      every(ObservationRef::Kind::kPoint, {0, 1, 2}, setup);
  positions.insert(positions.end(), points.begin(), points.end());
  add(out,
      {makeContributor(
           "set-up repeatability",
           setup,
           u,
           Distribution::kNormal,
           "environment.setup_repeatability_mm, per coordinate of each tracker reading"),
       positions});
  addActuatorSources(out, data, sources.actuators, unit, backlash_estimated);
  addLeadSources(out, data, sources.actuators, unit, homeReadings(model));
  addWeightSource(out, data, sources.hexapod_platform, model);
  return out;
}

std::vector<MeasuredCoordinate> residualCoordinates(const HexapodCalibrationData& data,
                                                    double sigma) {
  std::vector<MeasuredCoordinate> out;
  for (const ObservationRef& ref : observations(data)) {
    switch (ref.kind) {
      case ObservationRef::Kind::kPose:
        for (int k = 6; k < 12; ++k) out.push_back({ref, k, sigma});
        break;
      case ObservationRef::Kind::kPoint:
      case ObservationRef::Kind::kGauge:
        for (int k = 0; k < 3; ++k) out.push_back({ref, k, sigma});
        break;
      case ObservationRef::Kind::kDistance:
        out.push_back({ref, 0, sigma});
        break;
    }
  }
  return out;
}

void perturbMeasurement(HexapodCalibrationData& data, const MeasuredCoordinate& c, double delta) {
  const std::size_t i = c.ref.index;
  switch (c.ref.kind) {
    case ObservationRef::Kind::kPose: {
      kinematics::PoseRpy& pose = data.poses[i].pose;
      if (c.coordinate < 3) {
        pose.position(c.coordinate) += delta;
      } else if (c.coordinate < 6) {
        const Eigen::Vector3d w = delta * Eigen::Vector3d::Unit(c.coordinate - 3);
        pose.rpy = geometry::rpyFromRotation(
            geometry::so3Exp(w) * geometry::rotationFromRpy(pose.rpy), pose.rpy);
      } else {
        data.poses[i].readings(c.coordinate - 6) += delta;
      }
      return;
    }
    case ObservationRef::Kind::kPoint:
      if (c.coordinate < 3)
        data.points[i].point(c.coordinate) += delta;
      else
        data.points[i].readings(c.coordinate - 6) += delta;
      return;
    case ObservationRef::Kind::kGauge: {
      ConstrainedMotionData& set = data.constrained[c.ref.set];
      if (c.coordinate < 3)
        set.stations[i].gauges[static_cast<std::size_t>(c.coordinate)] += delta;
      else if (c.coordinate < 6)
        set.reference.gauges[static_cast<std::size_t>(c.coordinate - 3)] += delta;
      else if (c.coordinate < 12)
        set.stations[i].readings(c.coordinate - 6) += delta;
      else if (c.coordinate < 18)
        set.reference.readings(c.coordinate - 12) += delta;
      else
        set.reference.readings.array() += delta;
      return;
    }
    case ObservationRef::Kind::kDistance:
      if (c.coordinate == 0)
        data.distances[i].distance += delta;
      else if (c.coordinate < 12)
        data.distances[i].readings(c.coordinate - 6) += delta;
      else
        (*data.distances[i].readings_from)(c.coordinate - 12) += delta;
      return;
  }
}

void restoreMeasurement(HexapodCalibrationData& data,
                        const HexapodCalibrationData& original,
                        const MeasuredCoordinate& c) {
  const std::size_t i = c.ref.index;
  switch (c.ref.kind) {
    case ObservationRef::Kind::kPose:
      data.poses[i] = original.poses[i];
      return;
    case ObservationRef::Kind::kPoint:
      data.points[i] = original.points[i];
      return;
    case ObservationRef::Kind::kGauge: {
      ConstrainedMotionData& set = data.constrained[c.ref.set];
      const ConstrainedMotionData& from = original.constrained[c.ref.set];
      set.reference = from.reference;
      if (i < set.stations.size()) set.stations[i] = from.stations[i];
      return;
    }
    case ObservationRef::Kind::kDistance:
      data.distances[i] = original.distances[i];
      return;
  }
}

}  // namespace pkm::calibration::detail
