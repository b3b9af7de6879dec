/// @file
/// @brief Shared by the program pre-distortion tests (program_compensation_test.cpp,
/// program_compensation_cycles_test.cpp): the "calibrated" model (the milling model with seeded
/// joint errors), the tolerances of the round trip, and reading a written program back.
#pragma once

#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "pkm/cnc/interpreter.hpp"
#include "pkm/cnc/program.hpp"
#include "pkm/cnc/program_compensation.hpp"
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

/// The motions of program `text` run by a default interpreter.
inline std::vector<cnc::Move> movesOf(const std::string& text, const std::string& name) {
  cnc::MoveCollector moves;
  cnc::Interpreter interpreter;
  (void)interpreter.run(cnc::Program::parse(text, name), moves);
  return moves.moves;
}

/// Checks that the text of `r` reads back (rs274 semantics) to its commands within `tol`; returns
/// its motions.
inline std::vector<cnc::Move> expectReadsBackToCommands(const cnc::ProgramCompensation& r,
                                                        double tol) {
  const std::vector<cnc::Move> back = movesOf(r.text, "out.ngc");
  EXPECT_EQ(back.size(), r.points.size()) << r.text;
  for (std::size_t i = 0; i < back.size() && i < r.points.size(); ++i)
    for (std::size_t k = 0; k < 6; ++k)
      EXPECT_NEAR(back[i].end[k], r.points[i].command[k], tol)
          << "point " << i << " axis " << k << "\n"
          << r.text;
  return back;
}

}  // namespace pkm::test
