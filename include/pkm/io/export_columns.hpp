/// @file
/// @brief Columns of an instrument's export recognised by name (docs/formats.md, "Instrument
/// exports"): a header field's name and the unit it states (`Target (mm)`, `Error [µm]`,
/// `reading_mm`), case-insensitive aliases per quantity, explicit `role=NAME` assignments, and one
/// error that lists every missing quantity with the names accepted and the columns found.
#pragma once

#include <cstddef>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "pkm/io/text_table.hpp"

namespace pkm::io {

/// A header field split into its name (lower case, spaces and '_' runs as one space) and the unit
/// it states in parentheses, brackets or a `_unit` suffix, normalised ("µm" → "um").
/// "Target (mm)" → {"target", "mm"}; "Error [µm]" → {"error", "um"}; "reading_mm" →
/// {"reading", "mm"}; "Run" → {"run", ""}.
struct HeaderField {
  std::string name;
  std::string unit;  ///< "" when the field states none
};
[[nodiscard]] HeaderField splitHeaderField(std::string_view field);

/// Millimetres per `unit`: "mm" 1, "um" (also "µm", "micron", "microns") 1e-3, "nm" 1e-6,
/// "m" 1000, "in" (also "inch", "inches") 25.4; nullopt for anything else (case-insensitive).
[[nodiscard]] std::optional<double> millimetresPer(std::string_view unit);

/// One quantity an export gives, and the column names it goes by (lower case, without unit).
struct ColumnRole {
  std::string_view role;                ///< e.g. "target"
  std::vector<std::string_view> names;  ///< e.g. {"target", "nominal", "position"}
};

/// Explicit assignments `role=NAME` (the `--columns` option), in the order given.
using ColumnAssignments = std::vector<std::pair<std::string, std::string>>;

/// Parses "target=Target Pos,error=Dev (um)" into assignments. Throws pkm::InvalidArgument for an
/// item without '=' or with an empty side.
[[nodiscard]] ColumnAssignments parseColumnAssignments(std::string_view text);

/// The columns of one table assigned to roles.
class ExportColumns {
 public:
  /// Assigns each role in `roles`: an explicit assignment names the header field (its full text
  /// or its name without unit, case-insensitively); otherwise the first field whose name is one
  /// of the role's names. Throws pkm::IoError at the header for an assignment to an unknown role
  /// or to a column the table does not have (listing the columns found).
  ExportColumns(const TextTable& table,
                const std::vector<ColumnRole>& roles,
                const ColumnAssignments& assigned = {});

  /// Checks that every group of `alternatives` has one assigned role (a group such as
  /// {"measured", "error"} is met by either). Throws pkm::IoError at the header naming every
  /// unmet group with the names each role accepts, and the columns found — once.
  void require(std::initializer_list<std::initializer_list<std::string_view>> alternatives) const;

  /// The column of `role`, if assigned.
  [[nodiscard]] std::optional<std::size_t> find(std::string_view role) const;
  /// The column of `role`. Precondition: assigned (require()).
  [[nodiscard]] std::size_t at(std::string_view role) const;
  /// The unit the header of `role`'s column states ("" when none or unassigned).
  [[nodiscard]] std::string unit(std::string_view role) const;

 private:
  struct Assigned {
    std::string role;
    std::vector<std::string> names;
    std::optional<std::size_t> column;
  };
  const TextTable* table_;
  std::vector<Assigned> roles_;
};

/// The scale (mm per unit) of a column: the unit its header states, else `fallback` (an option
/// such as --unit; "" for none). Throws pkm::IoError at the header when the two disagree, when a
/// unit is not a length unit, or when neither gives one and `required` (naming `option`, the
/// option that supplies it); returns 1 (mm) when neither gives one and the unit is not required.
[[nodiscard]] double columnScale(const TextTable& table,
                                 const ExportColumns& columns,
                                 std::string_view role,
                                 std::string_view fallback,
                                 std::string_view option,
                                 bool required);

}  // namespace pkm::io
