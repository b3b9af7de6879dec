/// @file
/// @brief The file line of each row of a table, stored as runs of consecutive lines: a file
/// without blank or comment lines between its rows costs a few bytes, not 4 or 8 a row.
#pragma once

#include <cstddef>
#include <vector>

namespace pkm::io {

/// Line numbers of rows 0, 1, 2, ... in the order they were added.
class LineNumbers {
 public:
  /// Appends the next row's 1-based line.
  void add(std::size_t line) {
    if (runs_.empty() || runs_.back().first_line + (size_ - runs_.back().first_row) != line)
      runs_.push_back({size_, line});
    ++size_;
  }
  /// Appends every row of `other`, in order, its lines shifted by `line_offset`.
  void append(const LineNumbers& other, std::size_t line_offset = 0);
  /// Number of rows.
  [[nodiscard]] std::size_t size() const { return size_; }
  /// The line of row `row`. Precondition: row < size().
  [[nodiscard]] std::size_t operator[](std::size_t row) const;

 private:
  struct Run {
    std::size_t first_row = 0;   ///< the run's first row
    std::size_t first_line = 0;  ///< its line; row first_row + i is on line first_line + i
  };
  std::vector<Run> runs_;
  std::size_t size_ = 0;
};

}  // namespace pkm::io
