// Shared by the `gcode compensate` workflow's sources (workflow/gcode_compensate.hpp).
#pragma once

#include <string>

#include "pkm/cnc/program_compensation.hpp"
#include "pkm/workflow/gcode_compensate.hpp"

namespace pkm::workflow::detail {

/// "; the program has O-words: ..." when the program had to be flattened first, else "".
[[nodiscard]] std::string flattenedNote(const cnc::ProgramCompensation& r);

/// The hybrid machine's squareness correction (request.hybrid_frame, request.x2; validated).
[[nodiscard]] GcodeCompensateResult compensateHybridGcode(const GcodeCompensateRequest& request);

/// Writes the compensated program to request.out when it is set (io::AtomicFile).
void writeCompensated(const GcodeCompensateRequest& request, const GcodeCompensateResult& result);

}  // namespace pkm::workflow::detail
