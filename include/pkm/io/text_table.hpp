/// @file
/// @brief A CSV file with a header row, read whole and kept as text, for inputs that mix text and
/// numbers (directions "+"/"-", diagonal names) such as the files of `pkm analyze`
/// (docs/formats.md, "CSV input"; docs/analysis.md).
#pragma once

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "pkm/io/line_numbers.hpp"

namespace pkm::io {

/// Metadata of a file: the "# key: value" lines before the header, ("key", "value") in file order.
using Metadata = std::vector<std::pair<std::string, std::string>>;

/// A whole CSV table. Format: optional '#' lines (before the header, "# key: value" lines become
/// metadata; elsewhere they are comments), blank lines, a header row of unique column names, then
/// rows with exactly as many comma-separated fields as the header. Surrounding spaces, CRLF line
/// ends and a UTF-8 byte-order mark are accepted; quoting is not. Errors are pkm::IoError
/// "SOURCE:LINE: message".
class TextTable {
 public:
  /// Reads `path` ("-" reads standard input). Throws pkm::IoError when the file cannot be read,
  /// has no header, repeats a column name, a row has the wrong number of fields, or the file is
  /// 4 GiB or larger.
  [[nodiscard]] static TextTable read(const std::string& path);
  /// Parses `text`; `source` names it in messages. Throws as read().
  [[nodiscard]] static TextTable parse(std::string text, const std::string& source);
  /// Parses a table of measured data, which must have rows: as parse(), and throws pkm::IoError
  /// "SOURCE: no data rows (only a header)" for a table without any.
  [[nodiscard]] static TextTable parseData(std::string text, const std::string& source);

  /// The name used in messages (the path).
  [[nodiscard]] const std::string& source() const { return source_; }
  /// The header fields (trimmed).
  [[nodiscard]] const std::vector<std::string>& header() const { return header_; }
  /// The "# key: value" lines before the header.
  [[nodiscard]] const Metadata& metadata() const { return metadata_; }
  /// The value of metadata `key`, if present.
  [[nodiscard]] std::optional<std::string> meta(std::string_view key) const;
  /// Number of data rows.
  [[nodiscard]] std::size_t rows() const { return rows_.size(); }

  /// Index of the first header column named one of `names` (aliases in order of preference), or
  /// nullopt.
  [[nodiscard]] std::optional<std::size_t> findColumn(
      std::initializer_list<std::string_view> names) const;
  /// As findColumn; throws pkm::IoError "SOURCE:LINE: missing column 'a' (or 'b')" at the header.
  [[nodiscard]] std::size_t column(std::initializer_list<std::string_view> names) const;

  /// The field at (row, col), trimmed. Precondition: row < rows(), col < header().size().
  [[nodiscard]] std::string_view text(std::size_t row, std::size_t col) const;
  /// The field as a finite number; throws pkm::IoError "SOURCE:LINE: column 'c': 'x' is not a
  /// finite number".
  [[nodiscard]] double number(std::size_t row, std::size_t col) const;
  /// out[k] = number(row, cols[k]) for every k, in one walk along the row (the fast way to read
  /// a large numeric table). Throws as number(). Precondition: cols.size() == out.size(), every
  /// col < header().size().
  void numbers(std::size_t row, std::span<const std::size_t> cols, std::span<double> out) const;
  /// The field as an integer (a number without fraction, |n| < 2^53); throws pkm::IoError.
  [[nodiscard]] long long integer(std::size_t row, std::size_t col) const;
  /// The field as an approach direction, case-insensitively: +1 for "+", "+1", "1", "Forward",
  /// "Fwd", "F", "Up", "Positive", "Pos"; −1 for "-", "-1", "Reverse", "Rev", "R", "Backward",
  /// "Down", "Negative", "Neg"; throws pkm::IoError otherwise.
  [[nodiscard]] int direction(std::size_t row, std::size_t col) const;
  /// The 1-based file line of data row `row`.
  [[nodiscard]] std::size_t line(std::size_t row) const { return lines_[row]; }
  /// The 1-based file lines of all data rows.
  [[nodiscard]] const LineNumbers& lineNumbers() const { return lines_; }

  /// Throws pkm::IoError "SOURCE:LINE: what" for data row `row`.
  [[noreturn]] void fail(std::size_t row, const std::string& what) const;
  /// Throws pkm::IoError "SOURCE:LINE: what" at the header line.
  [[noreturn]] void failHeader(const std::string& what) const;

 private:
  std::string source_;
  std::string text_;
  std::vector<std::string> header_;
  std::size_t header_line_ = 0;
  Metadata metadata_;
  std::vector<std::uint32_t> rows_;  ///< offset in text_ of each data row's first character
  LineNumbers lines_;
};

}  // namespace pkm::io
