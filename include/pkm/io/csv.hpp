/// @file
/// @brief Streaming reader of numeric CSV files with a header row (docs/formats.md, "CSV").
#pragma once

#include <cstdio>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "pkm/core/text.hpp"
#include "pkm/io/named_text.hpp"

namespace pkm::io {

/// Reads a CSV file row by row, picking the columns named at construction by their header names.
/// Format: a header row, then rows of numbers separated by commas; surrounding spaces, CRLF line
/// ends, a UTF-8 byte-order mark, blank lines and lines starting with '#' are accepted. Extra
/// columns are allowed and ignored. Every error throws pkm::IoError with "FILE:LINE: message".
class CsvReader {
 public:
  /// Largest accepted line, in bytes.
  static constexpr std::size_t kMaxLineBytes = 1 << 20;

  /// Opens `path` ("-" reads standard input) and reads the header. `display_name` is used in error
  /// messages (defaults to `path`). Throws pkm::IoError if the file cannot be opened, is empty, or
  /// lacks a required column or repeats a column name.
  CsvReader(const std::string& path,
            std::vector<std::string> required_columns,
            std::string display_name = {});
  /// Reads the text of `input` (a file read whole, standard input or an upload), named
  /// `input.name` in messages, and its header. Throws as the constructor from a path (except
  /// that nothing is opened).
  CsvReader(NamedText input, std::vector<std::string> required_columns);
  ~CsvReader();
  CsvReader(const CsvReader&) = delete;
  CsvReader& operator=(const CsvReader&) = delete;

  /// Reads the next data row into `values` (one per required column, in the order given at
  /// construction). Returns false at end of file. Throws pkm::IoError on a wrong field count, a
  /// field that is not a finite number, or an over-long line.
  bool next(std::span<double> values);

  /// Also reads column `name` when the header has it: its values go to the next output index after
  /// the columns requested so far, and next() then expects one more value. Returns whether the
  /// header has the column. Call before the first next().
  bool addOptionalColumn(const std::string& name);

  /// 1-based line number of the last line read.
  [[nodiscard]] std::size_t line() const { return line_; }
  /// Name used in messages.
  [[nodiscard]] const std::string& name() const { return name_; }
  /// The header fields as read (trimmed).
  [[nodiscard]] const std::vector<std::string>& header() const { return header_; }

  /// Throws pkm::IoError "NAME:LINE: what" for the current line.
  [[noreturn]] void fail(const std::string& what) const;

 private:
  bool readLine(std::string_view& out);
  /// Reads a line of plain numbers, one per header field, all wanted: the common case, in one
  /// pass. False (values partly written) for any other line.
  bool readPlainRow(std::string_view text, std::span<double> values) const;
  void readHeader(const std::vector<std::string>& required_columns);

  std::FILE* file_ = nullptr;  ///< null: reading text_
  std::string text_;
  std::size_t text_pos_ = 0;
  bool owns_file_ = false;
  std::string name_;
  std::vector<char> buffer_;
  std::size_t begin_ = 0;
  std::size_t end_ = 0;
  bool eof_ = false;
  std::string long_line_;
  std::size_t line_ = 0;
  std::vector<std::string> header_;
  std::vector<int> column_of_field_;  ///< per header field: index into values, or -1
  std::size_t wanted_ = 0;
};

/// Parses a whole field as a finite double (leading '+' and surrounding spaces allowed).
/// Returns false for anything else, including "nan" and "inf".
[[nodiscard]] bool parseFiniteDouble(std::string_view text, double& value);

using pkm::trimBlanks;  // core/text.hpp

/// The comma-separated fields of `line` (views into it, each trimmed as by trimBlanks), in
/// order; an empty line gives one empty field.
[[nodiscard]] std::vector<std::string_view> splitFields(std::string_view line);

using pkm::splitWords;  // core/text.hpp

}  // namespace pkm::io
