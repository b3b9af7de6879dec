// The table reader against the physical limit (docs/performance.md, "Reading tables"): for one
// CSV file of numbers, the time of io::NumberTable::read (mapped, parsed in chunks on the cores)
// and of the least any reader must do — the file's bytes from the page cache (timed by the
// calling script as `cat FILE > /dev/null`) plus one std::from_chars over every number, on one
// core, of the bytes already in memory. Runs alternate; the medians are printed as
// "read S from_chars S rows N".
// Usage: read_limit FILE COLUMN... [--runs N]
#include <algorithm>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "pkm/io/mapped_file.hpp"
#include "pkm/io/number_table.hpp"

namespace {

double seconds(std::chrono::steady_clock::time_point a, std::chrono::steady_clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.size() % 2 == 1 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

/// Every number of the bytes after the first line through std::from_chars; their sum (so that the
/// work is not optimised away).
double fromCharsLoop(std::string_view bytes, std::size_t& count) {
  const char* p = bytes.data();
  const char* const end = p + bytes.size();
  p = static_cast<const char*>(std::memchr(p, '\n', bytes.size())) + 1;
  double sum = 0.0;
  count = 0;
  while (p < end) {
    double v = 0.0;
    const auto [next, ec] = std::from_chars(p, end, v);
    if (ec == std::errc()) {
      sum += v;
      ++count;
      p = next;
    }
    if (p < end) ++p;  // the separator
  }
  return sum;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: read_limit FILE COLUMN... [--runs N]\n");
    return 2;
  }
  const std::string path = argv[1];
  std::vector<pkm::io::ColumnNames> columns;
  int runs = 7;
  for (int i = 2; i < argc; ++i) {
    if (std::strcmp(argv[i], "--runs") == 0 && i + 1 < argc)
      runs = std::max(1, std::atoi(argv[++i]));
    else
      columns.push_back({argv[i]});
  }
  const pkm::io::MappedFile file = pkm::io::MappedFile::open(path);
  std::vector<double> read_s, loop_s;
  std::size_t rows = 0, numbers = 0;
  double check = 0.0;
  for (int r = 0; r < runs; ++r) {
    auto a = std::chrono::steady_clock::now();
    const pkm::io::NumberTable t = pkm::io::NumberTable::read(path, columns);
    auto b = std::chrono::steady_clock::now();
    read_s.push_back(seconds(a, b));
    rows = t.rows();
    a = std::chrono::steady_clock::now();
    check += fromCharsLoop(file.bytes(), numbers);
    b = std::chrono::steady_clock::now();
    loop_s.push_back(seconds(a, b));
  }
  std::printf("read %.6f from_chars %.6f rows %zu numbers %zu check %g\n",
              median(read_s),
              median(loop_s),
              rows,
              numbers,
              check);
  return 0;
}
