/// @file
/// @brief The bulk reader of numeric tables: the columns a caller names, read from a CSV or
/// whitespace-separated file in one pass over its bytes, in parallel chunks on the machine's
/// cores, into one row-major array of doubles (docs/formats.md, "CSV input"; docs/performance.md,
/// "Reading tables"). For files of thousands to millions of rows whose other columns the caller
/// does not need: a measured circle, a path of strut lengths.
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "pkm/io/line_numbers.hpp"
#include "pkm/io/text_table.hpp"

namespace pkm::io {

/// A wanted column: its names, in order of preference ("x", "x_mm").
using ColumnNames = std::vector<std::string>;

/// Numbers of the wanted columns of a table. Format as io::TextTable: optional "# key: value"
/// metadata lines before the header, '#' comment lines, blank lines, a header row of unique
/// names, rows with exactly as many fields as the header; a UTF-8 byte-order mark, CRLF and
/// surrounding blanks accepted. Fields are separated by commas, or by runs of spaces and tabs
/// when the header line has no comma and more than one field. Wanted fields must be finite
/// numbers ("+1", "1e-3" and the like); other fields may hold any text. Errors are
/// pkm::IoError "SOURCE:LINE: message" and name the first bad line of the file.
class NumberTable {
 public:
  /// Maps and reads `path` ("-" reads standard input). Throws pkm::IoError for an unreadable
  /// file, a missing header, a missing or repeated column, a row with the wrong number of fields
  /// or a wanted field that is not a finite number, and, when `require_rows`, a table without
  /// data rows.
  [[nodiscard]] static NumberTable read(const std::string& path,
                                        const std::vector<ColumnNames>& columns,
                                        bool require_rows = true);
  /// Reads `text` (not kept), named `source` in messages. Throws as read().
  [[nodiscard]] static NumberTable parse(std::string_view text,
                                         const std::string& source,
                                         const std::vector<ColumnNames>& columns,
                                         bool require_rows = true);

  /// The name used in messages.
  [[nodiscard]] const std::string& source() const { return source_; }
  /// The header fields (trimmed).
  [[nodiscard]] const std::vector<std::string>& header() const { return header_; }
  /// The "# key: value" lines before the header.
  [[nodiscard]] const Metadata& metadata() const { return metadata_; }
  /// The value of metadata `key`, if present.
  [[nodiscard]] std::optional<std::string> meta(std::string_view key) const;
  /// The header's index of wanted column k.
  [[nodiscard]] std::size_t headerIndex(std::size_t k) const { return header_index_[k]; }
  /// Whether fields are separated by commas (false: by blanks).
  [[nodiscard]] bool commaSeparated() const { return comma_; }

  /// Number of data rows.
  [[nodiscard]] std::size_t rows() const { return rows_; }
  /// Number of wanted columns.
  [[nodiscard]] std::size_t width() const { return header_index_.size(); }
  /// All values, row-major: row r's wanted column k at r * width() + k.
  [[nodiscard]] std::span<const double> values() const { return {values_.get(), rows_ * width()}; }
  /// Row r's values, in the order of the wanted columns. Precondition: r < rows().
  [[nodiscard]] std::span<const double> row(std::size_t r) const {
    return {values_.get() + r * width(), width()};
  }
  /// The 1-based file line of data row r.
  [[nodiscard]] std::size_t line(std::size_t r) const { return lines_[r]; }
  /// The 1-based file lines of all data rows.
  [[nodiscard]] const LineNumbers& lineNumbers() const { return lines_; }

  /// Throws pkm::IoError "SOURCE:LINE: what" at the header line.
  [[noreturn]] void failHeader(const std::string& what) const;
  /// Throws pkm::IoError "SOURCE:LINE: what" for data row r.
  [[noreturn]] void fail(std::size_t r, const std::string& what) const;

 private:
  std::string source_;
  std::vector<std::string> header_;
  std::size_t header_line_ = 0;
  Metadata metadata_;
  bool comma_ = true;
  std::vector<std::size_t> header_index_;
  std::unique_ptr<double[]> values_;  ///< allocated for every line, filled for the rows
  std::size_t rows_ = 0;
  LineNumbers lines_;

  friend class NumberTableParser;
};

}  // namespace pkm::io
