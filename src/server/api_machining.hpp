// The machining preview's part of POST /api/gcode/run (docs/web.md, docs/machining.md): the
// request's "machining" object and the answer's.
#pragma once

#include <optional>

#include "api_state.hpp"
#include "pkm/workflow/gcode_machining.hpp"

namespace pkm::server::detail {

/// The body's "machining" object as a request (absent or null: none). Throws HttpError 400 for
/// a field of the wrong type or size; the values are checked by the workflow (400 as well).
[[nodiscard]] std::optional<workflow::MachiningRequest> machiningRequest(const Json& body);

/// The preview as JSON: the grid, the initial and finished heights and each frame's changes as
/// base64 of little-endian float32 / uint32 arrays, the collisions, tools and volumes.
[[nodiscard]] Json machiningJson(const workflow::MachiningReport& report);

}  // namespace pkm::server::detail
