/// @file
/// @brief Input checks shared by the metrology evaluations: every evaluation validates its samples
/// with these before computing, so bad data (too few points, NaN) fails with a clear message.
#pragma once

#include <cstddef>
#include <span>
#include <string_view>

namespace pkm::metrology {

/// Throws pkm::InvalidArgument "<what>: <i>-th value is not finite" for the first NaN or infinity.
void requireFinite(std::span<const double> values, std::string_view what);

/// Throws pkm::InvalidArgument "<what>: needs at least <minimum> points, got <count>" when
/// count < minimum.
void requireCount(std::size_t count, std::size_t minimum, std::string_view what);

/// The stopping settings of a Levenberg–Marquardt fit (circle, probe offset): nullptr when usable
/// (max_iterations >= 1, both tolerances in (0, 1)), else the reason.
[[nodiscard]] const char* levenbergMarquardtSettingsProblem(int max_iterations,
                                                            double step_tolerance,
                                                            double cost_tolerance);

}  // namespace pkm::metrology
