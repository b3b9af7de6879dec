// Measurement tables from Python (tables.hpp).
#include "tables.hpp"

#include <fmt/format.h>
#include <pybind11/stl.h>

#include <cmath>

#include "pkm/core/error.hpp"
#include "pkm/io/number_format.hpp"

namespace pkm::python {
namespace {

bool isPath(py::handle obj) {
  return py::isinstance<py::str>(obj) || py::hasattr(obj, "__fspath__");
}

/// A column's fields as text: numbers in round-trip form, or strings without separators.
std::vector<std::string> fieldsOf(py::handle values, const std::string& where) {
  std::vector<std::string> fields;
  const py::array probe = py::array::ensure(values);
  if (probe && probe.dtype().kind() != 'U' && probe.dtype().kind() != 'O' &&
      probe.dtype().kind() != 'S') {
    const DoubleArray a = DoubleArray::ensure(values);
    if (!a || a.ndim() != 1) throw InvalidArgument(fmt::format("{}: expected a 1-D column", where));
    for (py::ssize_t i = 0; i < a.shape(0); ++i) {
      const double v = a.data()[i];
      if (!std::isfinite(v))
        throw InvalidArgument(fmt::format("{}: row {} is not a finite number ({})", where, i, v));
      std::string s;
      io::appendNumber(s, v);
      fields.push_back(std::move(s));
    }
    return fields;
  }
  for (py::handle item : values) {
    std::string s = py::str(item);
    if (s.find_first_of(",\n\r\"") != std::string::npos)
      throw InvalidArgument(fmt::format("{}: '{}' holds a comma, quote or newline", where, s));
    fields.push_back(std::move(s));
  }
  return fields;
}

}  // namespace

io::NamedText tableOf(py::handle obj,
                      const std::string& name,
                      const std::vector<std::string>& columns) {
  if (isPath(obj)) {
    return io::readNamedText(py::str(py::module_::import("os").attr("fspath")(obj)));
  }
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> fields;
  if (py::isinstance<py::dict>(obj)) {
    for (auto [key, values] : py::reinterpret_borrow<py::dict>(obj)) {
      header.push_back(py::str(key));
      fields.push_back(fieldsOf(values, fmt::format("{}: column '{}'", name, header.back())));
    }
  } else {
    if (columns.empty())
      throw InvalidArgument(fmt::format("{}: give a dict of named columns or a file path", name));
    const DoubleArray a =
        rowsOf(obj, static_cast<py::ssize_t>(columns.size()), name.c_str(), false);
    header = columns;
    fields.resize(columns.size());
    for (py::ssize_t i = 0; i < a.shape(0); ++i)
      for (std::size_t k = 0; k < columns.size(); ++k)
        io::appendNumber(fields[k].emplace_back(), a.data()[i * a.shape(1) + k]);
  }
  if (header.empty()) throw InvalidArgument(fmt::format("{}: no columns", name));
  for (std::size_t k = 1; k < fields.size(); ++k)
    if (fields[k].size() != fields[0].size())
      throw InvalidArgument(fmt::format("{}: column '{}' has {} rows, column '{}' {}",
                                        name,
                                        header[k],
                                        fields[k].size(),
                                        header[0],
                                        fields[0].size()));
  io::NamedText t{name, {}};
  for (std::size_t k = 0; k < header.size(); ++k) t.text += (k ? "," : "") + header[k];
  t.text += '\n';
  for (std::size_t i = 0; i < fields[0].size(); ++i) {
    for (std::size_t k = 0; k < header.size(); ++k) t.text += (k ? "," : "") + fields[k][i];
    t.text += '\n';
  }
  return t;
}

std::vector<io::NamedText> tablesOf(py::handle obj,
                                    const std::string& name,
                                    const std::vector<std::string>& columns) {
  const bool list = py::isinstance<py::list>(obj) || py::isinstance<py::tuple>(obj);
  if (list && py::len(obj) > 0) {
    const py::handle first = obj.begin()->ptr();
    const bool of_tables =
        py::isinstance<py::dict>(first) || isPath(first) ||
        (py::isinstance<py::array>(first) && py::reinterpret_borrow<py::array>(first).ndim() == 2);
    if (of_tables) {
      std::vector<io::NamedText> out;
      std::size_t i = 0;
      for (py::handle item : obj)
        out.push_back(tableOf(item, fmt::format("{}[{}]", name, i++), columns));
      return out;
    }
  }
  return {tableOf(obj, name, columns)};
}

}  // namespace pkm::python
