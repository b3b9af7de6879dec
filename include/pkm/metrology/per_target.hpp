/// @file
/// @brief The per-target mean of line-measurement readings: what a straightness profile, a mean
/// positioning deviation or a diagonal's length error is computed from when the readings of
/// several runs and both approach directions are averaged at each target position (ISO 230-2:2014
/// mean bidirectional deviation; the MXT700S parallelism paper averages the runs of each line the
/// same way).
#pragma once

#include <span>
#include <vector>

namespace pkm::metrology {

/// One reading at a target position (any unit; the caller has removed intermediate readings such
/// as the sub-steps of a step-diagonal run, which are not readings at the target).
struct TargetSample {
  double target = 0.0;
  double value = 0.0;
};

/// Targets in increasing order and the mean of the values read at each.
struct TargetMeans {
  std::vector<double> target;
  std::vector<double> mean;
};

/// Groups `samples` by exactly equal target and averages each group, summing in input order.
/// Empty input gives empty output.
[[nodiscard]] TargetMeans perTargetMeans(std::span<const TargetSample> samples);

}  // namespace pkm::metrology
