// POST /api/ik (docs/web.md): poses solved and checked by workflow::checkPoses.
#include <fmt/format.h>

#include "api_state.hpp"
#include "pkm/workflow/pose_checks.hpp"

namespace pkm::server::detail {

Response checkPoses(Api::State& s, const Request& r) {
  const Json body = parseObject(r);
  const MachineSpec m = s.resolveMachine(requiredString(body, "machine"));
  if (!body.contains("poses") || !body["poses"].is_array())
    throw HttpError(400,
                    "\"poses\" must be an array of [x, y, z, a, b, c] (hexapod) or "
                    "[x, y, z, i, j, k] (Exechon: tool point and direction)");
  workflow::PoseCheckRequest q;
  q.machine = m.spec;
  q.ini = m.ini;
  for (const Json& p : body["poses"]) {
    if (!p.is_array() || p.size() != 6)
      throw HttpError(400, fmt::format("poses[{}]: expected 6 numbers", q.poses.size()));
    std::array<double, 6> v{};
    for (std::size_t k = 0; k < 6; ++k) {
      if (!p[k].is_number())
        throw HttpError(400, fmt::format("poses[{}][{}]: not a number", q.poses.size(), k));
      v[k] = p[k].get<double>();
    }
    q.poses.push_back(v);
  }
  const workflow::PoseCheckResult result = workflow::checkPoses(q);
  Json rows = Json::array();
  for (const workflow::PoseCheckRow& row : result.rows) rows.push_back(poseRowJson(row));
  return json({{"machine", result.machine},
               {"type", result.machine_type},
               {"units", result.units},
               {"joints", result.joint_names},
               {"rows", rows}});
}

}  // namespace pkm::server::detail
