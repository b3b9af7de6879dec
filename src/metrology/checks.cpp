#include "pkm/metrology/checks.hpp"

#include <cmath>

#include "pkm/core/error.hpp"

namespace pkm::metrology {

void requireFinite(std::span<const double> values, std::string_view what) {
  for (std::size_t i = 0; i < values.size(); ++i) {
    PKM_CHECK(
        std::isfinite(values[i]), "{}: value {} of {} is not finite", what, i + 1, values.size());
  }
}

void requireCount(std::size_t count, std::size_t minimum, std::string_view what) {
  PKM_CHECK(count >= minimum, "{}: needs at least {} points, got {}", what, minimum, count);
}

const char* levenbergMarquardtSettingsProblem(int max_iterations,
                                              double step_tolerance,
                                              double cost_tolerance) {
  if (max_iterations < 1) return "max_iterations must be >= 1";
  if (!(step_tolerance > 0.0 && step_tolerance < 1.0)) return "step_tolerance must be in (0, 1)";
  if (!(cost_tolerance > 0.0 && cost_tolerance < 1.0)) return "cost_tolerance must be in (0, 1)";
  return nullptr;
}

}  // namespace pkm::metrology
