/// @file
/// @brief Shared by the `pkm hexapod ...` CLI tests (hexapod_cli_test.cpp,
/// hexapod_machine_cli_test.cpp): their fixture and the pose files of both built-in machines.
#pragma once

#include "support/cli_fixture.hpp"

namespace pkm::test {

/// Poses of the LinuxCNC hexapod-sim (inch, deg): home, then the two LinuxCNC reference poses.
inline constexpr const char* kSimPoses =
    "x,y,z,a,b,c\n0,0,20,0,0,0\n2,-1,22,3,-4,10\n-3,2,18,10,10,-15\n";
/// Poses of hexapod-default (mm, deg) about its home.
inline constexpr const char* kDefaultPoses =
    "x,y,z,a,b,c\n0,0,200,0,0,0\n10,-5,210,3,-2,5\n-20,15,180,-4,6,-10\n";

/// The fixture of the HexapodCli tests: a temporary folder and the `pkm` runner (CliTest).
class HexapodCli : public CliTest {};

}  // namespace pkm::test
