#include "pkm/simulation/hybrid_tracker.hpp"

#include <Eigen/LU>

#include "pkm/core/error.hpp"
#include "pkm/geometry/rigid_transform.hpp"

namespace pkm::simulation {
namespace {

constexpr double kRigid = 1e-9;        // |RᵀR − I| of a rigid placement
constexpr int kDrawsPerReading = 200;  // rejection-sampling budget

}  // namespace

void HybridTrackerSetup::validate() const {
  PKM_CHECK(!name.empty(), "a hybrid tracker measurement needs a name");
  PKM_CHECK(count >= 1, "{}: the command count {} must be >= 1", name, count);
  PKM_CHECK(x2.allFinite() && y2.allFinite() && x2(0) <= x2(1) && y2(0) <= y2(1),
            "{}: the x2 and y2 ranges must be finite with min <= max",
            name);
  PKM_CHECK(
      pkm_min.allFinite() && pkm_max.allFinite() && (pkm_min.array() <= pkm_max.array()).all(),
      "{}: the PKM box must be finite with min <= max",
      name);
  PKM_CHECK(smr_offset.allFinite(), "{}: the SMR offset is not finite", name);
  const Eigen::Matrix3d R = work_T_tracker.linear();
  PKM_CHECK(work_T_tracker.matrix().allFinite() &&
                (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() < kRigid &&
                R.determinant() > 0.0,
            "{}: the tracker placement is not a rigid transform",
            name);
  noise.validate();
}

std::vector<HybridTrackerReading> simulateHybridTracker(HybridVirtualMachine& machine,
                                                        const HybridTrackerSetup& setup,
                                                        RandomStream& rng) {
  setup.validate();
  const geometry::RigidTransform tracker_T_work = setup.work_T_tracker.inverse();
  std::vector<HybridTrackerReading> out;
  out.reserve(static_cast<std::size_t>(setup.count));
  const long budget = static_cast<long>(kDrawsPerReading) * setup.count;
  long draws = 0;
  while (static_cast<int>(out.size()) < setup.count) {
    PKM_CHECK(draws++ < budget,
              "{}: only {} of {} commands lie within the machine's limits after {} draws",
              setup.name,
              out.size(),
              setup.count,
              budget);
    HybridTrackerReading r;
    r.command.x2 = rng.uniform(setup.x2(0), setup.x2(1));
    r.command.y2 = rng.uniform(setup.y2(0), setup.y2(1));
    for (int k = 0; k < 3; ++k) r.command.pkm(k) = rng.uniform(setup.pkm_min(k), setup.pkm_max(k));
    if (!kinematics::hybridWithinLimits(machine.model(), r.command)) continue;
    Eigen::VectorXd c(5);
    c << r.command.x2, r.command.y2, r.command.pkm;
    geometry::RigidTransform work_T_tool;
    try {
      work_T_tool = machine.moveTo(c);
    } catch (const InvalidArgument&) {
      continue;  // the PKM cannot reach it (tripod FK)
    }
    r.truth = tracker_T_work * (work_T_tool * setup.smr_offset);
    r.measured = setup.noise.point(r.truth, rng);
    out.push_back(r);
  }
  return out;
}

}  // namespace pkm::simulation
