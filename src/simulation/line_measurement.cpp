#include "pkm/simulation/line_measurement.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "pkm/core/error.hpp"
#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/geometry/so3.hpp"

namespace pkm::simulation {

namespace {

constexpr double kUnitTolerance = 1e-9;

/// The instrument, set up and zeroed at the datum pose.
class LineInstrument {
 public:
  LineInstrument(const LineSetup& setup,
                 const Eigen::Vector3d& beam,
                 const geometry::RigidTransform& datum,
                 const MeasurementConditions* conditions)
      : setup_(setup),
        beam_(conditions != nullptr ? conditions->laserBeam(beam) : beam),
        datum_(datum),
        conditions_(conditions),
        offset_(conditions != nullptr ? setup.reflector_offset + conditions->reflectorOffset()
                                      : setup.reflector_offset) {
    lateral_ = setup.lateral.normalized();
    if (setup.quantity == LineQuantity::kStraightness) {
      Eigen::Vector3d l = setup.lateral - setup.lateral.dot(beam) * beam;
      PKM_CHECK(l.norm() > kUnitTolerance,
                "{}: the lateral direction is parallel to the beam",
                setup.name);
      lateral_ = (l.normalized() + setup.misalignment * beam).normalized();
    }
  }

  /// The tool's rotation at `pose` since the datum (rotation vector, rad, work frame).
  [[nodiscard]] Eigen::Vector3d rotation(const geometry::RigidTransform& pose) const {
    return geometry::so3Log(pose.linear() * datum_.linear().transpose());
  }

  /// The true (noise-free) reading at the actual pose.
  [[nodiscard]] double truth(const geometry::RigidTransform& pose, double datum_target) const {
    const Eigen::Vector3d d = pose * offset_ - datum_ * offset_;
    switch (setup_.quantity) {
      case LineQuantity::kLinear:
        return datum_target + (conditions_ != nullptr ? conditions_->laserDisplacement(beam_.dot(d))
                                                      : beam_.dot(d));
      case LineQuantity::kStraightness:
        return lateral_.dot(d);
      case LineQuantity::kAngular:
        return lateral_.dot(geometry::so3Log(pose.linear() * datum_.linear().transpose()));
    }
    return 0.0;
  }

 private:
  const LineSetup& setup_;
  Eigen::Vector3d beam_;
  geometry::RigidTransform datum_;
  const MeasurementConditions* conditions_;
  Eigen::Vector3d offset_;  // the reflector's offset from the tool point, tool frame
  Eigen::Vector3d lateral_;
};

}  // namespace

const char* toString(LineQuantity quantity) {
  switch (quantity) {
    case LineQuantity::kLinear:
      return "linear";
    case LineQuantity::kStraightness:
      return "straightness";
    case LineQuantity::kAngular:
      return "angular";
  }
  return "?";
}

const char* toString(LineProcedure procedure) {
  return procedure == LineProcedure::kContinuous ? "continuous" : "step_diagonal";
}

void PositioningCycle::validate() const {
  PKM_CHECK(std::isfinite(first) && std::isfinite(last), "cycle: targets must be finite");
  PKM_CHECK(targets >= 2, "cycle: targets {} must be at least 2", targets);
  PKM_CHECK(first < last, "cycle: the first target {} must be below the last {}", first, last);
  PKM_CHECK(runs >= 1, "cycle: runs {} must be at least 1", runs);
  PKM_CHECK(std::isfinite(overshoot) && overshoot >= 0.0, "cycle: overshoot must be >= 0");
  const double spacing = (last - first) / (targets - 1);
  PKM_CHECK(std::isfinite(target_jitter) && target_jitter >= 0.0 && target_jitter < spacing / 2,
            "cycle: target_jitter {} must be in [0, half the target spacing {})",
            target_jitter,
            spacing / 2);
}

void LineSetup::validate() const {
  PKM_CHECK(!name.empty(), "a measurement needs a name");
  PKM_CHECK(line.start.size() == line.direction.size() && line.start.allFinite() &&
                line.direction.allFinite(),
            "{}: the line start and direction must be finite and of the same size",
            name);
  cycle.validate();
  PKM_CHECK(reflector_offset.allFinite() && lateral.allFinite() && std::isfinite(misalignment),
            "{}: set-up values must be finite",
            name);
  PKM_CHECK(lateral.norm() > kUnitTolerance, "{}: the lateral direction is zero", name);
  noise.validate();
  if (procedure == LineProcedure::kStepDiagonal) {
    PKM_CHECK(
        quantity == LineQuantity::kLinear, "{}: a step-diagonal measurement must be linear", name);
    PKM_CHECK((line.direction.array() != 0.0).count() >= 2,
              "{}: a step-diagonal line must move at least two axes",
              name);
  }
}

std::vector<double> cycleTargets(const PositioningCycle& cycle, RandomStream& rng) {
  cycle.validate();
  std::vector<double> targets;
  const double spacing = (cycle.last - cycle.first) / (cycle.targets - 1);
  for (int i = 0; i < cycle.targets; ++i) {
    double t = i == cycle.targets - 1 ? cycle.last : cycle.first + i * spacing;
    if (i > 0 && i < cycle.targets - 1 && cycle.target_jitter > 0.0)
      t += rng.uniform(-cycle.target_jitter, cycle.target_jitter);
    targets.push_back(t);
  }
  return targets;
}

double rotationRange(const std::vector<LineRun>& runs) {
  std::vector<Eigen::Vector3d> w;
  for (const LineRun& r : runs)
    for (const LineReading& x : r.readings)
      if (x.sensed.recorded) w.push_back(x.sensed.rotation_rad);
  double range = 0.0;
  for (std::size_t i = 0; i < w.size(); ++i)
    for (std::size_t j = i + 1; j < w.size(); ++j) range = std::max(range, (w[i] - w[j]).norm());
  return range;
}

int readingCount(const LineSetup& setup) {
  const auto moving = static_cast<int>((setup.line.direction.array() != 0.0).count());
  const int per_target = setup.procedure == LineProcedure::kStepDiagonal ? moving : 1;
  return setup.cycle.runs * setup.cycle.targets * (setup.cycle.bidirectional ? 2 : 1) * per_target;
}

std::vector<LineRun> simulateLine(VirtualMachine& machine,
                                  const LineSetup& setup,
                                  RandomStream& rng) {
  return simulateLine(machine, setup, rng, nullptr);
}

namespace {

/// The machine's pose in the environment (thermal expansion and warm-up; unchanged without
/// `conditions`).
geometry::RigidTransform environmentPose(const MeasurementConditions* conditions,
                                         const geometry::RigidTransform& pose) {
  return conditions != nullptr ? conditions->actualPose(pose) : pose;
}

/// The runs of a line measurement (simulate's loop): the machine, the set-up, the instrument and
/// the values fixed for the line.
struct LineRunner {
  VirtualMachine& machine;
  const LineSetup& setup;
  RandomStream& rng;
  MeasurementConditions* conditions;
  const LineInstrument& instrument;      ///< zeroed at s0
  const std::vector<double>& targets;    ///< in increasing order
  const Eigen::Vector3d& beam;           ///< nominal tool travel per unit of the line
  const Eigen::Vector3d& datum_nominal;  ///< nominal tool point at s0
  double s0;                             ///< the first target, where the instrument is zeroed
  double below, above;                   ///< the overshoot positions before either direction
  double scale;                          ///< the instrument's scale error for the line
  int moving_axes;                       ///< axes the line moves

  /// Run `r` (1-based): the targets upwards, and downwards when the cycle is bidirectional.
  LineRun measureRun(int r) {
    LineRun run;
    run.run = r;
    Eigen::VectorXd at = setup.line.at(below);  // the current command
    const auto readAt = [&](double target, int direction, int sub_step) {
      if (conditions != nullptr) conditions->next();
      const geometry::RigidTransform pose = environmentPose(conditions, machine.moveTo(at));
      const double truth = instrument.truth(pose, s0);
      run.readings.push_back(
          {target, direction, setup.noise.apply(truth, target - s0, scale, rng), sub_step, {}});
      if (conditions != nullptr && setup.quantity == LineQuantity::kLinear) {
        const AirConditions air = conditions->sensedAir();
        run.readings.back().sensed = {true,
                                      air.temperature_c,
                                      air.pressure_pa,
                                      air.relative_humidity,
                                      conditions->sensedMaterialTemperature(),
                                      instrument.rotation(pose)};
      }
    };
    const auto read = [&](double s, int direction) {
      const Eigen::VectorXd goal = setup.line.at(s);
      if (setup.procedure == LineProcedure::kContinuous) {
        at = goal;
        readAt(s, direction, 0);
        return;
      }
      int sub_step = 0;
      for (Eigen::Index axis = 0; axis < goal.size(); ++axis) {
        if (setup.line.direction[axis] == 0.0) continue;
        at[axis] = goal[axis];
        ++sub_step;
        const double target =
            sub_step == moving_axes
                ? s
                : s0 + beam.dot(machine.nominalPose(at).translation() - datum_nominal);
        readAt(target, direction, sub_step);
      }
      at = goal;
    };
    machine.moveTo(at);
    for (const double s : targets) read(s, 1);
    if (setup.cycle.bidirectional) {
      at = setup.line.at(above);
      machine.moveTo(at);
      for (auto it = targets.rbegin(); it != targets.rend(); ++it) read(*it, -1);
    }
    return run;
  }
};

/// simulateLine's body; `scale_z` nullopt: the line draws its own scale error.
std::vector<LineRun> simulate(VirtualMachine& machine,
                              const LineSetup& setup,
                              RandomStream& rng,
                              MeasurementConditions* conditions,
                              std::optional<double> scale_z) {
  setup.validate();
  const std::vector<double> targets = cycleTargets(setup.cycle, rng);
  const Eigen::Vector3d beam = machine.nominalPose(setup.line.at(1.0)).translation() -
                               machine.nominalPose(setup.line.at(0.0)).translation();
  PKM_CHECK(std::abs(beam.norm() - 1.0) < kUnitTolerance,
            "{}: the nominal tool travel per unit of the line is {}, not 1",
            setup.name,
            beam.norm());
  const double s0 = targets.front();
  const double below = s0 - setup.cycle.overshoot;
  const double above = targets.back() + setup.cycle.overshoot;

  machine.reset(rng.bits());
  machine.moveTo(setup.line.at(below));
  if (conditions != nullptr) conditions->zero();
  const LineInstrument instrument(
      setup, beam, environmentPose(conditions, machine.moveTo(setup.line.at(s0))), conditions);

  const Eigen::Vector3d datum_nominal = machine.nominalPose(setup.line.at(s0)).translation();
  // The instrument's ppm accuracy (its environmental compensation) holds over the test: one scale
  // error for the line, not a draw per reading that would show as the machine's scatter.
  const double scale = scale_z ? setup.noise.scaleFor(*scale_z) : setup.noise.drawScale(rng);
  const auto moving_axes = static_cast<int>((setup.line.direction.array() != 0.0).count());
  LineRunner runner{machine,
                    setup,
                    rng,
                    conditions,
                    instrument,
                    targets,
                    beam,
                    datum_nominal,
                    s0,
                    below,
                    above,
                    scale,
                    moving_axes};
  std::vector<LineRun> runs;
  for (int r = 1; r <= setup.cycle.runs; ++r) runs.push_back(runner.measureRun(r));
  return runs;
}

}  // namespace

std::vector<LineRun> simulateLine(VirtualMachine& machine,
                                  const LineSetup& setup,
                                  RandomStream& rng,
                                  MeasurementConditions* conditions) {
  return simulate(machine, setup, rng, conditions, std::nullopt);
}

std::vector<LineRun> simulateLine(VirtualMachine& machine,
                                  const LineSetup& setup,
                                  RandomStream& rng,
                                  MeasurementConditions* conditions,
                                  double scale_z) {
  return simulate(machine, setup, rng, conditions, scale_z);
}

}  // namespace pkm::simulation
