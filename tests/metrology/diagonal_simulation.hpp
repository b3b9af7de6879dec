/// @file
/// @brief Test helpers for the diagonal methods: a Cartesian virtual machine with injected scale
/// and squareness errors, and noise-free (or noisy) laser readings along lines through it.
#pragma once

#include <string>
#include <vector>

#include "pkm/geometry/error_table.hpp"
#include "pkm/simulation/cartesian_machine.hpp"
#include "pkm/simulation/line_measurement.hpp"
#include "pkm/simulation/random.hpp"

namespace pkm::test {

/// Scale errors (ratio) and squareness (rad, project convention) injected into a Cartesian machine.
struct InjectedErrors {
  Eigen::Vector3d scale = Eigen::Vector3d::Zero();
  simulation::CartesianSquareness squareness;
};

/// A machine whose axes have positioning errors EXX = kx·x (etc.) over [−range, range] and the
/// given squareness; no other errors, no Abbe offsets.
inline simulation::CartesianMachine diagonalTestMachine(const InjectedErrors& injected,
                                                        double range = 2000.0) {
  simulation::CartesianErrors errors;
  for (int k = 0; k < 3; ++k) {
    geometry::ErrorMotion lo = geometry::ErrorMotion::Zero(), hi = geometry::ErrorMotion::Zero();
    lo[k] = -injected.scale[k] * range;
    hi[k] = injected.scale[k] * range;
    errors.axes[static_cast<std::size_t>(k)] =
        geometry::ErrorTable1d::fromErrorMotions({-range, range}, {lo, hi});
  }
  errors.squareness = injected.squareness;
  return simulation::CartesianMachine({}, errors);
}

/// Runs a linear (or step-diagonal) measurement from `from` to `to` with `targets` uniform targets
/// and `runs` bidirectional runs.
inline std::vector<simulation::LineRun> measureLine(
    simulation::VirtualMachine& machine,
    const Eigen::Vector3d& from,
    const Eigen::Vector3d& to,
    int targets,
    int runs,
    simulation::LineProcedure procedure = simulation::LineProcedure::kContinuous,
    simulation::NoiseModel noise = {},
    unsigned seed = 1) {
  simulation::LineSetup setup;
  setup.name = "line";
  setup.procedure = procedure;
  const double length = (to - from).norm();
  setup.line.start = from;
  setup.line.direction = (to - from) / length;
  setup.cycle.first = 0.0;
  setup.cycle.last = length;
  setup.cycle.targets = targets;
  setup.cycle.runs = runs;
  setup.cycle.overshoot = 2.0;
  setup.noise = noise;
  simulation::RandomStream rng(seed);
  return simulation::simulateLine(machine, setup, rng);
}

}  // namespace pkm::test
