#include "pkm/cnc/parameters.hpp"

#include <fmt/format.h>

#include "pkm/cnc/gcode_error.hpp"

namespace pkm::cnc {

bool isLengthParameter(int index) {
  // Each block is X Y Z A B C U V W: X Y Z and U V W are lengths.
  auto inBlock = [index](int base) {
    const int k = index - base;
    return (k >= 0 && k <= 2) || (k >= 6 && k <= 8);
  };
  if (inBlock(5061) || inBlock(5161) || inBlock(5181) || inBlock(kG92Base) || inBlock(5401))
    return true;
  for (int n = 1; n <= 9; ++n)
    if (inBlock(coordinateSystemBase(n))) return true;
  return false;
}

Parameters::Parameters() : numbered_(static_cast<std::size_t>(kParameterCount), 0.0) {
  locals_.emplace_back();
  set(kActiveSystemParam, 1.0);
}

bool Parameters::exists(const std::string& name) const {
  if (!name.empty() && name[0] == '_') return globals_.count(name) != 0;
  return locals_.back().count(name) != 0;
}

double Parameters::named(const std::string& name) const {
  const auto& scope = (!name.empty() && name[0] == '_') ? globals_ : locals_.back();
  const auto it = scope.find(name);
  if (it == scope.end()) throw GcodeError(fmt::format("named parameter #<{}> not defined", name));
  return it->second;
}

void Parameters::setNamed(const std::string& name, double value) {
  if (!name.empty() && name[0] == '_')
    globals_[name] = value;
  else
    locals_.back()[name] = value;
}

void Parameters::pushCall(const std::vector<double>& args) {
  std::array<double, 30> saved{};
  for (std::size_t i = 0; i < saved.size(); ++i) {
    saved[i] = numbered_[i + 1];
    numbered_[i + 1] = i < args.size() ? args[i] : 0.0;
  }
  saved_.push_back(saved);
  locals_.emplace_back();
}

void Parameters::popCall() {
  if (saved_.empty()) return;
  const std::array<double, 30>& saved = saved_.back();
  for (std::size_t i = 0; i < saved.size(); ++i) numbered_[i + 1] = saved[i];
  saved_.pop_back();
  locals_.pop_back();
}

}  // namespace pkm::cnc
