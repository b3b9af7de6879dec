// Google Benchmark: least-squares circle (Kåsa start + Levenberg-Marquardt) and exact minimum-zone
// circle (Remez exchange, certified) on 1e3, 1e5 and 1e6 noisy points of a 40 mm ring with a
// 3-lobe form (target: LSC + MZC of 1 000 000 points in well under a second).
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "pkm/metrology/circle_fit.hpp"
#include "pkm/metrology/min_zone_circle.hpp"
#include "support/tolerances.hpp"

namespace {

using pkm::metrology::Point2;

std::vector<Point2> ring(std::size_t n) {
  std::mt19937 rng(pkm::test::kSeed);
  std::normal_distribution<double> noise(0.0, 0.5e-3);
  std::vector<Point2> p(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double t = 2.0 * std::numbers::pi * static_cast<double>(k) / static_cast<double>(n);
    const double r = 20.0005 + 2e-3 * std::cos(3.0 * t) + noise(rng);
    p[k] = Point2(-316.081, 247.037) + r * Point2(std::cos(t), std::sin(t));
  }
  return p;
}

void BM_LeastSquaresCircle(benchmark::State& state) {
  const auto p = ring(static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(pkm::metrology::fitCircle(p));
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

void BM_MinimumZoneCircle(benchmark::State& state) {
  const auto p = ring(static_cast<std::size_t>(state.range(0)));
  int exchanges = 0;
  for (auto _ : state) {
    const auto z = pkm::metrology::fitMinimumZoneCircle(p);
    exchanges = z.exchanges;
    benchmark::DoNotOptimize(z);
  }
  state.counters["exchanges"] = exchanges;
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

void BM_LscAndMzc(benchmark::State& state) {
  const auto p = ring(static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) {
    const auto lsc = pkm::metrology::fitCircle(p);
    pkm::metrology::MinZoneOptions opt;
    opt.start = lsc.circle.center;
    benchmark::DoNotOptimize(pkm::metrology::fitMinimumZoneCircle(p, opt));
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

}  // namespace

BENCHMARK(BM_LeastSquaresCircle)
    ->Arg(1000)
    ->Arg(100000)
    ->Arg(1000000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MinimumZoneCircle)
    ->Arg(1000)
    ->Arg(100000)
    ->Arg(1000000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LscAndMzc)->Arg(1000)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
