/// @file
/// @brief Named test tolerances (house style: no bare magic numbers in test bodies).
#pragma once

namespace pkm::test {

inline constexpr double kTolExact = 1e-12;     ///< algebraic identities in double precision
inline constexpr double kTolRoundTrip = 1e-9;  ///< IK/FK round trips, model length unit / rad
inline constexpr double kTolFiniteDiff =
    1e-6;  ///< analytic vs central-difference derivatives (relative)
inline constexpr double kTolLinuxcnc = 5e-7;  ///< LinuxCNC reference values printed with 6 decimals
inline constexpr unsigned kSeed = 20261122u;  ///< fixed seed of every random test

}  // namespace pkm::test
