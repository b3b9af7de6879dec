/// @file
/// @brief Shared by the `pkm exechon ...` CLI tests (exechon_cli_test.cpp,
/// exechon_input_cli_test.cpp): their fixture, the paper's wrist point and hybrid tool poses, and
/// the data rows of a CSV output.
#pragma once

#include <string>
#include <vector>

#include "support/cli_fixture.hpp"

namespace pkm::test {

/// The paper's example: S = (20, 700, 1020) mm; q, alpha, beta (deg), h (mm) for branch (+,+,+,+).
inline constexpr const char* kZoppiWrist = "sx,sy,sz\n20,700,1020\n0,0,0\n";

/// Tool poses of mxt700s-like (work frame), all reachable with the centred split.
inline constexpr const char* kHybridPoses =
    "x,y,z,i,j,k\n"
    "0,0,0,0,0,-1\n"
    "10,20,-50,0,0,-1\n"
    "100,-50,30,0.1,0,-1\n"
    "1500,-120,100,0,0.05,-1\n";

/// The data rows of a CSV text (lines after the header that are not comments), split in fields.
inline std::vector<std::vector<std::string>> rowsOf(const std::string& csv) {
  std::vector<std::vector<std::string>> rows;
  const auto lines = splitLines(csv);
  for (std::size_t k = 1; k < lines.size(); ++k)
    if (!lines[k].empty() && lines[k][0] != '#') rows.push_back(splitFields(lines[k]));
  return rows;
}

/// The fixture of the ExechonCli tests: a temporary folder and the `pkm` runner (CliTest).
class ExechonCli : public CliTest {};

}  // namespace pkm::test
