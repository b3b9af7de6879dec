#include "pkm/io/text_table.hpp"

#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <iterator>
#include <sstream>

#include "pkm/core/error.hpp"
#include "pkm/io/csv.hpp"
#include "pkm/io/named_text.hpp"

namespace pkm::io {
TextTable TextTable::read(const std::string& path) {
  NamedText in = readNamedText(path);
  return parse(std::move(in.text), in.name);
}

TextTable TextTable::parseData(std::string text, const std::string& source) {
  TextTable t = parse(std::move(text), source);
  if (t.rows() == 0) throw IoError(fmt::format("{}: no data rows (only a header)", source));
  return t;
}

TextTable TextTable::parse(std::string text, const std::string& source) {
  TextTable t;
  t.source_ = source;
  t.text_ = std::move(text);
  const std::string_view all(t.text_);
  std::size_t pos = 0;
  std::size_t line_no = 0;
  bool header = false;
  while (pos < all.size()) {
    std::size_t end = all.find('\n', pos);
    if (end == std::string_view::npos) end = all.size();
    std::string_view line = trimBlanks(all.substr(pos, end - pos));
    pos = end + 1;
    ++line_no;
    if (line_no == 1 && line.starts_with("\xEF\xBB\xBF")) line = trimBlanks(line.substr(3));
    if (line.empty()) continue;
    if (line.front() == '#') {
      const std::string_view body = trimBlanks(line.substr(1));
      const std::size_t colon = body.find(':');
      if (!header && colon != std::string_view::npos)
        t.metadata_.emplace_back(trimBlanks(body.substr(0, colon)),
                                 trimBlanks(body.substr(colon + 1)));
      continue;
    }
    const std::size_t first_field = t.fields_.size();
    std::size_t start = 0;
    while (true) {
      const std::size_t comma = line.find(',', start);
      const std::string_view field = trimBlanks(line.substr(start, comma - start));
      t.fields_.push_back({static_cast<std::size_t>(field.data() - all.data()), field.size()});
      if (comma == std::string_view::npos) break;
      start = comma + 1;
    }
    const std::size_t count = t.fields_.size() - first_field;
    if (!header) {
      for (std::size_t i = first_field; i < t.fields_.size(); ++i) {
        const std::string name(all.substr(t.fields_[i].begin, t.fields_[i].size));
        if (name.empty())
          throw IoError(locate(source, line_no, fmt::format("header field {} is empty", i + 1)));
        for (const std::string& seen : t.header_)
          if (seen == name)
            throw IoError(locate(source, line_no, fmt::format("column '{}' appears twice", name)));
        t.header_.push_back(name);
      }
      t.fields_.clear();
      t.header_line_ = line_no;
      header = true;
      continue;
    }
    if (count != t.header_.size())
      throw IoError(locate(
          source, line_no, fmt::format("expected {} fields, found {}", t.header_.size(), count)));
    t.lines_.push_back(line_no);
  }
  if (!header) throw IoError(locate(source, 0, "no header row"));
  return t;
}

std::optional<std::string> TextTable::meta(std::string_view key) const {
  for (const auto& [k, v] : metadata_)
    if (k == key) return v;
  return std::nullopt;
}

std::optional<std::size_t> TextTable::findColumn(
    std::initializer_list<std::string_view> names) const {
  for (const std::string_view name : names)
    for (std::size_t i = 0; i < header_.size(); ++i)
      if (header_[i] == name) return i;
  return std::nullopt;
}

std::size_t TextTable::column(std::initializer_list<std::string_view> names) const {
  if (const auto found = findColumn(names)) return *found;
  std::string what;
  for (const std::string_view name : names)
    what +=
        what.empty() ? fmt::format("missing column '{}'", name) : fmt::format(" (or '{}')", name);
  failHeader(what);
}

std::string_view TextTable::text(std::size_t row, std::size_t col) const {
  const Span& f = fields_[row * header_.size() + col];
  return std::string_view(text_).substr(f.begin, f.size);
}

double TextTable::number(std::size_t row, std::size_t col) const {
  double value = 0.0;
  if (!parseFiniteDouble(text(row, col), value))
    fail(row,
         fmt::format("column '{}': '{}' is not a finite number", header_[col], text(row, col)));
  return value;
}

long long TextTable::integer(std::size_t row, std::size_t col) const {
  double value = 0.0;
  if (!parseFiniteDouble(text(row, col), value) || value != std::floor(value) ||
      std::fabs(value) >= 9007199254740992.0)
    fail(row, fmt::format("column '{}': '{}' is not an integer", header_[col], text(row, col)));
  return static_cast<long long>(value);
}

int TextTable::direction(std::size_t row, std::size_t col) const {
  const std::string_view d = text(row, col);
  std::string lower(d);
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  for (const char* plus : {"+", "+1", "1", "forward", "fwd", "f", "up", "positive", "pos"})
    if (lower == plus) return 1;
  for (const char* minus :
       {"-", "-1", "reverse", "rev", "r", "backward", "down", "negative", "neg"})
    if (lower == minus) return -1;
  fail(row,
       fmt::format("column '{}': direction '{}' is not one of +, -, Forward, Reverse, F, R, Up, "
                   "Down, 1, -1",
                   header_[col],
                   d));
}

void TextTable::fail(std::size_t row, const std::string& what) const {
  throw IoError(locate(source_, lines_[row], what));
}

void TextTable::failHeader(const std::string& what) const {
  throw IoError(locate(source_, header_line_, what));
}

}  // namespace pkm::io
