// Per-target means of line-measurement readings (per_target.hpp).
#include "pkm/metrology/per_target.hpp"

#include <map>
#include <utility>

namespace pkm::metrology {

TargetMeans perTargetMeans(std::span<const TargetSample> samples) {
  std::map<double, std::pair<double, int>> sums;
  for (const TargetSample& s : samples) {
    auto& [sum, n] = sums[s.target];
    sum += s.value;
    ++n;
  }
  TargetMeans out;
  out.target.reserve(sums.size());
  out.mean.reserve(sums.size());
  for (const auto& [target, acc] : sums) {
    out.target.push_back(target);
    out.mean.push_back(acc.first / acc.second);
  }
  return out;
}

}  // namespace pkm::metrology
