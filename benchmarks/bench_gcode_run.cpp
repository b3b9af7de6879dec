// `pkm gcode run` throughput: joint-space conversion (IK of every interpolated point of the
// default hexapod), interpolation of a spiral program, the cycle-time model and the path checks,
// reported as points per second (items/s). Target: >= 2e6 points/s per core for the conversion.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "pkm/cnc/cycle_time.hpp"
#include "pkm/cnc/joint_checks.hpp"
#include "pkm/cnc/joint_path.hpp"
#include "pkm/cnc/path_interpolation.hpp"
#include "pkm/io/machine_loader.hpp"

namespace {

using namespace pkm::cnc;
namespace kin = pkm::kinematics;

constexpr std::size_t kPoints = 1'000'000;
constexpr double kTol = 0.01;  // mm

const kin::HexapodModel& model() {
  static const kin::HexapodModel m = pkm::io::builtinMachine("default").model;
  return m;
}

/// A tilted spiral around home: X/Y on a growing circle, Z and A/B/C varying (all reachable).
const std::vector<PathPoint>& spiral() {
  static const std::vector<PathPoint> pts = [] {
    std::vector<PathPoint> v(kPoints);
    for (std::size_t i = 0; i < kPoints; ++i) {
      const double u = static_cast<double>(i) / kPoints, a = 200.0 * u;
      v[i].line = i + 1;
      v[i].pos = {100 * u * std::cos(a),
                  100 * u * std::sin(a),
                  200 - 50 * u,
                  5 * std::sin(a),
                  5 * std::cos(a),
                  20 * u};
      v[i].kind = MoveKind::kLinear;
      v[i].feed = 3000;
    }
    return v;
  }();
  return pts;
}

void BM_JointConversion(benchmark::State& state) {
  HexapodJointConverter conv(model());
  const auto& pts = spiral();
  std::vector<kin::StrutVector> q;
  for (auto _ : state) {
    conv.solveAll(pts, q);
    benchmark::DoNotOptimize(q.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(pts.size()));
}
BENCHMARK(BM_JointConversion)->Unit(benchmark::kMillisecond);

void BM_InterpolateArcs(benchmark::State& state) {
  // Full circles of radius 50 at the tolerance: the sagitta rule's point count.
  Move m;
  m.kind = MoveKind::kArc;
  m.end = {50, 0, 200, 0, 0, 0};
  m.centre = {0, 0, std::nan("")};
  m.turns = 1;
  m.feed = 1000;
  std::vector<PathPoint> out;
  out.reserve(1 << 16);
  for (auto _ : state) {
    out.clear();
    PathInterpolator cut(jointSpaceInterpolation(model(), kTol), m.end);
    for (int k = 0; k < 100; ++k) cut.append(m, 0, out);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(out.size()));
}
BENCHMARK(BM_InterpolateArcs)->Unit(benchmark::kMillisecond);

void BM_CycleTime(benchmark::State& state) {
  HexapodJointConverter conv(model());
  const auto& pts = spiral();
  std::vector<kin::StrutVector> q;
  conv.solveAll(pts, q);
  for (auto _ : state) benchmark::DoNotOptimize(estimateCycleTime(pts, q, MotionLimits{}).total);
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(pts.size()));
}
BENCHMARK(BM_CycleTime)->Unit(benchmark::kMillisecond);

void BM_CheckPath(benchmark::State& state) {
  HexapodJointConverter conv(model());
  std::vector<PathPoint> pts(spiral().begin(), spiral().begin() + 100'000);
  std::vector<kin::StrutVector> q;
  conv.solveAll(pts, q);
  for (auto _ : state) benchmark::DoNotOptimize(checkPath(model(), pts, q, MotionLimits{}).points);
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(pts.size()));
}
BENCHMARK(BM_CheckPath)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
