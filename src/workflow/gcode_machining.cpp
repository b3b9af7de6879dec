// The machining preview of a `gcode run` (workflow/gcode_machining.hpp).
#include "pkm/workflow/gcode_machining.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>

#include "gcode_run_detail.hpp"
#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/geometry/so3.hpp"

namespace pkm::workflow {

namespace {

/// A feed step moving less than this in XY is a plunge (mm): it does not size the auto stock's
/// top.
constexpr double kPlungeXy = 1e-6;
/// The most animation moments a request may ask for.
constexpr std::size_t kMaxMachiningFrames = 10'000;

bool finite(const double* v, std::size_t n) {
  return std::all_of(v, v + n, [](double x) { return std::isfinite(x); });
}

/// The tool in the spindle for each motion of `moves`, by the tool changes' order.
class ToolTrack {
 public:
  explicit ToolTrack(const cnc::MoveCollector& moves) : changes_(moves.tool_changes) {}
  /// The change in effect at motion `move` (nullptr: none yet, no tool).
  const cnc::ToolChangeEvent* at(std::size_t move) {
    while (next_ < changes_.size() && changes_[next_].after_moves <= move) ++next_;
    return next_ == 0 ? nullptr : &changes_[next_ - 1];
  }

 private:
  const std::vector<cnc::ToolChangeEvent>& changes_;
  std::size_t next_ = 0;
};

/// The preview's tool for tool number `number` (0: the default tool).
MachiningTool toolFor(int number,
                      std::size_t line,
                      const MachiningRequest& request,
                      const cnc::ToolTable& tools) {
  MachiningTool t;
  t.first_line = line;
  if (number == 0) {
    t.tool = request.default_tool;
    return t;
  }
  const cnc::ToolEntry* entry = tools.find(number);
  if (entry == nullptr)
    throw InvalidArgument(
        fmt::format("machining: line {}: tool T{} is not in the tool table, so its size is unknown",
                    line,
                    number));
  try {
    t.tool = cnc::cuttingToolOf(*entry, request.default_tool);
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(
        fmt::format("machining: line {}: {} (the tool table's D and Z give the preview's tool)",
                    line,
                    e.what()));
  }
  t.tip_offset = t.tool.length;
  return t;
}

/// The tool's unit axis (tip to spindle) at path point i of `run`.
std::array<double, 3> toolAxis(const detail::JointRun& run, std::size_t i) {
  const cnc::Axes& p = run.points[i].pos;
  if (run.exechon) {
    // The drawn direction is the Exechon's world_u_tool, from the spindle point towards the tool
    // point (world_p_tool = world_p_S + length·world_u_tool): the tool axis is its opposite.
    const PoseCheckRow row = run.frame_at(i);
    std::array<double, 3> u = row.tool_direction;
    const double n = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    if (n > 0.0)
      for (double& x : u) x /= -n;
    return n > 0.0 ? u : std::array<double, 3>{0.0, 0.0, 1.0};
  }
  const Eigen::Matrix3d R =
      geometry::rotationFromRpy({degToRad(p[3]), degToRad(p[4]), degToRad(p[5])});
  return {R(0, 2), R(1, 2), R(2, 2)};
}

/// The auto stock: the feed tips' box grown by the largest radius plus the margin.
cnc::StockShape autoStock(const MachiningRequest& request,
                          const detail::JointRun& run,
                          const std::vector<cnc::ToolPose>& tips,
                          double radius) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  std::array<double, 3> lo{kInf, kInf, kInf}, hi{-kInf, -kInf, -kInf};
  for (std::size_t i = 1; i < run.points.size(); ++i) {
    if (run.points[i].kind == cnc::MoveKind::kRapid) continue;
    for (std::size_t d = 0; d < 2; ++d) {
      lo[d] = std::min(lo[d], tips[i].tip[d]);
      hi[d] = std::max(hi[d], tips[i].tip[d]);
    }
    lo[2] = std::min(lo[2], tips[i].tip[2]);
    // The top: where feed moves cut sideways; a vertical feed (a plunge) starts in the air.
    const double dx = tips[i].tip[0] - tips[i - 1].tip[0], dy = tips[i].tip[1] - tips[i - 1].tip[1];
    if (i > 1 && dx * dx + dy * dy > kPlungeXy * kPlungeXy) {
      hi[2] = std::max({hi[2], tips[i].tip[2], tips[i - 1].tip[2]});
    }
  }
  if (!(lo[0] <= hi[0]))
    throw InvalidArgument(
        "machining: the program has no feed move to size the stock from; give a box or a "
        "cylinder");
  const double grow = radius + request.margin;
  cnc::StockShape s;
  s.min = {lo[0] - grow, lo[1] - grow};
  s.max = {hi[0] + grow, hi[1] + grow};
  s.bottom = lo[2] - std::max(request.margin, 1.0);
  s.top = hi[2] > s.bottom ? hi[2] : s.bottom + std::max(request.margin, 1.0);
  return s;
}

cnc::StockShape givenStock(const MachiningRequest& r) {
  cnc::StockShape s;
  if (r.stock == "box") {
    s.min = {std::min(r.box[0], r.box[3]), std::min(r.box[1], r.box[4])};
    s.max = {std::max(r.box[0], r.box[3]), std::max(r.box[1], r.box[4])};
    s.bottom = std::min(r.box[2], r.box[5]);
    s.top = std::max(r.box[2], r.box[5]);
  } else {
    s.kind = cnc::StockShape::Kind::kCylinder;
    s.centre = {r.cylinder[0], r.cylinder[1]};
    s.radius = r.cylinder[2];
    s.bottom = std::min(r.cylinder[3], r.cylinder[4]);
    s.top = std::max(r.cylinder[3], r.cylinder[4]);
  }
  s.validate();
  return s;
}

double autoCell(const cnc::StockShape& s, double cells) {
  const double side = s.kind == cnc::StockShape::Kind::kCylinder
                          ? 2.0 * s.radius
                          : std::max(s.max[0] - s.min[0], s.max[1] - s.min[1]);
  return std::max(side / cells, kMinAutoCell);
}

}  // namespace

void MachiningRequest::validate() const {
  if (stock != "auto" && stock != "box" && stock != "cylinder")
    throw InvalidArgument(
        fmt::format("machining: unknown stock '{}' (auto, box or cylinder)", stock));
  if (!finite(box.data(), box.size()) || !finite(cylinder.data(), cylinder.size()))
    throw InvalidArgument("machining: the stock's dimensions must be finite numbers");
  if (!(std::isfinite(margin) && margin >= 0.0))
    throw InvalidArgument("machining: the margin must be >= 0 mm");
  if (!(std::isfinite(cell) && cell >= 0.0))
    throw InvalidArgument("machining: the cell size must be >= 0 mm (0: automatic)");
  if (!(auto_cells >= 10.0 && auto_cells <= 2000.0))
    throw InvalidArgument("machining: auto_cells must be from 10 to 2000");
  if (frames > kMaxMachiningFrames)
    throw InvalidArgument(
        fmt::format("machining: at most {} frames (got {})", kMaxMachiningFrames, frames));
  if (max_changes == 0) throw InvalidArgument("machining: max_changes must be > 0");
  default_tool.validate();
}

void setStock(MachiningRequest& request, std::string_view spec) {
  const std::size_t colon = spec.find(':');
  const std::string_view kind = spec.substr(0, colon);
  const auto bad = [spec]() {
    return InvalidArgument(fmt::format(
        "--stock '{}': give auto, box:X0,Y0,Z0,X1,Y1,Z1 or cylinder:CX,CY,R,Z0,Z1 (mm)", spec));
  };
  if (kind == "auto" && colon == std::string_view::npos) {
    request.stock = "auto";
    return;
  }
  if ((kind != "box" && kind != "cylinder") || colon == std::string_view::npos) throw bad();
  std::vector<double> v;
  std::string_view rest = spec.substr(colon + 1);
  while (true) {
    const std::size_t comma = rest.find(',');
    const std::string field(rest.substr(0, comma));
    std::size_t used = 0;
    double x = 0.0;
    try {
      x = std::stod(field, &used);
    } catch (const std::exception&) {
      throw bad();
    }
    if (used != field.size() || !std::isfinite(x)) throw bad();
    v.push_back(x);
    if (comma == std::string_view::npos) break;
    rest = rest.substr(comma + 1);
  }
  request.stock = std::string(kind);
  if (kind == "box" && v.size() == 6)
    std::copy(v.begin(), v.end(), request.box.begin());
  else if (kind == "cylinder" && v.size() == 5)
    std::copy(v.begin(), v.end(), request.cylinder.begin());
  else
    throw bad();
}

std::string machiningText(const MachiningReport& r) {
  std::string out = fmt::format(
      "machining: stock {}, {} x {} cells of {:.3g} mm\n", r.stock.describe(), r.nx, r.ny, r.cell);
  for (const MachiningTool& t : r.tools)
    out += fmt::format(
        "  tool T{}: {} end, diameter {:g} mm, tip {:g} mm below the controlled "
        "point (from line {})\n",
        t.tool.number,
        cnc::toString(t.tool.end),
        t.tool.diameter,
        t.tip_offset,
        t.first_line);
  out += fmt::format("  removed {:.1f} mm3 of {:.1f} mm3 ({} tool positions)\n",
                     r.result.initial_volume - r.result.final_volume,
                     r.result.initial_volume,
                     r.result.positions);
  if (r.result.events.empty()) return out + "  no collision: rapids, holder, platform, table\n";
  for (const cnc::MachiningEvent& e : r.result.events)
    out += fmt::format(
        "  COLLISION {} line {}: {:.3f} mm deep at tip X {:.3f} Y {:.3f} Z {:.3f}, "
        "t {:.2f} s ({} positions)\n",
        e.kind,
        e.line,
        e.depth,
        e.tip[0],
        e.tip[1],
        e.tip[2],
        e.t,
        e.count);
  return out;
}

std::size_t MachiningReport::collisions() const {
  std::size_t n = 0;
  for (const auto& [kind, count] : result.event_counts) n += count;
  return n;
}

namespace detail {

MachiningReport runMachining(const MachiningRequest& request,
                             const JointRun& run,
                             const cnc::MoveCollector& moves,
                             const cnc::ToolTable& tools,
                             const std::vector<std::size_t>& path_index,
                             const RunControl& control) {
  const auto start = std::chrono::steady_clock::now();
  MachiningReport report;
  // The tool and its tip at every path point (point 0, where the machine happened to be before
  // the program, is not part of the program's motion).
  const std::size_t n = run.points.size();
  std::vector<cnc::ToolPose> poses(n);
  std::vector<int> tool_of(n, 0);
  std::map<int, MachiningTool> used;
  ToolTrack track(moves);
  double radius = 0.0;
  for (std::size_t i = 1; i < n; ++i) {
    const cnc::PathPoint& p = run.points[i];
    const cnc::ToolChangeEvent* change = track.at(p.move);
    const int number = change == nullptr ? 0 : change->tool;
    auto it = used.find(number);
    if (it == used.end()) it = used.emplace(number, toolFor(number, p.line, request, tools)).first;
    tool_of[i] = number;
    radius = std::max(radius, it->second.tool.diameter / 2.0);
    poses[i].axis = toolAxis(run, i);
    for (std::size_t d = 0; d < 3; ++d)
      poses[i].tip[d] = p.pos[d] - it->second.tip_offset * poses[i].axis[d];
  }
  report.stock =
      request.stock == "auto" ? autoStock(request, run, poses, radius) : givenStock(request);
  report.cell = request.cell > 0.0 ? request.cell : autoCell(report.stock, request.auto_cells);
  cnc::MachiningOptions options;
  options.max_changes = request.max_changes;
  const double total = run.time.t.empty() ? 0.0 : run.time.t.back();
  for (std::size_t k = 1; k <= request.frames && total > 0.0; ++k)
    options.frame_times.push_back(total * static_cast<double>(k) /
                                  static_cast<double>(request.frames));
  cnc::MachiningSimulator sim(report.stock, report.cell, options);
  report.nx = sim.stock().nx();
  report.ny = sim.stock().ny();
  report.x0 = sim.stock().x0();
  report.y0 = sim.stock().y0();
  report.initial = sim.stock().heights();
  const double mm = run.len == "inch" ? 25.4 : 1.0;  // the drawing is in the machine's unit
  int current = -1;
  for (std::size_t i = 1; i < n; ++i) {
    if (i % 4096 == 0) control.checkCancelled();
    if (tool_of[i] != current) {
      current = tool_of[i];
      sim.setTool(used.at(current).tool);
    }
    const cnc::PathPoint& p = run.points[i];
    sim.moveTo(poses[i], run.time.t[i], p.line, p.kind == cnc::MoveKind::kRapid);
    if (!run.frame_at) continue;
    const PoseCheckRow row = run.frame_at(i);
    if (!row.carriage.empty() || row.moving_points.empty()) continue;  // hybrid: frame P moves
    std::vector<std::array<double, 3>> platform;
    for (const WorldPoint& q : row.moving_points)
      platform.push_back({q[0] * mm, q[1] * mm, q[2] * mm});
    sim.checkPart("platform", platform, run.time.t[i], p.line);
  }
  report.heights = sim.stock().heights();
  report.result = sim.finish();
  for (const auto& [number, tool] : used) report.tools.push_back(tool);
  for (const std::size_t i : path_index) {
    const std::size_t k = std::max<std::size_t>(i, 1);  // point 0: shown where the motion starts
    report.path_tools.push_back(poses[std::min(k, n - 1)]);
    report.path_tool_numbers.push_back(tool_of[std::min(k, n - 1)]);
  }
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

}  // namespace detail

}  // namespace pkm::workflow
