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

}  // namespace pkm::metrology
