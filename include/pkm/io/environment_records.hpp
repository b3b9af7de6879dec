/// @file
/// @brief The environment records of measurement files (docs/formats.md, "Environment records"):
/// per-reading columns of air temperature, pressure, humidity and material temperature, as a
/// laser's environmental compensation unit logs them, and "# key: value" set-up metadata (dead
/// path, beam alignment). The budgets of `pkm analyze` evaluate their sources at them
/// (metrology/recorded_conditions.hpp).
#pragma once

#include <vector>

#include "pkm/io/named_text.hpp"
#include "pkm/io/text_table.hpp"
#include "pkm/metrology/recorded_conditions.hpp"

namespace pkm::io {

/// The records of one table. Columns, recognised by name case-insensitively (spaces and '_'
/// alike) with the unit in parentheses, brackets or as a last word:
/// - air temperature (`air temperature`, `air temp`): degC, C, °C or K (default degC);
/// - air pressure (`air pressure`, `pressure`, `barometric pressure`): Pa, hPa, mbar, kPa or mmHg
///   (default Pa);
/// - air humidity (`air humidity`, `humidity`, `relative humidity`, `rh`): %, %RH or percent;
/// - material temperature (`material temperature`, `material temp`, `mat temp`, each optionally
///   numbered: several sensors are averaged per reading): as air temperature.
/// Metadata (one value for the file, used when no column gives the quantity): `air temperature
/// C`, `air pressure Pa`, `air humidity %RH`, `material temperature C`; set-up: `dead path mm`,
/// `beam alignment urad` (the bound of the beam's misalignment). Throws pkm::IoError
/// "SOURCE:LINE: message" for a unit it does not know, a field that is not a number, or a value
/// outside the plausible range (air −40..100 °C, 60 000..140 000 Pa, 0..100 %RH; material
/// −50..100 °C; dead path and alignment ≥ 0).
[[nodiscard]] metrology::RecordedConditions environmentRecords(const TextTable& table);

/// The records of every file, merged (a Renishaw .rtl file records none here). Throws as
/// environmentRecords, naming the file.
[[nodiscard]] metrology::RecordedConditions readEnvironmentRecords(
    const std::vector<NamedText>& files);

}  // namespace pkm::io
