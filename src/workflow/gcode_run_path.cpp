// The path of a `gcode run` for a front end (gcode_run_detail.hpp): evenly decimated, keeping the
// ends and every point where a check's worst value occurs.
#include <algorithm>

#include "gcode_run_detail.hpp"

namespace pkm::workflow::detail {
namespace {

/// Indices into run.points to keep: every stride-th point, the first and the last, and the
/// points whose position equals a check's worst (or first violation's) position.
std::vector<std::size_t> keptPoints(const JointRun& run, std::size_t max_points) {
  const std::size_t n = run.points.size();
  std::vector<char> keep(n, 0);
  const std::size_t stride = n <= max_points ? 1 : (n + max_points - 1) / max_points;
  for (std::size_t i = 0; i < n; i += stride) keep[i] = 1;
  if (n > 0) keep[n - 1] = 1;
  std::vector<cnc::Axes> special;
  for (const cnc::CheckStat& st : run.report.stats) {
    if (!st.enabled) continue;
    special.push_back(st.worst.pos);
    if (st.violations > 0) special.push_back(st.first.pos);
  }
  for (std::size_t i = 0; i < n; ++i)
    if (std::find(special.begin(), special.end(), run.points[i].pos) != special.end()) keep[i] = 1;
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < n; ++i)
    if (keep[i]) out.push_back(i);
  return out;
}

}  // namespace

GcodeRunPath runPath(const JointRun& run, std::size_t max_points) {
  GcodeRunPath path;
  if (max_points == 0) return path;
  path.joints = run.joint_names;
  path.joint_units = run.joint_units;
  path.total_points = run.points.size();
  path.index = keptPoints(run, max_points);
  const std::size_t joints = run.joint_names.size();
  for (const std::size_t i : path.index) {
    const cnc::PathPoint& p = run.points[i];
    path.t.push_back(run.time.t[i]);
    path.line.push_back(p.line);
    path.pose.push_back(p.pos);
    const kinematics::StrutVector q = run.joints_at(i);
    path.q.emplace_back(q.data(), q.data() + joints);
  }
  return path;
}

void runFrames(const JointRun& run, std::size_t count, GcodeRunResult& result) {
  const std::size_t n = run.points.size();
  if (count == 0 || n == 0) return;
  const double total = run.time.t.back();
  std::size_t i = 0;
  for (std::size_t k = 0; k < count; ++k) {
    const double t =
        count == 1 ? 0.0 : total * static_cast<double>(k) / static_cast<double>(count - 1);
    while (i + 1 < n && run.time.t[i + 1] <= t) ++i;
    if (!result.frame_index.empty() && result.frame_index.back() == i) continue;
    result.frame_t.push_back(run.time.t[i]);
    result.frame_index.push_back(i);
    result.frames.push_back(run.frame_at(i));
  }
}

}  // namespace pkm::workflow::detail
