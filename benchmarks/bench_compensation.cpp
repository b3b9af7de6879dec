// Google Benchmark: compensation (docs/compensation.md): hexapod pose pre-distortion per pose
// (single poses seeded at the desired pose, and a path seeded with the previous correction), the
// LinuxCNC runtime model on a full 256-row table, and writing/parsing that table.
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "pkm/compensation/linuxcnc_comp.hpp"
#include "pkm/compensation/predistortion.hpp"
#include "support/sample_models.hpp"

namespace {

using namespace pkm;

/// The 6-6 test machine and a copy with ±0.5 mm joint and ±0.2 mm offset errors.
struct Models {
  kinematics::HexapodModel nominal = test::millingModel();
  kinematics::HexapodModel calibrated = nominal;
  Models() {
    std::mt19937 rng(20261122u);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (auto& s : calibrated.struts) {
      for (int k = 0; k < 3; ++k) {
        s.world_p_base[k] += 0.5 * u(rng);
        s.platform_p_joint[k] += 0.5 * u(rng);
      }
      s.length_offset += 0.2 * u(rng);
    }
  }
};

std::vector<kinematics::PoseRpy> circlePath(const kinematics::PoseRpy& home, int n) {
  std::vector<kinematics::PoseRpy> path;
  for (int i = 0; i < n; ++i) {
    const double t = 2.0 * std::numbers::pi * i / n;
    kinematics::PoseRpy p = home;
    p.position += Eigen::Vector3d(50 * std::cos(t), 50 * std::sin(t), 10 * std::sin(3 * t));
    p.rpy[0] = 0.05 * std::sin(2 * t);
    path.push_back(p);
  }
  return path;
}

void BM_PredistortSinglePose(benchmark::State& state) {
  const Models m;
  const auto path = circlePath(m.nominal.home, 1000);
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(compensation::predistort(m.nominal, m.calibrated, path[k]));
    k = (k + 1) % path.size();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}
BENCHMARK(BM_PredistortSinglePose);

void BM_PredistortPath(benchmark::State& state) {
  const Models m;
  const auto path = circlePath(m.nominal.home, 1000);
  for (auto _ : state) {
    benchmark::DoNotOptimize(compensation::predistortPath(m.nominal, m.calibrated, path));
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * 1000));
}
BENCHMARK(BM_PredistortPath);

compensation::LinuxcncCompFile fullTable() {
  compensation::AxisErrorTable t{"X", {}, {}, {}};
  for (int i = 0; i < 256; ++i) {
    t.nominal.push_back(2.0 * i);
    t.error_up.push_back(1e-3 * std::sin(0.05 * i));
    t.error_down.push_back(1e-3 * std::sin(0.05 * i) - 5e-3);
  }
  return compensation::linuxcncCompFromTable(t, 1);
}

void BM_ApplyLinuxcncComp256(benchmark::State& state) {
  const auto f = fullTable();
  double x = 0.0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(compensation::applyLinuxcncComp(f, x, 1));
    x = x > 510.0 ? 0.0 : x + 0.731;
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}
BENCHMARK(BM_ApplyLinuxcncComp256);

void BM_WriteParseLinuxcncComp256(benchmark::State& state) {
  const auto f = fullTable();
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        compensation::parseLinuxcncComp(compensation::writeLinuxcncComp(f), "bench", 1));
  }
}
BENCHMARK(BM_WriteParseLinuxcncComp256);

}  // namespace

BENCHMARK_MAIN();
