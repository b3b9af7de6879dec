#include "pkm/core/units.hpp"

namespace pkm {

std::string_view toString(LengthUnit unit) { return unit == LengthUnit::kInch ? "inch" : "mm"; }

std::optional<LengthUnit> lengthUnitFromString(std::string_view text) {
  if (text == "mm") return LengthUnit::kMillimetre;
  if (text == "inch" || text == "in") return LengthUnit::kInch;
  return std::nullopt;
}

}  // namespace pkm
