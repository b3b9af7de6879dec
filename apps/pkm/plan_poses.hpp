// `pkm plan-poses`: the options shared by the hexapod and Exechon planners.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cli_common.hpp"

namespace pkm::cli {

struct PlanArgs {
  MachineOption machine;
  int count = 30;
  std::string index = "O1";
  std::string measurement;  ///< "pose", "point", or "" (the machine's default)
  int candidates = 1000;
  std::uint64_t seed = 1;
  double reach = 0.0;
  double tilt_deg = 10.0;
  double feed = 1000.0;
  std::vector<double> target_offset;  ///< Exechon: x, y, z of the tracker target (tool frame)
  std::string gcode;
  bool force = false;
};

/// Plans tracker points for an Exechon machine and writes the CSV (standard output) and G-code.
void runExechonPlan(const PlanArgs& a);

}  // namespace pkm::cli
