#include "pkm/io/analysis_report.hpp"

#include <algorithm>
#include <cassert>
#include <iterator>
#include <utility>

namespace pkm::io {

void PointSources::beginInput(std::string name) {
  names_.push_back(std::move(name));
  first_.push_back(lines_.size());
}

void PointSources::addLine(std::size_t line) {
  assert(!names_.empty());
  lines_.add(line);
}

void PointSources::addLines(const LineNumbers& lines) {
  assert(!names_.empty());
  lines_.append(lines);
}

PointSource PointSources::operator[](std::size_t i) const {
  assert(i < lines_.size());
  // The last input whose first point is at or before i.
  const auto it = std::upper_bound(first_.begin(), first_.end(), i);
  const auto input = static_cast<std::size_t>(std::distance(first_.begin(), it)) - 1;
  return {names_[input], lines_[i]};
}

}  // namespace pkm::io
