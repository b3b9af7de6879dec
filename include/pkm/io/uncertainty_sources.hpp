/// @file
/// @brief Instrument and environment descriptions (metrology::UncertaintySources) as JSON, the
/// file of `pkm analyze <kind> --uncertainty FILE` (docs/formats.md, "Uncertainty sources"):
/// an object with the optional members "laser", "probe", "dial_gauge", "tracker", "environment"
/// (with "air") and "coverage_factor"; a member left out keeps its built-in typical value.
#pragma once

#include <string>

#include "pkm/io/named_text.hpp"
#include "pkm/metrology/uncertainty_sources.hpp"

namespace pkm::io {

/// The schema name written and accepted in "schema".
inline constexpr const char* kUncertaintySourcesSchema = "pkm.uncertainty-sources/1";

/// Reads an uncertainty-sources document. Throws pkm::IoError "NAME:LINE: /pointer: message" for
/// invalid JSON, an unknown key, a value of the wrong type, or values that fail
/// metrology::UncertaintySources::isValid (then the message names the field).
[[nodiscard]] metrology::UncertaintySources readUncertaintySources(const NamedText& text);

/// The document of `sources` (every member, two-space indent, a closing newline); reading it back
/// gives `sources` exactly.
[[nodiscard]] std::string uncertaintySourcesJson(const metrology::UncertaintySources& sources);

}  // namespace pkm::io
