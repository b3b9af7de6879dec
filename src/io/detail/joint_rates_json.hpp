// Private to the io module: reading the "joint_rates" member of a machine file.
#pragma once

#include <string>

#include "io/detail/json_doc.hpp"
#include "pkm/io/joint_rates.hpp"

namespace pkm::io::detail {

/// Reads `"joint_rates"` at `ptr`: velocity and acceleration (and the wrist's when `wrist`), each
/// optional and > 0. Unknown keys and bad values fail with the file's line.
JointRateSpec readJointRates(const JsonDoc& doc, const json& v, const std::string& ptr, bool wrist);

}  // namespace pkm::io::detail
