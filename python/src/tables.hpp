/// @file
/// @brief Measurement tables from Python for the workflows that read tables (io::NamedText):
/// a dict of columns, an (N, k) array with the kind's columns, or a file path. Numbers are written
/// in pkm's round-trip form (io::appendNumber), so the workflow reads exactly the array's values
/// through the same reader as the command line.
#pragma once

#include <string>
#include <vector>

#include "common.hpp"
#include "pkm/io/named_text.hpp"

namespace pkm::python {

/// One table: a dict {column: 1-D numbers or strings}, an (N, columns.size()) array with
/// `columns` as its header, or a str/os.PathLike read as a file. `name` names it in messages
/// ("NAME:LINE: ..."; line 2 is row 0). Throws pkm::InvalidArgument for a bad shape or value.
[[nodiscard]] io::NamedText tableOf(py::handle obj,
                                    const std::string& name,
                                    const std::vector<std::string>& columns);

/// One table or a list/tuple of tables (each as tableOf), named NAME[i] in a list.
[[nodiscard]] std::vector<io::NamedText> tablesOf(py::handle obj,
                                                  const std::string& name,
                                                  const std::vector<std::string>& columns);

}  // namespace pkm::python
