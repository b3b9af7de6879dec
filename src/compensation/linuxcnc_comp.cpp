#include "pkm/compensation/linuxcnc_comp.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "number_text.hpp"
#include "pkm/core/error.hpp"

namespace pkm::compensation {

void LinuxcncCompFile::validate() const {
  PKM_CHECK(type == 0 || type == 1, "COMP_FILE_TYPE must be 0 or 1, got {}", type);
  PKM_CHECK(!nominal.empty(), "a LinuxCNC compensation file needs at least one row");
  PKM_CHECK(nominal.size() <= kLinuxcncMaxRows,
            "a LinuxCNC compensation file holds at most {} rows (EMCMOT_COMP_SIZE), got {}",
            kLinuxcncMaxRows,
            nominal.size());
  PKM_CHECK(forward.size() == nominal.size() && reverse.size() == nominal.size(),
            "LinuxCNC compensation columns differ in size");
  for (std::size_t i = 0; i < nominal.size(); ++i) {
    PKM_CHECK(std::isfinite(nominal[i]) && std::isfinite(forward[i]) && std::isfinite(reverse[i]),
              "LinuxCNC compensation row {} is not finite",
              i);
    PKM_CHECK(i == 0 || nominal[i] > nominal[i - 1],
              "LinuxCNC compensation nominal values must increase (row {})",
              i);
  }
}

double LinuxcncCompFile::trim(std::size_t i, int direction) const {
  const double v = direction > 0 ? forward[i] : reverse[i];
  return type == 0 ? nominal[i] - v : v;  // usrmotintf.cc: type 0 stores actual positions
}

LinuxcncCompFile linuxcncCompFromTable(const AxisErrorTable& table, int type) {
  table.validate();
  PKM_CHECK(type == 0 || type == 1, "COMP_FILE_TYPE must be 0 or 1, got {}", type);
  PKM_CHECK(table.size() <= kLinuxcncMaxRows,
            "axis table '{}' has {} rows, LinuxCNC takes at most {}: resample it (fitToTarget)",
            table.axis,
            table.size(),
            kLinuxcncMaxRows);
  const StoredValue stored = type == 0 ? StoredValue::kActualPosition : StoredValue::kCorrection;
  LinuxcncCompFile f;
  f.type = type;
  f.nominal = table.nominal;
  for (std::size_t i = 0; i < table.size(); ++i) {
    f.forward.push_back(storedValue(stored, table.nominal[i], table.error_up[i]));
    f.reverse.push_back(storedValue(stored, table.nominal[i], table.error_down[i]));
  }
  f.validate();
  return f;
}

std::string writeLinuxcncComp(const LinuxcncCompFile& file) {
  file.validate();
  std::string out;
  for (std::size_t i = 0; i < file.nominal.size(); ++i) {
    out += fmt::format("{} {} {}\n",
                       detail::shortestText(file.nominal[i]),
                       detail::shortestText(file.forward[i]),
                       detail::shortestText(file.reverse[i]));
  }
  return out;
}

namespace {

/// Parses one whitespace-separated token as a finite double; false if it is not one.
bool parseNumber(const std::string& token, double& value) {
  const char* begin = token.c_str();
  char* end = nullptr;
  errno = 0;
  value = std::strtod(begin, &end);
  return end != begin && *end == '\0' && errno != ERANGE && std::isfinite(value);
}

}  // namespace

LinuxcncCompFile parseLinuxcncComp(const std::string& text, const std::string& source, int type) {
  PKM_CHECK(type == 0 || type == 1, "COMP_FILE_TYPE must be 0 or 1, got {}", type);
  LinuxcncCompFile f;
  f.type = type;
  std::istringstream in(text);
  std::size_t line_no = 0, blank_since = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream fields(line);
    std::vector<std::string> tokens;
    for (std::string t; fields >> t;) tokens.push_back(t);
    if (tokens.empty()) {
      if (blank_since == 0) blank_since = line_no;
      continue;
    }
    if (blank_since != 0) {
      throw IoError(locate(
          source, blank_since, "blank line before more rows (LinuxCNC stops loading at it)"));
    }
    double v[3] = {0.0, 0.0, 0.0};
    if (tokens.size() != 3 || !parseNumber(tokens[0], v[0]) || !parseNumber(tokens[1], v[1]) ||
        !parseNumber(tokens[2], v[2])) {
      throw IoError(locate(source,
                           line_no,
                           fmt::format("expected three numbers 'nominal forward reverse', got "
                                       "'{}' (LinuxCNC stops loading at such a line)",
                                       line)));
    }
    if (!f.nominal.empty() && !(v[0] > f.nominal.back())) {
      throw IoError(locate(source,
                           line_no,
                           fmt::format("nominal {} does not increase (previous {})",
                                       tokens[0],
                                       detail::shortestText(f.nominal.back()))));
    }
    if (f.nominal.size() == kLinuxcncMaxRows) {
      throw IoError(locate(
          source, line_no, fmt::format("more than {} rows (EMCMOT_COMP_SIZE)", kLinuxcncMaxRows)));
    }
    f.nominal.push_back(v[0]);
    f.forward.push_back(v[1]);
    f.reverse.push_back(v[2]);
  }
  if (f.nominal.empty()) throw IoError(locate(source, 0, "no compensation rows"));
  return f;
}

LinuxcncCompFile readLinuxcncComp(const std::string& path, int type) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(locate(path, 0, "cannot open file"));
  std::ostringstream text;
  text << in.rdbuf();
  return parseLinuxcncComp(text.str(), path, type);
}

double applyLinuxcncComp(const LinuxcncCompFile& file, double commanded, int direction) {
  PKM_CHECK(std::isfinite(commanded), "applyLinuxcncComp: commanded position is not finite");
  PKM_CHECK(direction == 1 || direction == -1, "applyLinuxcncComp: direction must be +1 or -1");
  const std::vector<double>& x = file.nominal;
  const std::size_t n = x.size();
  if (commanded <= x.front()) return commanded + file.trim(0, direction);
  if (commanded >= x.back()) return commanded + file.trim(n - 1, direction);
  std::size_t lo = 0;
  while (x[lo + 1] <= commanded) ++lo;  // control.c walks the entries the same way
  const double t0 = file.trim(lo, direction), t1 = file.trim(lo + 1, direction);
  const double slope = (t1 - t0) / (x[lo + 1] - x[lo]);
  return commanded + t0 + slope * (commanded - x[lo]);
}

}  // namespace pkm::compensation
