#include "pkm/calibration/hexapod_parameters.hpp"

#include <fmt/format.h>

#include <cmath>

#include "pkm/core/error.hpp"

namespace pkm::calibration {
namespace {
constexpr const char* kAxisName[] = {"x", "y", "z"};
}  // namespace

std::string hexapodParameterName(int index) {
  PKM_CHECK(index >= 0 && index < kHexapodParameters,
            "hexapod parameter index {} is outside [0, {})",
            index,
            kHexapodParameters);
  const int strut = index / kParametersPerStrut;
  const int k = index % kParametersPerStrut;
  if (k < 3) return fmt::format("base{}.{}", strut, kAxisName[k]);
  if (k < 6) return fmt::format("platform{}.{}", strut, kAxisName[k - 3]);
  return fmt::format("offset{}", strut);
}

int hexapodParameterIndex(const std::string& name) {
  for (int k = 0; k < kHexapodParameters; ++k)
    if (hexapodParameterName(k) == name) return k;
  throw InvalidArgument(
      fmt::format("unknown hexapod parameter '{}' (expected names such as "
                  "base0.x, platform5.z, offset2)",
                  name));
}

HexapodParameterVector hexapodParameters(const kinematics::HexapodModel& model) {
  HexapodParameterVector p;
  for (int i = 0; i < kinematics::kStruts; ++i) {
    const kinematics::Strut& s = model.struts[static_cast<std::size_t>(i)];
    p.segment<3>(baseParameter(i, 0)) = s.world_p_base;
    p.segment<3>(platformParameter(i, 0)) = s.platform_p_joint;
    p(offsetParameter(i)) = s.length_offset;
  }
  return p;
}

kinematics::HexapodModel withHexapodParameters(kinematics::HexapodModel model,
                                               const HexapodParameterVector& parameters) {
  for (int k = 0; k < kHexapodParameters; ++k)
    PKM_CHECK(std::isfinite(parameters(k)),
              "hexapod parameter {} is not finite",
              hexapodParameterName(k));
  for (int i = 0; i < kinematics::kStruts; ++i) {
    kinematics::Strut& s = model.struts[static_cast<std::size_t>(i)];
    s.world_p_base = parameters.segment<3>(baseParameter(i, 0));
    s.platform_p_joint = parameters.segment<3>(platformParameter(i, 0));
    s.length_offset = parameters(offsetParameter(i));
  }
  return model;
}

HexapodParameterMask allHexapodParametersFree() {
  HexapodParameterMask mask;
  mask.fill(true);
  return mask;
}

}  // namespace pkm::calibration
