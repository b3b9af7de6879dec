/// @file
/// @brief Shared by the program pre-distortion tests (program_compensation_test.cpp,
/// program_compensation_cycles_test.cpp): the "calibrated" model (the milling model with seeded
/// joint errors) and the tolerances of the round trip.
#pragma once

#include <random>

#include "pkm/kinematics/hexapod_model.hpp"
#include "support/tolerances.hpp"

namespace pkm::test {

inline constexpr double kJointMatch = 1e-6;  // mm: the round-trip requirement
inline constexpr double kTextDigits = 1e-8;  // mm/deg: the 9 decimals of the written words
inline constexpr double kJointError = 0.5;   // mm, joint errors of the "calibrated" model
inline constexpr double kTol = 0.01;         // mm

/// `nominal` with seeded uniform errors of ±kJointError on every joint and length offset.
inline kinematics::HexapodModel calibrated(const kinematics::HexapodModel& nominal) {
  std::mt19937 rng(kSeed);
  std::uniform_real_distribution<double> u(-kJointError, kJointError);
  kinematics::HexapodModel m = nominal;
  for (auto& s : m.struts) {
    for (int k = 0; k < 3; ++k) {
      s.world_p_base[k] += u(rng);
      s.platform_p_joint[k] += u(rng);
    }
    s.length_offset += u(rng);
  }
  return m;
}

}  // namespace pkm::test
