// A hexapod truth.json text as `pkm simulate` writes it (docs/formats.md, "truth.json"), for the
// tests of io::parseHexapodTruth and `pkm linuxcnc config --simulate-truth`.
#pragma once

#include <string>

namespace pkm::test {

/// The truth of the built-in hexapod-default with small errors and seed 004's actuation.
inline std::string hexapodTruthText(const std::string& machine = "hexapod-default") {
  return R"({
  "schema": "pkm.truth/1",
  "scenario": "test",
  "seed": 4,
  "machine_kind": "hexapod",
  "machine": ")" +
         machine + R"(",
  "errors": {
    "base_joint": [[1, -2, 3], [0, 0, 0], [0.5, 0, 0], [0, 0, 0], [0, 0, 0], [0, 0, -1]],
    "platform_joint": [[0, 0, 0], [0.25, 0, 0], [0, 0, 0], [0, -0.5, 0], [0, 0, 0], [0, 0, 0]],
    "length_offset": [1, 0, 0, -2, 0, 0.5]
  },
  "true_geometry": {"base": [], "platform": [], "length_offset": []},
  "actuation": {"encoder_resolution": 0.001, "backlash": [0.005, 0.005, 0.005, 0.005, 0.005, 0.005], "repeatability_sigma": 0.002}
}
)";
}

}  // namespace pkm::test
