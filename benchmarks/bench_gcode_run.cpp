// `pkm gcode run` throughput: joint-space conversion (IK of every interpolated point of the
// default hexapod), interpolation of a spiral program, the cycle-time model and the path checks,
// reported as points per second (items/s), and the same for the built-in Exechon (both
// orientation modes). Target: >= 2e6 points/s per core for the conversion.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "pkm/cnc/cycle_time.hpp"
#include "pkm/cnc/exechon_path.hpp"
#include "pkm/cnc/exechon_path_checks.hpp"
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

const kin::ExechonModel& exechon() {
  static const kin::ExechonModel m = pkm::io::loadExechonMachine("mxt700s-like").model;
  return m;
}

/// 200 000 points on a circle of radius 100 mm in the Exechon's PKM frame, `step_mm` apart, rising
/// 50 mm, with a turning tool vector (A ±15° once per turn, C over 30°).
std::vector<PathPoint> exechonCircle(double step_mm) {
  constexpr std::size_t n = 200'000;
  std::vector<PathPoint> v(n);
  const double turn = step_mm / 100.0;  // rad per point
  for (std::size_t i = 0; i < n; ++i) {
    const double u = static_cast<double>(i) / n, a = turn * static_cast<double>(i);
    v[i].line = i + 1;
    v[i].pos = {100 * std::cos(a), 100 * std::sin(a), 50 * u, 15 * std::sin(a), 0, 30 * u};
    v[i].kind = MoveKind::kLinear;
    v[i].feed = 3000;
  }
  return v;
}

const std::vector<PathPoint>& exechonCircle() {
  static const std::vector<PathPoint> pts = exechonCircle(0.01);
  return pts;
}

/// Converts `pts` with a fresh converter per iteration (Arg 0: vector, 1: axes).
void runExechonConversion(benchmark::State& state, const std::vector<PathPoint>& pts) {
  const auto mode =
      state.range(0) == 0 ? ExechonOrientation::kToolVector : ExechonOrientation::kWristAxes;
  std::vector<ExechonPathSample> out;
  for (auto _ : state) {
    ExechonJointConverter conv(exechon(), mode);
    conv.solveAll(pts, out);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetLabel(mode == ExechonOrientation::kToolVector ? "vector" : "axes");
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(pts.size()));
}

/// Exechon conversion: tool IK by continuity (vector: A/C give the tool vector; axes: A/C are the
/// wrist readings and the tripod parameters are found by Newton's method from an extrapolated
/// start).
void BM_ExechonJointConversion(benchmark::State& state) {
  runExechonConversion(state, exechonCircle());
}
BENCHMARK(BM_ExechonJointConversion)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

/// As above with 1 mm between points, about the step `gcode run` takes on the mxt700s-like at
/// its default 0.01 mm chordal tolerance (max step 3.6 mm there). Axes mode takes one Newton step
/// per point on both circles.
void BM_ExechonJointConversionCoarse(benchmark::State& state) {
  static const std::vector<PathPoint> pts = exechonCircle(1.0);
  runExechonConversion(state, pts);
}
BENCHMARK(BM_ExechonJointConversionCoarse)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void BM_ExechonCheckPath(benchmark::State& state) {
  std::vector<PathPoint> pts(exechonCircle().begin(), exechonCircle().begin() + 100'000);
  ExechonJointConverter conv(exechon(), ExechonOrientation::kToolVector);
  std::vector<ExechonPathSample> samples;
  conv.solveAll(pts, samples);
  const JointRateLimits limits = exechonRateLimits(MotionLimits{}, 180, 1800);
  for (auto _ : state)
    benchmark::DoNotOptimize(checkExechonPath(exechon(), pts, samples, limits).points);
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(pts.size()));
}
BENCHMARK(BM_ExechonCheckPath)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
