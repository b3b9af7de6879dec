// Google Benchmark: Exechon tripod IK (closed form from S), full tool IK (tool pose -> legs + C, A
// by continuity), tripod FK warm start (one servo step on a smooth 1 kHz path) and cold start (from
// home). Argument 0: Zoppi's closed form; 1: leg B's base-joint offsets (l12B 0.7, l23B -0.45 mm,
// solved numerically).
#include <benchmark/benchmark.h>

#include <cstdint>
#include <numbers>
#include <vector>

#include "kinematics/exechon_sample_models.hpp"
#include "pkm/kinematics/exechon_fk.hpp"
#include "pkm/kinematics/exechon_ik.hpp"
#include "pkm/kinematics/exechon_wrist.hpp"

namespace {

using namespace pkm::kinematics;

/// A smooth path of 10000 configurations around home, with its wrist points, tool poses and joints.
struct PathFixture {
  ExechonModel model = pkm::test::machineModel();
  explicit PathFixture(bool offsets)
      : PathFixture(offsets ? withOffsets() : pkm::test::machineModel()) {}
  static ExechonModel withOffsets() {
    ExechonModel m = pkm::test::machineModel();
    m.tripod.l12B = 0.7;
    m.tripod.l23B = -0.45;
    return m;
  }
  std::vector<ExechonConfiguration> configs;
  std::vector<Eigen::Vector3d> zoppi_S;
  std::vector<ExechonToolPose> tools;
  std::vector<ExechonLegVector> readings;
  explicit PathFixture(const ExechonModel& m) : model(m) {
    ExechonData data(model);
    const int n = 10000;
    for (int k = 0; k < n; ++k) {
      const double t = 2 * std::numbers::pi * k / n;
      ExechonConfiguration c = model.home;
      c.e += Eigen::Vector3d(0.15 * std::sin(t), 0.1 * std::sin(2 * t), 100 * (1 - std::cos(t)));
      c.c += 2 * std::sin(t);
      c.a += 0.3 * std::sin(3 * t);
      evaluateConfiguration(model, data, c);
      configs.push_back(c);
      zoppi_S.push_back(data.zoppi_p_S);
      tools.push_back({data.world_p_tool, data.world_u_tool});
      readings.push_back(data.readings);
    }
  }
};

const PathFixture& fixture(std::int64_t offsets = 0) {
  static const PathFixture zoppi(false), legb(true);
  return offsets != 0 ? legb : zoppi;
}

void BM_ExechonTripodIk(benchmark::State& state) {
  const auto& f = fixture(state.range(0));
  state.SetLabel(state.range(0) != 0 ? "legB-offsets" : "zoppi");
  ExechonData data(f.model);
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(tripodInverseKinematics(f.model, data, f.zoppi_S[k]));
    benchmark::DoNotOptimize(data.readings);
    k = (k + 1) % f.zoppi_S.size();
  }
}
BENCHMARK(BM_ExechonTripodIk)->Arg(0)->Arg(1);

void BM_ExechonToolIk(benchmark::State& state) {
  const auto& f = fixture(state.range(0));
  state.SetLabel(state.range(0) != 0 ? "legB-offsets" : "zoppi");
  ExechonData data(f.model);
  ExechonConfiguration previous = f.configs.back();
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(toolInverseKinematics(f.model, data, f.tools[k], previous));
    previous = configurationOf(data);
    k = (k + 1) % f.tools.size();
  }
}
BENCHMARK(BM_ExechonToolIk)->Arg(0)->Arg(1);

void BM_ExechonTripodIkWithJacobian(benchmark::State& state) {
  const auto& f = fixture();
  ExechonData data(f.model);
  std::size_t k = 0;
  for (auto _ : state) {
    tripodInverseKinematics(f.model, data, f.zoppi_S[k]);
    benchmark::DoNotOptimize(computeTripodJacobian(f.model, data));
    k = (k + 1) % f.zoppi_S.size();
  }
}
BENCHMARK(BM_ExechonTripodIkWithJacobian);

void BM_ExechonTripodFkWarm(benchmark::State& state) {
  const auto& f = fixture(state.range(0));
  state.SetLabel(state.range(0) != 0 ? "legB-offsets" : "zoppi");
  ExechonData data(f.model);
  Eigen::Vector3d seed = f.configs.back().e;
  std::size_t k = 0;
  for (auto _ : state) {
    const FkSummary s = tripodForwardKinematics(f.model, data, f.readings[k], seed);
    benchmark::DoNotOptimize(s);
    seed = data.e;
    k = (k + 1) % f.readings.size();
  }
}
BENCHMARK(BM_ExechonTripodFkWarm)->Arg(0)->Arg(1);

void BM_ExechonTripodFkCold(benchmark::State& state) {
  const auto& f = fixture();
  ExechonData data(f.model);
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(tripodForwardKinematics(f.model, data, f.readings[k], f.model.home.e));
    k = (k + 1) % f.readings.size();
  }
}
BENCHMARK(BM_ExechonTripodFkCold);

}  // namespace

BENCHMARK_MAIN();
