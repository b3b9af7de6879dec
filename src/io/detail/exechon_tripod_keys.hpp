/// @file
/// @brief Internal: the JSON keys of the Exechon tripod geometry and the fields they name (shared
/// by the Exechon machine reader and writer).
#pragma once

#include "pkm/kinematics/exechon_model.hpp"

namespace pkm::io::detail {

/// Zoppi's 12 dimensions, then leg B's base-joint offsets (written only when non-zero).
inline constexpr const char* kTripodKeys[] = {
    "dA", "dB", "dC", "l12A", "l12C", "pA", "pB", "pC", "hA", "hC", "hx", "hz", "l12B", "l23B"};
/// How many of kTripodKeys are Zoppi's dimensions.
inline constexpr int kZoppiKeys = 12;
/// How many kTripodKeys there are.
inline constexpr int kTripodKeyCount = 14;

/// The field of `t` that kTripodKeys[i] names.
inline double* tripodField(kinematics::ExechonTripodGeometry& t, int i) {
  double* fields[] = {&t.dA,
                      &t.dB,
                      &t.dC,
                      &t.l12A,
                      &t.l12C,
                      &t.pA,
                      &t.pB,
                      &t.pC,
                      &t.hA,
                      &t.hC,
                      &t.hx,
                      &t.hz,
                      &t.l12B,
                      &t.l23B};
  return fields[i];
}

}  // namespace pkm::io::detail
