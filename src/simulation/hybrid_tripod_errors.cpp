#include "pkm/simulation/hybrid_tripod_errors.hpp"

#include <cmath>
#include <string>

#include "pkm/core/error.hpp"
#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/kinematics/exechon_data.hpp"
#include "pkm/kinematics/exechon_wrist.hpp"
#include "pkm/simulation/compliance.hpp"

namespace pkm::simulation {

namespace kin = pkm::kinematics;

bool ExechonTripodErrors::isZero() const {
  return dA == 0.0 && dB == 0.0 && dC == 0.0 && l12A == 0.0 && l12C == 0.0 && l12B == 0.0 &&
         l23B == 0.0 && pA == 0.0 && pB == 0.0 && pC == 0.0 && hA == 0.0 && hC == 0.0 &&
         hx == 0.0 && hz == 0.0 && length_offset.isZero(0.0) && c0 == 0.0 && a0 == 0.0 &&
         tool_length == 0.0;
}

void ExechonTripodErrors::validate() const {
  const auto finite = [](double v, const char* name) {
    PKM_CHECK(std::isfinite(v), "tripod error {} is not finite", name);
  };
  finite(dA, "dA");
  finite(dB, "dB");
  finite(dC, "dC");
  finite(l12A, "l12A");
  finite(l12C, "l12C");
  finite(l12B, "l12B");
  finite(l23B, "l23B");
  finite(pA, "pA");
  finite(pB, "pB");
  finite(pC, "pC");
  finite(hA, "hA");
  finite(hC, "hC");
  finite(hx, "hx");
  finite(hz, "hz");
  PKM_CHECK(length_offset.allFinite(), "tripod error length_offset is not finite");
  finite(c0, "c0");
  finite(a0, "a0");
  finite(tool_length, "tool_length");
}

kin::ExechonModel perturbedExechon(const kin::ExechonModel& nominal,
                                   const ExechonTripodErrors& errors) {
  errors.validate();
  kin::ExechonModel m = nominal;
  m.name = nominal.name + " (true)";
  kin::ExechonTripodGeometry& t = m.tripod;
  t.dA += errors.dA;
  t.dB += errors.dB;
  t.dC += errors.dC;
  t.l12A += errors.l12A;
  t.l12C += errors.l12C;
  t.l12B += errors.l12B;
  t.l23B += errors.l23B;
  t.pA += errors.pA;
  t.pB += errors.pB;
  t.pC += errors.pC;
  t.hA += errors.hA;
  t.hC += errors.hC;
  t.hx += errors.hx;
  t.hz += errors.hz;
  for (std::size_t i = 0; i < m.legs.size(); ++i)
    m.legs[i].length_offset += errors.length_offset[static_cast<Eigen::Index>(i)];
  m.wrist.c0 += errors.c0;
  m.wrist.a0 += errors.a0;
  m.wrist.tool_length += errors.tool_length;
  m.validate();
  return m;
}

HybridTripod::HybridTripod(kin::ExechonModel nominal,
                           const ExechonTripodErrors& errors,
                           kin::FkOptions fk)
    : nominal_(std::move(nominal)), errors_(errors), fk_(fk) {
  nominal_.validate();
  actual_ = perturbedExechon(nominal_, errors_);
  std::string why;
  PKM_CHECK(fk_.isValid(&why), "tripod forward-kinematics options: {}", why);
}

void HybridTripod::setCompliance(std::optional<ExechonCompliance> compliance) {
  std::string why;
  PKM_CHECK(!compliance || compliance->isValid(&why), "Exechon compliance: {}", why);
  compliance_ = std::move(compliance);
}

geometry::RigidTransform HybridTripod::errorMotion(const Eigen::Vector3d& p) const {
  PKM_CHECK(p.allFinite(), "PKM command is not finite");
  kin::ExechonToolPose target;
  target.position = p;
  target.direction = -Eigen::Vector3d::UnitZ();  // the vertical tool of the hybrid chain
  kin::ExechonData nom(nominal_);
  const kin::ExechonIkStatus ik = kin::toolInverseKinematics(nominal_, nom, target);
  PKM_CHECK(ik == kin::ExechonIkStatus::kOk,
            "nominal Exechon tool IK at PKM command ({}, {}, {}): {}",
            p.x(),
            p.y(),
            p.z(),
            kin::toString(ik));
  kin::ExechonData act(actual_);
  const kin::ExechonConfiguration seed = kin::configurationOf(nom);
  const kin::ExechonJoints travelled = withLeadErrors(kin::jointsOf(nom), lead_);
  const kin::ExechonJoints joints =
      compliance_ ? exechonDeflectedJoints(actual_, travelled, seed, fk_, *compliance_) : travelled;
  const kin::FkSummary fk = kin::toolForwardKinematics(actual_, act, joints, seed, fk_);
  PKM_CHECK(fk.status == kin::FkStatus::kOk,
            "true Exechon tool FK at PKM command ({}, {}, {}): {}",
            p.x(),
            p.y(),
            p.z(),
            kin::toString(fk.status));
  geometry::RigidTransform e = geometry::RigidTransform::Identity();
  e.linear() = act.world_R_tool * nom.world_R_tool.transpose();
  e.translation() = act.world_p_tool - nom.world_p_tool;
  return e;
}

void HybridTripod::setLegLeadErrors(const ExechonLegLeadErrors& lead) {
  for (const ScrewLeadError& e : lead) e.validate();
  lead_ = lead;
}

}  // namespace pkm::simulation
