#include "pkm/kinematics/hybrid_model.hpp"

#include <algorithm>
#include <cmath>

#include "pkm/core/error.hpp"

namespace pkm::kinematics {

namespace {
bool validRange(double lo, double hi) { return !std::isnan(lo) && !std::isnan(hi) && lo <= hi; }

bool inside(double v, double lo, double hi) { return v >= lo && v <= hi; }

/// Centre of [lo, hi] when both ends are finite, otherwise 0 clamped into the range.
double preferred(double lo, double hi) {
  if (std::isfinite(lo) && std::isfinite(hi)) return 0.5 * (lo + hi);
  return std::clamp(0.0, lo, hi);
}
}  // namespace

Eigen::Vector3d HybridMachineModel::workOffset() const { return X2_p_P + P_p_tcp0 - Y2_p_work; }

void HybridMachineModel::validate() const {
  PKM_CHECK(validRange(x2_stroke.min, x2_stroke.max),
            "X2 stroke [{}, {}] is empty",
            x2_stroke.min,
            x2_stroke.max);
  PKM_CHECK(validRange(y2_stroke.min, y2_stroke.max),
            "Y2 stroke [{}, {}] is empty",
            y2_stroke.min,
            y2_stroke.max);
  for (int a = 0; a < 3; ++a) {
    PKM_CHECK(validRange(pkm_min[a], pkm_max[a]),
              "PKM working volume along axis {}: [{}, {}] is empty",
              a,
              pkm_min[a],
              pkm_max[a]);
  }
  PKM_CHECK(X2_p_P.allFinite(), "X2_p_P is not finite");
  PKM_CHECK(P_p_tcp0.allFinite(), "P_p_tcp0 is not finite");
  PKM_CHECK(Y2_p_work.allFinite(), "Y2_p_work is not finite");
}

bool hybridWithinLimits(const HybridMachineModel& model, const HybridCommand& command) {
  bool ok = inside(command.x2, model.x2_stroke.min, model.x2_stroke.max) &&
            inside(command.y2, model.y2_stroke.min, model.y2_stroke.max);
  for (int a = 0; a < 3; ++a) ok = ok && inside(command.pkm[a], model.pkm_min[a], model.pkm_max[a]);
  return ok;
}

Eigen::Vector3d hybridNominalToolPosition(const HybridMachineModel& model,
                                          const HybridCommand& command) {
  return command.pkm + Eigen::Vector3d(command.x2, -command.y2, 0.0) + model.workOffset();
}

HybridCommand hybridCommandForTool(const HybridMachineModel& model,
                                   const Eigen::Vector3d& work_p_tool,
                                   double x2,
                                   double y2) {
  HybridCommand c;
  c.x2 = x2;
  c.y2 = y2;
  c.pkm = work_p_tool - model.workOffset() - Eigen::Vector3d(x2, -y2, 0.0);
  return c;
}

HybridCommand hybridCommandCentred(const HybridMachineModel& model,
                                   const Eigen::Vector3d& work_p_tool) {
  model.validate();
  PKM_CHECK(work_p_tool.allFinite(), "tool position is not finite");
  const Eigen::Vector3d local = work_p_tool - model.workOffset();  // = pkm + (x2, -y2, 0)
  const double xp = preferred(model.pkm_min.x(), model.pkm_max.x());
  const double yp = preferred(model.pkm_min.y(), model.pkm_max.y());
  const double x2 = std::clamp(local.x() - xp, model.x2_stroke.min, model.x2_stroke.max);
  const double y2 = std::clamp(yp - local.y(), model.y2_stroke.min, model.y2_stroke.max);
  return hybridCommandForTool(model, work_p_tool, x2, y2);
}

}  // namespace pkm::kinematics
