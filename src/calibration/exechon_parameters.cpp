#include "pkm/calibration/exechon_parameters.hpp"

#include <array>

#include "pkm/core/error.hpp"
#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/geometry/so3.hpp"

namespace pkm::calibration {
namespace {

const std::array<const char*, kExechonParameters>& names() {
  static const std::array<const char*, kExechonParameters> n{
      "tripod.dA",   "tripod.dB",   "tripod.dC", "tripod.l12A", "tripod.l12C",
      "tripod.l12B", "tripod.l23B", "tripod.pA", "tripod.pB",   "tripod.pC",
      "tripod.hA",   "tripod.hC",   "tripod.hx", "tripod.hz",   "offsetA",
      "offsetB",     "offsetC",     "wrist.c0",  "wrist.a0",    "wrist.tool_length",
      "base.x",      "base.y",      "base.z",    "base.rx",     "base.ry",
      "base.rz"};
  return n;
}

}  // namespace

std::string exechonParameterName(int index) {
  PKM_CHECK(index >= 0 && index < kExechonParameters,
            "Exechon parameter index {} outside [0, {})",
            index,
            kExechonParameters);
  return names()[static_cast<std::size_t>(index)];
}

int exechonParameterIndex(const std::string& name) {
  for (int k = 0; k < kExechonParameters; ++k)
    if (name == names()[static_cast<std::size_t>(k)]) return k;
  throw InvalidArgument(fmt::format("unknown Exechon parameter '{}'", name));
}

bool exechonParameterIsLength(int index) {
  return !(index == kExechonWristParameter || index == kExechonWristParameter + 1 ||
           index >= kExechonBaseParameter + 3);
}

ExechonParameterVector exechonParameters(const kinematics::ExechonModel& model,
                                         const geometry::RigidTransform& reference_world_T_zoppi) {
  const kinematics::ExechonTripodGeometry& t = model.tripod;
  ExechonParameterVector p;
  p << t.dA, t.dB, t.dC, t.l12A, t.l12C, t.l12B, t.l23B, t.pA, t.pB, t.pC, t.hA, t.hC, t.hx, t.hz,
      model.legs[0].length_offset, model.legs[1].length_offset, model.legs[2].length_offset,
      model.wrist.c0, model.wrist.a0, model.wrist.tool_length, 0, 0, 0, 0, 0, 0;
  p.segment<3>(kExechonBaseParameter) =
      model.world_T_zoppi.translation() - reference_world_T_zoppi.translation();
  p.segment<3>(kExechonBaseParameter + 3) =
      geometry::so3Log(model.world_T_zoppi.linear() * reference_world_T_zoppi.linear().transpose());
  return p;
}

kinematics::ExechonModel withExechonParameters(
    kinematics::ExechonModel model,
    const ExechonParameterVector& p,
    const geometry::RigidTransform& reference_world_T_zoppi) {
  PKM_CHECK(p.allFinite(), "Exechon parameters must be finite");
  kinematics::ExechonTripodGeometry& t = model.tripod;
  t.dA = p(0);
  t.dB = p(1);
  t.dC = p(2);
  t.l12A = p(3);
  t.l12C = p(4);
  t.l12B = p(5);
  t.l23B = p(6);
  t.pA = p(7);
  t.pB = p(8);
  t.pC = p(9);
  t.hA = p(10);
  t.hC = p(11);
  t.hx = p(12);
  t.hz = p(13);
  for (int k = 0; k < 3; ++k)
    model.legs[static_cast<std::size_t>(k)].length_offset = p(kExechonOffsetParameter + k);
  model.wrist.c0 = p(kExechonWristParameter);
  model.wrist.a0 = p(kExechonWristParameter + 1);
  model.wrist.tool_length = p(kExechonWristParameter + 2);
  geometry::RigidTransform T = geometry::RigidTransform::Identity();
  T.linear() =
      geometry::so3Exp(p.segment<3>(kExechonBaseParameter + 3)) * reference_world_T_zoppi.linear();
  T.translation() = reference_world_T_zoppi.translation() + p.segment<3>(kExechonBaseParameter);
  model.world_T_zoppi = T;
  return model;
}

ExechonParameterMask allExechonParametersFree() {
  ExechonParameterMask m{};
  m.fill(true);
  return m;
}

}  // namespace pkm::calibration
