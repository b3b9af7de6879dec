#include "pkm/core/error.hpp"

namespace pkm {

std::string locate(const std::string& file, std::size_t line, const std::string& what) {
  if (line == 0) return fmt::format("{}: {}", file, what);
  return fmt::format("{}:{}: {}", file, line, what);
}

}  // namespace pkm
