// G-code interpreter throughput on a plain generated program of 1e6 lines (G1 moves with
// three axes and a feed, some rapids and arcs): parse only, execute only, and both, reported as
// lines per second (items/s). Target: >= 1e6 lines/s for parse + execute.
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <string>

#include "pkm/cnc/interpreter.hpp"

namespace {

constexpr int kLines = 1'000'000;

const std::string& plainProgram() {
  static const std::string text = [] {
    std::string t = "G21 G90 G17 G94 F1200\n";
    t.reserve(static_cast<std::size_t>(kLines) * 40);
    for (int i = 1; i < kLines - 1; ++i) {
      const double x = (i % 1000) * 0.05;
      const double y = (i / 1000) * 0.05;
      if (i % 100 == 0)
        t += fmt::format("G0 X{:.3f} Y{:.3f} Z2.000\n", x, y);
      else if (i % 50 == 0)
        t += fmt::format("G2 X{:.3f} Y{:.3f} I0.025 J0\n", x, y);  // half circle from X - 0.05
      else
        t += fmt::format("G1 X{:.3f} Y{:.3f} Z{:.3f}\n", x, y, -0.001 * (i % 7));
    }
    t += "M2\n";
    return t;
  }();
  return text;
}

class CountingSink final : public pkm::cnc::MoveSink {
 public:
  void onMove(const pkm::cnc::Move& m) override {
    ++count;
    sum += m.end[0];
  }
  std::size_t count = 0;
  double sum = 0.0;
};

void BM_GcodeParse(benchmark::State& state) {
  const std::string& text = plainProgram();
  for (auto _ : state) {
    const pkm::cnc::Program p = pkm::cnc::Program::parse(text, "bench.ngc");
    benchmark::DoNotOptimize(p.blocks().data());
  }
  state.SetItemsProcessed(state.iterations() * kLines);
}
BENCHMARK(BM_GcodeParse)->Unit(benchmark::kMillisecond)->Iterations(3);

void BM_GcodeExecute(benchmark::State& state) {
  const pkm::cnc::Program p = pkm::cnc::Program::parse(plainProgram(), "bench.ngc");
  std::size_t moves = 0;
  for (auto _ : state) {
    pkm::cnc::Interpreter interp;
    CountingSink sink;
    interp.run(p, sink);
    moves = sink.count;
    benchmark::DoNotOptimize(sink.sum);
  }
  state.SetItemsProcessed(state.iterations() * kLines);
  state.counters["moves"] = static_cast<double>(moves);
}
BENCHMARK(BM_GcodeExecute)->Unit(benchmark::kMillisecond)->Iterations(3);

void BM_GcodeParseAndExecute(benchmark::State& state) {
  const std::string& text = plainProgram();
  for (auto _ : state) {
    const pkm::cnc::Program p = pkm::cnc::Program::parse(text, "bench.ngc");
    pkm::cnc::Interpreter interp;
    CountingSink sink;
    interp.run(p, sink);
    benchmark::DoNotOptimize(sink.sum);
  }
  state.SetItemsProcessed(state.iterations() * kLines);
}
BENCHMARK(BM_GcodeParseAndExecute)->Unit(benchmark::kMillisecond)->Iterations(3);

void BM_GcodeCsv(benchmark::State& state) {
  const pkm::cnc::Program p = pkm::cnc::Program::parse(plainProgram(), "bench.ngc");
  pkm::cnc::Interpreter interp;
  pkm::cnc::MoveCollector all;
  interp.run(p, all);
  for (auto _ : state) {
    std::string out;
    out.reserve(all.moves.size() * 64);
    for (const auto& m : all.moves) pkm::cnc::appendMoveCsv(out, m);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<long>(all.moves.size()));
}
BENCHMARK(BM_GcodeCsv)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
