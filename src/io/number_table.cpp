#include "pkm/io/number_table.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>

#include "io/detail/decimal.hpp"
#include "io/detail/table_preamble.hpp"
#include "pkm/core/error.hpp"
#include "pkm/core/parallel.hpp"
#include "pkm/io/csv.hpp"
#include "pkm/io/mapped_file.hpp"

namespace pkm::io {

/// Reads the data rows of one chunk of whole lines (see NumberTable::parse). One per chunk: it
/// keeps the chunk's error message, so chunks read on different threads share nothing written.
class NumberTableParser {
 public:
  NumberTableParser(const NumberTable& t, std::span<const int> slot_of_field, std::size_t width)
      : t_(t),
        slots_(slot_of_field),
        slots_wanted_(width),
        plain_(t.comma_ && std::find(slots_.begin(), slots_.end(), -1) == slots_.end()) {}

  /// What one chunk of lines gave.
  struct Chunk {
    std::size_t begin = 0, end = 0;  ///< offsets of its whole lines
    std::size_t lines = 0;           ///< lines in it
    std::size_t rows = 0;            ///< data rows read
    LineNumbers line_numbers;        ///< rows' lines, counted from 1 at the chunk's start
    std::size_t error_line = 0;      ///< relative line of the first error, 0 when none
    std::string error;
  };

  /// Reads chunk `c` of `all`, its rows' values to out[0 ...].
  void read(std::string_view all, Chunk& c, double* out) const {
    const char* p = all.data() + c.begin;
    const char* const end = all.data() + c.end;
    std::size_t line = 0;
    while (p < end) {
      ++line;
      while (p < end && detail::isTableBlank(*p)) ++p;
      if (p == end) break;
      if (*p == '\n' || *p == '#') {  // a blank or comment line
        const void* nl = std::memchr(p, '\n', static_cast<std::size_t>(end - p));
        p = nl == nullptr ? end : static_cast<const char*>(nl) + 1;
        continue;
      }
      if (const char* next = plain_ ? readPlainRow(p, end, out) : nullptr; next != nullptr) {
        p = next;
      } else {
        p = t_.comma_ ? readCommaRow(p, end, out) : readBlankRow(p, end, out);
      }
      if (p == nullptr) {
        c.error_line = line;
        c.error = std::move(error_);
        return;
      }
      out += slots_wanted_;
      c.line_numbers.add(line);
      ++c.rows;
    }
  }

 private:
  int slotOf(std::size_t field) const { return field < slots_.size() ? slots_[field] : -1; }

  /// The wanted field at p (blanks before it skipped) into v; returns its end (in a CSV row, the
  /// blanks after it skipped too) or nullptr with error_ set.
  const char* number(const char* p, const char* end, std::size_t field, double& v) const {
    const char* a = detail::scanSimpleDecimal(p, end, v);
    if (a != nullptr && t_.comma_)
      while (a < end && detail::isTableBlank(*a)) ++a;
    const bool at_end = a != nullptr && (a == end || *a == '\n' || (t_.comma_ && *a == ',') ||
                                         (!t_.comma_ && detail::isTableBlank(*a)));
    if (at_end) return a;
    const char* e = p;  // the slow path: the whole field, then from_chars
    while (e < end && *e != '\n' && (t_.comma_ ? *e != ',' : !detail::isTableBlank(*e))) ++e;
    const std::string_view text(p, static_cast<std::size_t>(e - p));
    if (!parseFiniteDouble(text, v)) {
      error_ = fmt::format(
          "column '{}': '{}' is not a finite number", t_.header_[field], trimBlanks(text));
      return nullptr;
    }
    return e;
  }

  /// The common row of a CSV file whose every column is wanted: plain numbers (the fast path's)
  /// and single commas, nothing else; returns the next line's start, or nullptr (values partly
  /// written) for anything else, which the general reading then reads or names.
  const char* readPlainRow(const char* p, const char* end, double* out) const {
    const std::size_t last = slots_.size() - 1;
    for (std::size_t f = 0;; ++f) {
      const char* q = detail::scanSimpleDecimal(p, end, out[slots_[f]]);
      if (q == nullptr || q == end) return f == last ? q : nullptr;
      if (f == last) {
        if (*q == '\n') return q + 1;
        return *q == '\r' && q + 1 < end && q[1] == '\n' ? q + 2 : nullptr;
      }
      if (*q != ',') return nullptr;
      p = q + 1;
    }
  }

  const char* readCommaRow(const char* p, const char* end, double* out) const {
    std::size_t field = 0;
    while (true) {
      while (p < end && detail::isTableBlank(*p)) ++p;
      const int slot = slotOf(field);
      if (slot >= 0) {
        p = number(p, end, field, out[slot]);
        if (p == nullptr) return nullptr;
      } else {
        while (p < end && *p != ',' && *p != '\n') ++p;
      }
      ++field;
      if (p == end || *p == '\n') break;
      ++p;  // the comma
    }
    return finishRow(p, end, field);
  }

  const char* readBlankRow(const char* p, const char* end, double* out) const {
    std::size_t field = 0;
    while (p < end && *p != '\n') {
      const int slot = slotOf(field);
      if (slot >= 0) {
        p = number(p, end, field, out[slot]);
        if (p == nullptr) return nullptr;
      } else {
        while (p < end && *p != '\n' && !detail::isTableBlank(*p)) ++p;
      }
      ++field;
      while (p < end && detail::isTableBlank(*p)) ++p;
    }
    return finishRow(p, end, field);
  }

  const char* finishRow(const char* p, const char* end, std::size_t fields) const {
    if (fields != t_.header_.size()) {
      error_ = fmt::format("expected {} fields, found {}", t_.header_.size(), fields);
      return nullptr;
    }
    return p == end ? end : p + 1;
  }

  const NumberTable& t_;
  std::span<const int> slots_;
  std::size_t slots_wanted_ = 0;
  bool plain_ = false;  ///< comma-separated, every column wanted: readPlainRow first
  mutable std::string error_;
};

namespace {

/// Chunk boundaries at line starts, nearly equal in bytes, over [begin, all.size()).
std::vector<std::size_t> chunkBounds(std::string_view all, std::size_t begin) {
  const std::size_t bytes = all.size() - begin;
  const std::size_t chunks = bytes < kParallelMinItems * 16 ? 1 : kParallelChunks;
  std::vector<std::size_t> bounds(chunks + 1, all.size());
  bounds[0] = begin;
  for (std::size_t c = 1; c < chunks; ++c) {
    const std::size_t guess = std::max(bounds[c - 1], begin + bytes / chunks * c);
    const void* nl = std::memchr(all.data() + guess, '\n', all.size() - guess);
    bounds[c] = nl == nullptr
                    ? all.size()
                    : static_cast<std::size_t>(static_cast<const char*>(nl) - all.data()) + 1;
  }
  return bounds;
}

}  // namespace

NumberTable NumberTable::read(const std::string& path,
                              const std::vector<ColumnNames>& columns,
                              bool require_rows) {
  const MappedFile file = MappedFile::open(path);
  return parse(file.bytes(), file.name(), columns, require_rows);
}

NumberTable NumberTable::parse(std::string_view all,
                               const std::string& source,
                               const std::vector<ColumnNames>& columns,
                               bool require_rows) {
  if (all.size() > MappedFile::kMaxBytes)
    throw IoError(locate(source, 0, "larger than 4 GiB; split the file"));
  NumberTable t;
  t.source_ = source;
  detail::TablePreamble pre = detail::readTablePreamble(all, source, true);
  t.header_ = std::move(pre.header);
  t.metadata_ = std::move(pre.metadata);
  t.header_line_ = pre.header_line;
  t.comma_ = pre.comma;
  std::vector<int> slots(t.header_.size(), -1);
  for (const ColumnNames& names : columns) {
    auto found = t.header_.end();
    for (auto n = names.begin(); n != names.end() && found == t.header_.end(); ++n)
      found = std::find(t.header_.begin(), t.header_.end(), *n);
    if (found == t.header_.end()) {
      std::string what;
      for (const std::string& n : names)
        what += what.empty() ? fmt::format("missing column '{}'", n) : fmt::format(" (or '{}')", n);
      t.failHeader(what);
    }
    const auto index = static_cast<std::size_t>(found - t.header_.begin());
    if (slots[index] >= 0) t.failHeader(fmt::format("column '{}' is asked for twice", *found));
    slots[index] = static_cast<int>(t.header_index_.size());
    t.header_index_.push_back(index);
  }

  // The chunks' lines, counted first so that every chunk writes its rows in place.
  const std::vector<std::size_t> bounds = chunkBounds(all, std::min(pre.data_begin, all.size()));
  const std::size_t chunks = bounds.size() - 1;
  std::vector<NumberTableParser::Chunk> parts(chunks);
  forEachChunk(all.size() - bounds[0], chunks, [&](std::size_t c, std::size_t, std::size_t) {
    NumberTableParser::Chunk& part = parts[c];
    part.begin = bounds[c];
    part.end = bounds[c + 1];
    const char* b = all.data() + part.begin;
    part.lines = static_cast<std::size_t>(std::count(b, all.data() + part.end, '\n'));
    if (part.end == all.size() && part.end > part.begin && all.back() != '\n') ++part.lines;
  });
  std::vector<std::size_t> first_slot(chunks + 1, 0);
  for (std::size_t c = 0; c < chunks; ++c) first_slot[c + 1] = first_slot[c] + parts[c].lines;
  const std::size_t width = t.width();
  // At most one row a line: 8·width bytes a line, allocated once and not zeroed (every slot a row
  // takes is written; the ones of blank and comment lines are closed up below).
  if (first_slot[chunks] * width > 0) t.values_.reset(new double[first_slot[chunks] * width]);
  forEachChunk(all.size() - bounds[0], chunks, [&](std::size_t c, std::size_t, std::size_t) {
    NumberTableParser(t, slots, width).read(all, parts[c], t.values_.get() + first_slot[c] * width);
  });

  // Errors in file order; the rows moved together where blank or comment lines left gaps.
  std::size_t lines_before = pre.header_line;
  for (std::size_t c = 0; c < chunks; ++c) {
    const NumberTableParser::Chunk& part = parts[c];
    if (part.error_line != 0)
      throw IoError(locate(source, lines_before + part.error_line, part.error));
    if (t.rows_ != first_slot[c] && part.rows > 0)
      std::memmove(t.values_.get() + t.rows_ * width,
                   t.values_.get() + first_slot[c] * width,
                   part.rows * width * sizeof(double));
    t.rows_ += part.rows;
    t.lines_.append(part.line_numbers, lines_before);
    lines_before += part.lines;
  }
  if (require_rows && t.rows_ == 0)
    throw IoError(fmt::format("{}: no data rows (only a header)", source));
  return t;
}

std::optional<std::string> NumberTable::meta(std::string_view key) const {
  for (const auto& [k, v] : metadata_)
    if (k == key) return v;
  return std::nullopt;
}

void NumberTable::failHeader(const std::string& what) const {
  throw IoError(locate(source_, header_line_, what));
}

void NumberTable::fail(std::size_t r, const std::string& what) const {
  throw IoError(locate(source_, lines_[r], what));
}

}  // namespace pkm::io
