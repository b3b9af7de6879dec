// Google Benchmark: the readers every analysis and `pkm hexapod fk` go through, on generated text
// in memory (no disk): io::TextTable on a million two-column rows of 6-decimal coordinates, as a
// CMM exports a scanned ring (target: parsed and every number read in well under 0.2 s), and
// io::CsvReader on 100 000 six-column rows of 17-digit strut lengths, as `pkm hexapod ik` writes
// them.
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "pkm/io/csv.hpp"
#include "pkm/io/named_text.hpp"
#include "pkm/io/number_format.hpp"
#include "pkm/io/text_table.hpp"
#include "support/tolerances.hpp"

namespace {

std::string ringText(std::size_t n) {
  std::mt19937 rng(pkm::test::kSeed);
  std::normal_distribution<double> noise(0.0, 1e-3);
  std::string text = "x,y\n";
  text.reserve(n * 24);
  for (std::size_t k = 0; k < n; ++k) {
    const double t = 2.0 * std::numbers::pi * static_cast<double>(k) / static_cast<double>(n);
    const double r = 50.0 + 0.005 * std::cos(3.0 * t) + noise(rng);
    fmt::format_to(std::back_inserter(text),
                   "{:.6f},{:.6f}\n",
                   12.3 + r * std::cos(t),
                   -4.56 + r * std::sin(t));
  }
  return text;
}

std::string strutText(std::size_t n) {
  std::mt19937 rng(pkm::test::kSeed);
  std::uniform_real_distribution<double> u(25.0, 35.0);
  std::string text = "l0,l1,l2,l3,l4,l5\n";
  for (std::size_t k = 0; k < n; ++k) {
    for (int i = 0; i < 6; ++i) {
      if (i > 0) text += ',';
      pkm::io::appendNumber(text, u(rng));
    }
    text += '\n';
  }
  return text;
}

void BM_TextTableTwoColumns(benchmark::State& state) {
  const std::string text = ringText(static_cast<std::size_t>(state.range(0)));
  const std::array<std::size_t, 2> cols = {0, 1};
  for (auto _ : state) {
    const pkm::io::TextTable table = pkm::io::TextTable::parse(text, "ring.csv");
    double sum = 0.0;
    std::array<double, 2> xy{};
    for (std::size_t r = 0; r < table.rows(); ++r) {
      table.numbers(r, cols, xy);
      sum += xy[0] + xy[1];
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
  state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(text.size()));
}
BENCHMARK(BM_TextTableTwoColumns)->Arg(1000000)->Unit(benchmark::kMillisecond);

void BM_CsvReaderStrutLengths(benchmark::State& state) {
  const std::string text = strutText(static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) {
    pkm::io::CsvReader reader(pkm::io::NamedText{"lengths.csv", text},
                              {"l0", "l1", "l2", "l3", "l4", "l5"});
    std::array<double, 6> row{};
    double sum = 0.0;
    while (reader.next(row)) sum += row[0] + row[5];
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
  state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(text.size()));
}
BENCHMARK(BM_CsvReaderStrutLengths)->Arg(100000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
