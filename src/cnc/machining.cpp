// The machining preview: a tool swept through a height-field stock (cnc/machining.hpp).
#include "pkm/cnc/machining.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "pkm/core/error.hpp"

namespace pkm::cnc {

namespace {

/// Most tool positions one motion is cut into (a 1 km rapid at 0.1 mm steps).
constexpr double kMaxStepsPerMove = 1e7;

using XyPoint = std::array<double, 2>;

double cross2(const XyPoint& o, const XyPoint& a, const XyPoint& b) {
  return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

/// The convex hull of `p` counter-clockwise (Andrew's monotone chain).
std::vector<XyPoint> convexHull2(std::vector<XyPoint> p) {
  std::sort(p.begin(), p.end());
  if (p.size() < 3) return p;
  std::vector<XyPoint> h(2 * p.size());
  std::size_t k = 0;
  for (const XyPoint& q : p) {
    while (k >= 2 && cross2(h[k - 2], h[k - 1], q) <= 0.0) --k;
    h[k++] = q;
  }
  for (std::size_t i = p.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross2(h[k - 2], h[k - 1], p[i]) <= 0.0) --k;
    h[k++] = p[i];
  }
  h.resize(k - 1);
  return h;
}

bool insideHull(const std::vector<XyPoint>& h, const XyPoint& q) {
  if (h.size() < 3) return false;
  for (std::size_t i = 0; i < h.size(); ++i)
    if (cross2(h[i], h[(i + 1) % h.size()], q) < 0.0) return false;
  return true;
}

}  // namespace

void MachiningOptions::validate() const {
  if (!(std::isfinite(max_step) && max_step >= 0.0))
    throw InvalidArgument(fmt::format("machining: the step must be >= 0 mm (got {})", max_step));
  if (!(std::isfinite(collision_depth) && collision_depth >= 0.0))
    throw InvalidArgument("machining: the collision depth must be >= 0 mm");
  if (max_changes == 0) throw InvalidArgument("machining: max_changes must be > 0");
  for (std::size_t k = 0; k < frame_times.size(); ++k)
    if (!std::isfinite(frame_times[k]) || (k > 0 && !(frame_times[k] > frame_times[k - 1])))
      throw InvalidArgument("machining: the frame times must be finite and increasing");
}

MachiningSimulator::MachiningSimulator(const StockShape& stock,
                                       double cell,
                                       MachiningOptions options)
    : field_(stock, cell), options_(std::move(options)) {
  options_.validate();
  stamp_.assign(field_.heights().size(), 0);
  result_.initial_volume = field_.volume();
}

void MachiningSimulator::setTool(const CuttingTool& tool) {
  tool.validate();
  tool_ = tool;
}

void MachiningSimulator::moveTo(const ToolPose& pose, double t, std::size_t line, bool rapid) {
  if (!placed_) {
    placed_ = true;
    at_ = pose;
    t_ = t;
    rapid_removed_.clear();
    cutAt(pose, t, line, rapid);
    return;
  }
  double dist2 = 0.0, dot = 0.0;
  for (std::size_t i = 0; i < 3; ++i) {
    dist2 += (pose.tip[i] - at_.tip[i]) * (pose.tip[i] - at_.tip[i]);
    dot += pose.axis[i] * at_.axis[i];
  }
  const double angle = std::acos(std::clamp(dot, -1.0, 1.0));
  const double sweep = std::max(std::sqrt(dist2), angle * (tool_.length + tool_.holder_length));
  const double step = options_.max_step > 0.0 ? options_.max_step : field_.cell() / 2.0;
  const double n = std::clamp(std::ceil(sweep / step), 1.0, kMaxStepsPerMove);
  const ToolPose from = at_;
  const double t0 = t_;
  rapid_removed_.clear();
  for (double s = 1.0; s <= n; s += 1.0) {
    const double f = s / n;
    ToolPose p;
    double norm = 0.0;
    for (std::size_t i = 0; i < 3; ++i) {
      p.tip[i] = from.tip[i] + f * (pose.tip[i] - from.tip[i]);
      p.axis[i] = from.axis[i] + f * (pose.axis[i] - from.axis[i]);
      norm += p.axis[i] * p.axis[i];
    }
    if (norm < 1e-12)
      p.axis = from.axis;  // opposite axes: keep the old one through the flip
    else
      for (double& a : p.axis) a /= std::sqrt(norm);
    cutAt(s == n ? pose : p, t0 + f * (t - t0), line, rapid);
  }
  at_ = pose;
  t_ = t;
}

void MachiningSimulator::cutAt(const ToolPose& pose, double t, std::size_t line, bool rapid) {
  closeFramesUpTo(t);
  ++result_.positions;
  const ToolSolid solid = toolSolid(tool_, pose);
  const double bottom = solid.bottom();
  const double eps = options_.collision_depth;
  if (bottom < field_.bottom() - eps) event("table", line, t, pose, field_.bottom() - bottom);
  if (bottom < field_.top()) {
    const auto box = solid.footprint(false);
    double deepest = 0.0;
    field_.forEachCell(box[0], box[1], box[2], box[3], [&](std::size_t k, double x, double y) {
      const double z = solid.cutterZ(x, y);
      if (!(z < field_.height(k))) return;
      const double d = field_.lower(k, z);
      if (d <= 0.0) return;
      record(k);
      if (rapid) deepest = std::max(deepest, rapid_removed_[k] += d);
    });
    if (rapid && deepest > eps) event("rapid", line, t, pose, deepest);
  }
  if (solid.holderBottom() >= field_.top()) return;
  const auto box = solid.footprint(true);
  double deepest = 0.0;
  field_.forEachCell(box[0], box[1], box[2], box[3], [&](std::size_t k, double x, double y) {
    deepest = std::max(deepest, static_cast<double>(field_.height(k)) - solid.holderZ(x, y));
  });
  if (deepest > eps) event("holder", line, t, pose, deepest);
}

void MachiningSimulator::checkPart(const std::string& kind,
                                   const std::vector<std::array<double, 3>>& points,
                                   double t,
                                   std::size_t line) {
  if (points.empty()) return;
  double low = points[0][2];
  std::array<double, 3> c{}, n{};
  std::vector<XyPoint> xy;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& a = points[i];
    const auto& b = points[(i + 1) % points.size()];
    low = std::min(low, a[2]);
    for (std::size_t d = 0; d < 3; ++d) c[d] += a[d] / static_cast<double>(points.size());
    n[0] += (a[1] - b[1]) * (a[2] + b[2]);  // Newell's normal of the polygon
    n[1] += (a[2] - b[2]) * (a[0] + b[0]);
    n[2] += (a[0] - b[0]) * (a[1] + b[1]);
    xy.push_back({a[0], a[1]});
  }
  const ToolPose where{{c[0], c[1], c[2]}, {0.0, 0.0, 1.0}};
  const double eps = options_.collision_depth;
  if (low < field_.bottom() - eps) event("table", line, t, where, field_.bottom() - low);
  if (low >= field_.top() || std::abs(n[2]) < 1e-9) return;
  const std::vector<XyPoint> h = convexHull2(xy);
  double x0 = xy[0][0], x1 = x0, y0 = xy[0][1], y1 = y0;
  for (const XyPoint& p : xy) {
    x0 = std::min(x0, p[0]);
    x1 = std::max(x1, p[0]);
    y0 = std::min(y0, p[1]);
    y1 = std::max(y1, p[1]);
  }
  double deepest = 0.0;
  field_.forEachCell(x0, y0, x1, y1, [&](std::size_t k, double x, double y) {
    if (!insideHull(h, {x, y})) return;
    const double z = c[2] - (n[0] * (x - c[0]) + n[1] * (y - c[1])) / n[2];
    deepest = std::max(deepest, static_cast<double>(field_.height(k)) - z);
  });
  if (deepest > eps) event(kind, line, t, where, deepest);
}

void MachiningSimulator::record(std::size_t k) {
  if (options_.frame_times.empty() || !result_.frames_complete) return;
  const auto frame = static_cast<std::uint32_t>(next_frame_ + 1);
  if (stamp_[k] == frame) return;
  stamp_[k] = frame;
  pending_.push_back(static_cast<std::uint32_t>(k));
}

void MachiningSimulator::closeFramesUpTo(double t) {
  const std::vector<double>& times = options_.frame_times;
  while (next_frame_ < times.size() && times[next_frame_] < t) {
    StockFrame f;
    f.t = times[next_frame_];
    if (result_.frames_complete && changes_ + pending_.size() > options_.max_changes)
      result_.frames_complete = false;
    if (result_.frames_complete) {
      changes_ += pending_.size();
      f.cells = pending_;
      f.heights.reserve(pending_.size());
      for (const std::uint32_t k : pending_) f.heights.push_back(field_.height(k));
      result_.frames.push_back(std::move(f));
    }
    pending_.clear();
    ++next_frame_;
  }
}

void MachiningSimulator::event(
    const std::string& kind, std::size_t line, double t, const ToolPose& pose, double depth) {
  ++result_.event_counts[kind];
  const auto key = std::make_pair(kind, line);
  const auto it = event_index_.find(key);
  if (it == event_index_.end()) {
    if (result_.events.size() >= options_.max_events) return;
    event_index_.emplace(key, result_.events.size());
    result_.events.push_back({kind, line, t, pose.tip, depth, 1});
    return;
  }
  MachiningEvent& e = result_.events[it->second];
  ++e.count;
  if (depth > e.depth) {
    e.depth = depth;
    e.t = t;
    e.tip = pose.tip;
  }
}

MachiningResult MachiningSimulator::finish() {
  closeFramesUpTo(std::numeric_limits<double>::infinity());
  result_.final_volume = field_.volume();
  return std::move(result_);
}

}  // namespace pkm::cnc
