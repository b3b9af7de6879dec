// Text tables as numpy columns (columns.hpp).
#include "columns.hpp"

#include <limits>
#include <string_view>
#include <vector>

#include "pkm/core/error.hpp"

namespace pkm::python {

py::array columnOf(const io::TextTable& table, std::size_t col) {
  const std::size_t n = table.rows();
  py::array_t<double> numbers = newArray(static_cast<py::ssize_t>(n));
  double* out = numbers.mutable_data();
  bool numeric = true;
  for (std::size_t r = 0; r < n && numeric; ++r) {
    if (table.text(r, col).empty()) {
      out[r] = std::numeric_limits<double>::quiet_NaN();
      continue;
    }
    try {
      out[r] = table.number(r, col);
    } catch (const IoError&) {
      numeric = false;  // a text column (a direction, a move kind, a name)
    }
  }
  if (numeric) return std::move(numbers);
  std::vector<std::string_view> words(n);
  bool ascii = true;
  for (std::size_t r = 0; r < n; ++r) {
    words[r] = table.text(r, col);
    for (const char ch : words[r]) ascii = ascii && static_cast<unsigned char>(ch) < 0x80;
  }
  if (ascii) return statusArray(words);  // filled in C++
  py::list decoded;                      // UTF-8 text: decoded by Python
  for (std::string_view w : words) decoded.append(py::str(w.data(), w.size()));
  return py::module_::import("numpy").attr("array")(decoded, "str");
}

py::dict columnsOf(const io::TextTable& table) {
  py::dict out;
  for (std::size_t c = 0; c < table.header().size(); ++c)
    out[py::str(table.header()[c])] = columnOf(table, c);
  return out;
}

py::dict metadataOf(const io::TextTable& table) {
  py::dict out;
  for (const auto& [key, value] : table.metadata()) out[py::str(key)] = py::str(value);
  return out;
}

}  // namespace pkm::python
