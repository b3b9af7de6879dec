#include "data_errors.hpp"

namespace pkm::workflow::detail {

std::string dataNames(std::initializer_list<std::span<const io::NamedText>> groups) {
  std::string out;
  for (const std::span<const io::NamedText> g : groups)
    for (const io::NamedText& in : g) out += (out.empty() ? "" : ", ") + in.name;
  return out;
}

}  // namespace pkm::workflow::detail
