// The measured coordinates the budgets perturb (detail/hexapod_errors.hpp): a perturbation and
// its restoration leave the data exactly as they were, for every kind of observation.
#include "calibration/detail/hexapod_errors.hpp"

#include <gtest/gtest.h>

namespace pkm::calibration::detail {
namespace PKM_TEST_NS {

/// One observation of each kind, with distinct values everywhere.
HexapodCalibrationData everyKind() {
  HexapodCalibrationData data;
  PoseObservation pose;
  pose.readings << 101, 102, 103, 104, 105, 106;
  pose.pose.position = Eigen::Vector3d(10, -20, 200);
  pose.pose.rpy = Eigen::Vector3d(0.01, -0.02, 0.3);
  data.poses = {pose, pose};
  data.poses[1].pose.position.x() = 11.0;
  PointObservation point;
  point.readings << 201, 202, 203, 204, 205, 206;
  point.point = Eigen::Vector3d(-5, 6, 180);
  data.points = {point};
  ConstrainedMotionData set;
  set.reference.readings << 301, 302, 303, 304, 305, 306;
  set.reference.gauges = {0.1, 0.2, 0.3};
  GaugeStation station;
  station.readings << 311, 312, 313, 314, 315, 316;
  station.gauges = {0.4, 0.5, 0.6};
  set.stations = {station, station};
  data.constrained = {set};
  DistanceObservation distance;
  distance.readings << 401, 402, 403, 404, 405, 406;
  distance.readings_from = kinematics::StrutVector::Constant(410.0);
  distance.distance = 250.0;
  data.distances = {distance};
  return data;
}

/// Bitwise equality of the measured values of two data sets of the same shape.
void expectSame(const HexapodCalibrationData& a, const HexapodCalibrationData& b) {
  for (std::size_t i = 0; i < a.poses.size(); ++i) {
    EXPECT_EQ(a.poses[i].readings, b.poses[i].readings);
    EXPECT_EQ(a.poses[i].pose.position, b.poses[i].pose.position);
    EXPECT_EQ(a.poses[i].pose.rpy, b.poses[i].pose.rpy);
  }
  EXPECT_EQ(a.points[0].readings, b.points[0].readings);
  EXPECT_EQ(a.points[0].point, b.points[0].point);
  const ConstrainedMotionData &s = a.constrained[0], &t = b.constrained[0];
  EXPECT_EQ(s.reference.readings, t.reference.readings);
  EXPECT_EQ(s.reference.gauges, t.reference.gauges);
  for (std::size_t i = 0; i < s.stations.size(); ++i) {
    EXPECT_EQ(s.stations[i].readings, t.stations[i].readings);
    EXPECT_EQ(s.stations[i].gauges, t.stations[i].gauges);
  }
  EXPECT_EQ(a.distances[0].readings, b.distances[0].readings);
  EXPECT_EQ(*a.distances[0].readings_from, *b.distances[0].readings_from);
  EXPECT_EQ(a.distances[0].distance, b.distances[0].distance);
}

TEST(RestoreMeasurement, UndoesEveryPerturbationExactly) {
  const HexapodCalibrationData original = everyKind();
  using Kind = ObservationRef::Kind;
  const std::vector<MeasuredCoordinate> coordinates = {{{Kind::kPose, 1, 0}, 0},
                                                       {{Kind::kPose, 1, 0}, 4},
                                                       {{Kind::kPose, 0, 0}, 9},
                                                       {{Kind::kPoint, 0, 0}, 2},
                                                       {{Kind::kPoint, 0, 0}, 7},
                                                       {{Kind::kGauge, 1, 0}, 1},
                                                       {{Kind::kGauge, 0, 0}, 5},
                                                       {{Kind::kGauge, 1, 0}, 8},
                                                       {{Kind::kGauge, 0, 0}, 14},
                                                       {{Kind::kGauge, 0, 0}, 18},
                                                       {{Kind::kDistance, 0, 0}, 0},
                                                       {{Kind::kDistance, 0, 0}, 6},
                                                       {{Kind::kDistance, 0, 0}, 13}};
  HexapodCalibrationData d = original;
  for (const MeasuredCoordinate& c : coordinates) {
    for (const double delta : {1e-3, -1e-6}) {
      perturbMeasurement(d, c, delta);
      restoreMeasurement(d, original, c);
      expectSame(d, original);
    }
  }
}

TEST(RestoreMeasurement, LeavesTheOtherObservationsAsTheyAre) {
  // Only the perturbed coordinate's observation is copied back: a change elsewhere stays.
  const HexapodCalibrationData original = everyKind();
  HexapodCalibrationData d = original;
  d.poses[0].readings(0) = 0.0;
  const MeasuredCoordinate c{{ObservationRef::Kind::kPose, 1, 0}, 2};
  perturbMeasurement(d, c, 0.5);
  restoreMeasurement(d, original, c);
  EXPECT_EQ(d.poses[1].pose.position, original.poses[1].pose.position);
  EXPECT_EQ(d.poses[0].readings(0), 0.0);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::calibration::detail
