#include "pkm/io/line_numbers.hpp"

#include <algorithm>
#include <cassert>

namespace pkm::io {

void LineNumbers::append(const LineNumbers& other, std::size_t line_offset) {
  for (std::size_t i = 0; i < other.runs_.size(); ++i) {
    const Run& run = other.runs_[i];
    const std::size_t rows =
        (i + 1 < other.runs_.size() ? other.runs_[i + 1].first_row : other.size_) - run.first_row;
    add(run.first_line + line_offset);  // joins the previous run when it continues it
    size_ += rows - 1;
  }
}

std::size_t LineNumbers::operator[](std::size_t row) const {
  assert(row < size_);
  // The last run that starts at or before `row`.
  const auto it =
      std::upper_bound(runs_.begin(), runs_.end(), row, [](std::size_t r, const Run& run) {
        return r < run.first_row;
      });
  const Run& run = *(it - 1);
  return run.first_line + (row - run.first_row);
}

}  // namespace pkm::io
