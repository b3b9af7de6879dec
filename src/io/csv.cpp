#include "pkm/io/csv.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>

#include "io/detail/decimal.hpp"
#include "pkm/core/error.hpp"

namespace pkm::io {

namespace {
constexpr std::size_t kChunk = 1 << 16;

}  // namespace

std::vector<std::string_view> splitFields(std::string_view line) {
  std::vector<std::string_view> fields;
  while (true) {
    const std::size_t comma = line.find(',');
    fields.push_back(trimBlanks(line.substr(0, comma)));
    if (comma == std::string_view::npos) return fields;
    line.remove_prefix(comma + 1);
  }
}

bool parseFiniteDouble(std::string_view text, double& value) {
  text = trimBlanks(text);
  if (!text.empty() && text.front() == '+') {
    text.remove_prefix(1);
    if (!text.empty() && text.front() == '-') return false;  // "+-1"
  }
  if (text.empty()) return false;
  if (detail::parseSimpleDecimal(text.data(), text.data() + text.size(), value)) return true;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  return ec == std::errc() && ptr == text.data() + text.size() && std::isfinite(value);
}

CsvReader::CsvReader(const std::string& path,
                     std::vector<std::string> required_columns,
                     std::string display_name)
    : name_(display_name.empty() ? path : std::move(display_name)), buffer_(kChunk) {
  if (path == "-") {
    file_ = stdin;
  } else {
    file_ = std::fopen(path.c_str(), "rb");
    owns_file_ = true;
    if (file_ == nullptr)
      throw IoError(locate(name_, 0, fmt::format("cannot open: {}", std::strerror(errno))));
  }
  readHeader(required_columns);
}

CsvReader::CsvReader(NamedText input, std::vector<std::string> required_columns)
    : text_(std::move(input.text)), name_(std::move(input.name)), buffer_(kChunk) {
  readHeader(required_columns);
}

void CsvReader::readHeader(const std::vector<std::string>& required_columns) {
  std::string_view text;
  bool got = false;
  while (readLine(text)) {
    if (line_ == 1 && text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);
    const std::string_view t = trimBlanks(text);
    if (t.empty() || t.front() == '#') continue;
    got = true;
    break;
  }
  if (!got) fail("empty file: expected a header row");
  std::size_t pos = 0;
  while (true) {
    const std::size_t comma = text.find(',', pos);
    header_.emplace_back(trimBlanks(
        text.substr(pos, comma == std::string_view::npos ? std::string_view::npos : comma - pos)));
    if (comma == std::string_view::npos) break;
    pos = comma + 1;
  }
  column_of_field_.assign(header_.size(), -1);
  for (std::size_t f = 0; f < header_.size(); ++f) {
    for (std::size_t g = 0; g < f; ++g)
      if (header_[g] == header_[f])
        fail(fmt::format("column '{}' appears twice in the header", header_[f]));
  }
  std::vector<std::string> missing;
  for (std::size_t c = 0; c < required_columns.size(); ++c) {
    bool found = false;
    for (std::size_t f = 0; f < header_.size(); ++f) {
      if (header_[f] == required_columns[c]) {
        column_of_field_[f] = static_cast<int>(c);
        found = true;
      }
    }
    if (!found) missing.push_back(required_columns[c]);
  }
  if (!missing.empty())
    fail(fmt::format("missing column(s) {} in header '{}' (expected {})",
                     fmt::join(missing, ", "),
                     fmt::join(header_, ","),
                     fmt::join(required_columns, ",")));
  wanted_ = required_columns.size();
}

bool CsvReader::addOptionalColumn(const std::string& name) {
  for (std::size_t f = 0; f < header_.size(); ++f) {
    if (header_[f] == name) {
      if (column_of_field_[f] < 0) column_of_field_[f] = static_cast<int>(wanted_++);
      return true;
    }
  }
  return false;
}

CsvReader::~CsvReader() {
  if (owns_file_ && file_ != nullptr) std::fclose(file_);
}

void CsvReader::fail(const std::string& what) const { throw IoError(locate(name_, line_, what)); }

bool CsvReader::readLine(std::string_view& out) {
  long_line_.clear();
  bool spilled = false;
  while (true) {
    const char* start = buffer_.data() + begin_;
    const void* nl = std::memchr(start, '\n', end_ - begin_);
    if (nl != nullptr) {
      const auto len = static_cast<std::size_t>(static_cast<const char*>(nl) - start);
      ++line_;
      if (spilled) {
        long_line_.append(start, len);
        if (long_line_.size() > kMaxLineBytes)
          fail(fmt::format("line longer than {} bytes", kMaxLineBytes));
        out = long_line_;
      } else {
        out = std::string_view(start, len);
      }
      begin_ += len + 1;
      return true;
    }
    // No newline in the buffer: keep the partial line and read more.
    long_line_.append(start, end_ - begin_);
    spilled = true;
    begin_ = end_ = 0;
    if (long_line_.size() > kMaxLineBytes) {
      ++line_;
      fail(fmt::format("line longer than {} bytes", kMaxLineBytes));
    }
    if (eof_) {
      if (long_line_.empty()) return false;
      ++line_;
      out = long_line_;
      return true;
    }
    std::size_t n = 0;
    if (file_ != nullptr) {
      n = std::fread(buffer_.data(), 1, buffer_.size(), file_);
    } else {
      n = std::min(buffer_.size(), text_.size() - text_pos_);
      std::memcpy(buffer_.data(), text_.data() + text_pos_, n);
      text_pos_ += n;
    }
    if (n < buffer_.size()) {
      if (file_ != nullptr && std::ferror(file_)) fail("read error");
      eof_ = true;
    }
    end_ = n;
  }
}

bool CsvReader::readPlainRow(std::string_view text, std::span<double> values) const {
  // Only plain numbers separated by single commas, as programs write them; anything else (blanks,
  // '+', comments, other fields, errors) is left to the general reading, which names the problem.
  const char* p = text.data();
  const char* const end = p + text.size();
  const std::size_t fields = header_.size();
  for (std::size_t field = 0; field < fields; ++field) {
    const int column = column_of_field_[field];
    if (column < 0) return false;
    const char* q = detail::scanSimpleDecimal(p, end, values[static_cast<std::size_t>(column)]);
    if (q == nullptr) return false;
    if (field + 1 == fields) return q == end;
    if (q == end || *q != ',') return false;
    p = q + 1;
  }
  return false;
}

bool CsvReader::next(std::span<double> values) {
  if (values.size() != wanted_)
    throw InvalidArgument("CsvReader::next: wrong number of output values");
  std::string_view text;
  while (readLine(text)) {
    if (readPlainRow(text, values)) return true;
    const std::string_view t = trimBlanks(text);
    if (t.empty() || t.front() == '#') continue;
    std::size_t pos = 0;
    std::size_t field = 0;
    while (true) {
      const std::size_t comma = text.find(',', pos);
      const std::string_view cell =
          text.substr(pos, comma == std::string_view::npos ? std::string_view::npos : comma - pos);
      if (field >= header_.size())
        fail(fmt::format("too many fields: the header has {}", header_.size()));
      const int column = column_of_field_[field];
      if (column >= 0 && !parseFiniteDouble(cell, values[static_cast<std::size_t>(column)]))
        fail(fmt::format(
            "column '{}': '{}' is not a finite number", header_[field], trimBlanks(cell)));
      ++field;
      if (comma == std::string_view::npos) break;
      pos = comma + 1;
    }
    if (field != header_.size())
      fail(fmt::format("expected {} fields, found {}", header_.size(), field));
    return true;
  }
  return false;
}

}  // namespace pkm::io
