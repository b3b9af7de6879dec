/// @file
/// @brief Tables the library writes as text (a simulation's measurement files, the moves CSV of
/// `pkm gcode moves`) as numpy columns: read by io::TextTable, the reader of `pkm analyze`, so the
/// arrays hold exactly the printed values (shortest round-trip numbers).
#pragma once

#include <string>

#include "common.hpp"
#include "pkm/io/text_table.hpp"

namespace pkm::python {

/// Column `col` of `table` as a numpy array: float64 when every field is a number or empty
/// (empty: NaN), else an array of strings ('<U…'). Called with the GIL held.
[[nodiscard]] py::array columnOf(const io::TextTable& table, std::size_t col);

/// Every column of `table`, {header name: columnOf}, in file order.
[[nodiscard]] py::dict columnsOf(const io::TextTable& table);

/// The "# key: value" lines of `table` as {key: value} (str), in file order.
[[nodiscard]] py::dict metadataOf(const io::TextTable& table);

}  // namespace pkm::python
