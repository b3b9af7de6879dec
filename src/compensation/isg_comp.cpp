#include "pkm/compensation/isg_comp.hpp"

#include <fmt/format.h>

#include <cctype>
#include <cmath>

#include "number_text.hpp"
#include "pkm/core/error.hpp"

namespace pkm::compensation {
namespace {

std::string linearAxis(const std::string& name) {
  std::string a = name;
  for (char& c : a) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  PKM_CHECK(a == "X" || a == "Y" || a == "Z",
            "ISG CSV arguments are the linear axes X, Y, Z; got '{}'",
            name);
  return a;
}

}  // namespace

void IsgBlock::validate() const {
  PKM_CHECK(argument == "X" || argument == "Y" || argument == "Z",
            "ISG CSV argument must be X, Y or Z, got '{}'",
            argument);
  PKM_CHECK(comment.find('\n') == std::string::npos, "ISG CSV comment must be one line");
  PKM_CHECK(positions.size() >= 2, "ISG CSV block needs at least 2 rows");
  PKM_CHECK(!columns.empty(), "ISG CSV block needs at least one parameter column");
  for (std::size_t i = 0; i < positions.size(); ++i) {
    PKM_CHECK(std::isfinite(positions[i]), "ISG CSV position {} is not finite", i);
    PKM_CHECK(i == 0 || positions[i] > positions[i - 1],
              "ISG CSV positions must be strictly increasing (row {})",
              i);
  }
  for (const IsgColumn& c : columns) {
    bool ok = !c.name.empty();
    for (char ch : c.name)
      ok = ok && (std::isupper(static_cast<unsigned char>(ch)) ||
                  std::isdigit(static_cast<unsigned char>(ch)));
    PKM_CHECK(ok, "'{}' is not an ISG CSV parameter name", c.name);
    PKM_CHECK(c.values.size() == positions.size(),
              "ISG CSV column {} has {} values for {} rows",
              c.name,
              c.values.size(),
              positions.size());
    for (std::size_t i = 0; i < c.values.size(); ++i) {
      PKM_CHECK(std::isfinite(c.values[i]), "ISG CSV column {} row {} is not finite", c.name, i);
    }
  }
}

IsgBlock isgBlockFromTable(const AxisErrorTable& table) {
  table.validate();
  const std::string a = linearAxis(table.axis);
  IsgBlock b;
  b.comment =
      fmt::format("positioning error of {} (actual - commanded, mean of both directions), mm", a);
  b.argument = a;
  b.positions = table.nominal;
  IsgColumn c{fmt::format("E{}{}", a, a), {}};
  for (std::size_t i = 0; i < table.size(); ++i) c.values.push_back(table.meanError(i));
  b.columns.push_back(std::move(c));
  b.validate();
  return b;
}

IsgBlock isgBlockFromTable(const CrossAxisTable& table) {
  table.validate();
  const std::string in = linearAxis(table.input_axis), out = linearAxis(table.output_axis);
  PKM_CHECK(in != out, "a straightness table needs two different axes, got {} twice", in);
  IsgBlock b;
  b.comment = fmt::format("straightness of {} in {} (actual - nominal), mm", in, out);
  b.argument = in;
  b.positions = table.position;
  b.columns.push_back({fmt::format("E{}{}", out, in), table.error});
  b.validate();
  return b;
}

std::string writeIsgCsv(std::span<const IsgBlock> blocks) {
  PKM_CHECK(!blocks.empty(), "an ISG CSV file needs at least one block");
  std::string out;
  for (std::size_t k = 0; k < blocks.size(); ++k) {
    const IsgBlock& b = blocks[k];
    b.validate();
    if (k > 0) out += "#\n";
    if (!b.comment.empty()) out += fmt::format("// {}\n", b.comment);
    out += b.argument;
    for (const IsgColumn& c : b.columns) {
      out += ' ';
      out += c.name;
    }
    out += "\n";
    for (std::size_t i = 0; i < b.positions.size(); ++i) {
      out += detail::fixedText(b.positions[i]);
      for (const IsgColumn& c : b.columns) {
        out += ' ';
        out += detail::fixedText(c.values[i]);
      }
      out += "\n";
    }
  }
  return out;
}

}  // namespace pkm::compensation
