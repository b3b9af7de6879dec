#include "pkm/compensation/siemens_comp.hpp"

#include <fmt/format.h>

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <map>
#include <optional>
#include <sstream>

#include "number_text.hpp"
#include "pkm/core/error.hpp"

namespace pkm::compensation {
namespace {

/// |MIN + STEP·(n−1) − MAX| allowed, mm (the fixed-point text keeps 9 decimals).
constexpr double kEndTolerance = 1e-6;

bool isIdentifier(const std::string& s) {
  if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
  for (char c : s) {
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
  }
  return true;
}

void checkGrid(const std::vector<double>& values, double min, double step, double max) {
  PKM_CHECK(
      values.size() >= 2, "a compensation table needs at least 2 points, has {}", values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    PKM_CHECK(std::isfinite(values[i]), "compensation value {} is not finite", i);
  }
  PKM_CHECK(std::isfinite(min) && std::isfinite(max) && std::isfinite(step) && step > 0.0,
            "MIN, MAX must be finite and STEP > 0 (MIN {}, STEP {}, MAX {})",
            min,
            step,
            max);
  const double end = min + step * static_cast<double>(values.size() - 1);
  PKM_CHECK(std::abs(end - max) <= kEndTolerance,
            "MIN + STEP·(points − 1) = {} differs from MAX = {}",
            end,
            max);
}

double gridValue(
    const std::vector<double>& values, double min, double step, double max, bool modulo, double x) {
  PKM_CHECK(!std::isnan(x), "compensation position is NaN");
  if (modulo && std::isfinite(x)) {
    const double period = max - min;
    x = min + std::fmod(std::fmod(x - min, period) + period, period);
  }
  if (x <= min) return values.front();
  if (x >= max) return values.back();
  const double u = (x - min) / step;
  auto i = static_cast<std::size_t>(std::floor(u));
  if (i >= values.size() - 1) i = values.size() - 2;
  const double t = u - static_cast<double>(i);
  return values[i] + t * (values[i + 1] - values[i]);
}

/// Grid of an evenly spaced position column.
struct Grid {
  double min, step, max;
};

Grid gridOf(const std::vector<double>& positions) {
  PKM_CHECK(isEvenlySpaced(positions),
            "SINUMERIK compensation tables need equidistant points: resample (fitToTarget)");
  const double min = positions.front(), max = positions.back();
  return {min, (max - min) / static_cast<double>(positions.size() - 1), max};
}

std::string num(double v) { return detail::fixedText(v); }

// --- part-program reader -------------------------------------------------------------------

/// One `$NAME[i,j,...]=value` line.
struct Assignment {
  std::string name;                  ///< without '$'
  std::vector<std::string> indices;  ///< trimmed
  std::string value;                 ///< trimmed
  std::size_t line = 0;
};

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return {};
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

std::string upper(std::string s) {
  for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

std::vector<Assignment> readAssignments(const std::string& text, const std::string& source) {
  std::vector<Assignment> out;
  std::istringstream in(text);
  std::size_t line_no = 0;
  for (std::string raw; std::getline(in, raw);) {
    ++line_no;
    std::string line = raw.substr(0, raw.find(';'));
    line = trim(line);
    const std::string up = upper(line);
    if (line.empty() || line[0] == '%' || up.rfind("CHANDATA(", 0) == 0 || up == "M17" ||
        up == "M30" || up == "M02" || up == "M2") {
      continue;
    }
    const auto open = line.find('['), close = line.find(']'), eq = line.find('=');
    if (line[0] != '$' || open == std::string::npos || close == std::string::npos ||
        eq == std::string::npos || !(open < close && close < eq)) {
      throw IoError(
          locate(source, line_no, fmt::format("expected $NAME[...]=value, got '{}'", trim(raw))));
    }
    Assignment a;
    a.name = upper(trim(line.substr(1, open - 1)));
    std::stringstream idx(line.substr(open + 1, close - open - 1));
    for (std::string s; std::getline(idx, s, ',');) a.indices.push_back(trim(s));
    if (!trim(line.substr(close + 1, eq - close - 1)).empty()) {
      throw IoError(locate(source, line_no, "text between ']' and '='"));
    }
    a.value = trim(line.substr(eq + 1));
    a.line = line_no;
    out.push_back(std::move(a));
  }
  return out;
}

[[noreturn]] void fail(const std::string& source, const Assignment& a, const std::string& what) {
  throw IoError(locate(source, a.line, fmt::format("${}: {}", a.name, what)));
}

double number(const std::string& source, const Assignment& a, const std::string& text) {
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(begin, &end);
  if (end == begin || *end != '\0' || errno == ERANGE || !std::isfinite(v)) {
    fail(source, a, fmt::format("'{}' is not a finite number", text));
  }
  return v;
}

long long integer(const std::string& source, const Assignment& a, const std::string& text) {
  const double v = number(source, a, text);
  if (v != std::floor(v) || std::abs(v) > 1e9) {
    fail(source, a, fmt::format("'{}' is not an integer", text));
  }
  return static_cast<long long>(v);
}

void expectIndices(const std::string& source, const Assignment& a, std::size_t n) {
  if (a.indices.size() != n) {
    fail(source, a, fmt::format("expected {} indices, got {}", n, a.indices.size()));
  }
}

/// Collects the points N = 0..n−1 of a table; throws for gaps and repeats.
class PointCollector {
 public:
  void add(const std::string& source, const Assignment& a, long long n, double v) {
    if (n < 0 || n > 1'000'000) fail(source, a, fmt::format("point index {} out of range", n));
    if (!points_.emplace(n, std::pair{v, a.line}).second) {
      fail(source, a, fmt::format("point {} given twice", n));
    }
  }
  std::vector<double> values(const std::string& source) const {
    std::vector<double> v;
    for (const auto& [n, p] : points_) {
      if (n != static_cast<long long>(v.size())) {
        throw IoError(locate(source, p.second, fmt::format("point {} is missing", v.size())));
      }
      v.push_back(p.first);
    }
    return v;
  }

 private:
  std::map<long long, std::pair<double, std::size_t>> points_;
};

/// Checks that every assignment refers to the same table key (encoder + axis, or table index).
void sameKey(const std::string& source,
             const Assignment& a,
             std::optional<std::string>& key,
             const std::string& k) {
  if (key && *key != k) fail(source, a, fmt::format("table '{}' differs from '{}'", k, *key));
  key = k;
}

template <typename Table>
Table finish(Table t, const std::string& source, std::size_t last_line) {
  try {
    t.validate();
  } catch (const InvalidArgument& e) {
    throw IoError(locate(source, last_line, e.what()));
  }
  return t;
}

std::string axisValue(const std::string& source, const Assignment& a) {
  std::string v = a.value;
  if (v.size() >= 2 && v.front() == '(' && v.back() == ')') v = trim(v.substr(1, v.size() - 2));
  if (!isIdentifier(v)) fail(source, a, fmt::format("'{}' is not an axis identifier", a.value));
  return v;
}

}  // namespace

// --- EEC -------------------------------------------------------------------------------------

void SiemensEecTable::validate() const {
  PKM_CHECK(encoder == 0 || encoder == 1, "EEC encoder index must be 0 or 1, got {}", encoder);
  PKM_CHECK(isIdentifier(axis), "'{}' is not a SINUMERIK axis identifier", axis);
  checkGrid(values, min, step, max);
}

double SiemensEecTable::valueAt(double x) const {
  return gridValue(values, min, step, max, modulo, x);
}

SiemensEecTable siemensEecFromTable(const AxisErrorTable& table, int encoder) {
  table.validate();
  const Grid g = gridOf(table.nominal);
  SiemensEecTable t{encoder, table.axis, {}, g.min, g.step, g.max, false};
  for (std::size_t i = 0; i < table.size(); ++i) t.values.push_back(table.meanError(i));
  t.validate();
  return t;
}

std::string writeSiemensEec(const SiemensEecTable& t) {
  t.validate();
  const std::string key = fmt::format("{},{}", t.encoder, t.axis);
  std::string out = "%_N_AX_EEC_INI\nCHANDATA(1)\n";
  out +=
      "; pkm compensate: value = error (actual - commanded), mm; a positive value moves the axis"
      " in - (K3)\n";
  for (std::size_t i = 0; i < t.values.size(); ++i) {
    out += fmt::format("$AA_ENC_COMP[{},{},{}]={}\n", t.encoder, i, t.axis, num(t.values[i]));
  }
  out += fmt::format("$AA_ENC_COMP_STEP[{}]={}\n", key, num(t.step));
  out += fmt::format("$AA_ENC_COMP_MIN[{}]={}\n", key, num(t.min));
  out += fmt::format("$AA_ENC_COMP_MAX[{}]={}\n", key, num(t.max));
  out += fmt::format("$AA_ENC_COMP_IS_MODULO[{}]={}\nM17\n", key, t.modulo ? 1 : 0);
  return out;
}

SiemensEecTable parseSiemensEec(const std::string& text, const std::string& source) {
  SiemensEecTable t;
  std::optional<std::string> key;
  PointCollector points;
  bool has_step = false, has_min = false, has_max = false;
  std::size_t last = 0;
  for (const Assignment& a : readAssignments(text, source)) {
    last = a.line;
    if (a.name == "AA_ENC_COMP") {
      expectIndices(source, a, 3);
      sameKey(source, a, key, fmt::format("{},{}", a.indices[0], a.indices[2]));
      points.add(source, a, integer(source, a, a.indices[1]), number(source, a, a.value));
      t.encoder = static_cast<int>(integer(source, a, a.indices[0]));
      t.axis = a.indices[2];
      continue;
    }
    expectIndices(source, a, 2);
    sameKey(source, a, key, fmt::format("{},{}", a.indices[0], a.indices[1]));
    if (a.name == "AA_ENC_COMP_STEP") {
      t.step = number(source, a, a.value);
      has_step = true;
    } else if (a.name == "AA_ENC_COMP_MIN") {
      t.min = number(source, a, a.value);
      has_min = true;
    } else if (a.name == "AA_ENC_COMP_MAX") {
      t.max = number(source, a, a.value);
      has_max = true;
    } else if (a.name == "AA_ENC_COMP_IS_MODULO") {
      const long long m = integer(source, a, a.value);
      if (m != 0 && m != 1) fail(source, a, "must be 0 or 1");
      t.modulo = m == 1;
    } else {
      fail(source, a, "unknown system variable in an EEC table");
    }
  }
  if (!has_step || !has_min || !has_max) {
    throw IoError(locate(source, last, "$AA_ENC_COMP_STEP, _MIN and _MAX are all required"));
  }
  t.values = points.values(source);
  return finish(std::move(t), source, last);
}

// --- CEC -------------------------------------------------------------------------------------

void SiemensCecTable::validate() const {
  PKM_CHECK(index >= 0, "CEC table index must be >= 0, got {}", index);
  PKM_CHECK(isIdentifier(input_axis), "'{}' is not a SINUMERIK axis identifier", input_axis);
  PKM_CHECK(isIdentifier(output_axis), "'{}' is not a SINUMERIK axis identifier", output_axis);
  PKM_CHECK(direction >= -1 && direction <= 1, "CEC direction must be -1, 0 or 1");
  PKM_CHECK(mult_by_table >= 0, "CEC MULT_BY_TABLE must be >= 0");
  checkGrid(values, min, step, max);
}

double SiemensCecTable::valueAt(double x) const {
  return gridValue(values, min, step, max, modulo, x);
}

SiemensCecTable siemensCecFromTable(const CrossAxisTable& table, int index) {
  table.validate();
  const Grid g = gridOf(table.position);
  SiemensCecTable t;
  t.index = index;
  t.input_axis = table.input_axis;
  t.output_axis = table.output_axis;
  t.values = table.error;
  t.min = g.min;
  t.step = g.step;
  t.max = g.max;
  t.validate();
  return t;
}

std::string writeSiemensCec(const SiemensCecTable& t) {
  t.validate();
  std::string out = "%_N_NC_CEC_INI\nCHANDATA(1)\n";
  out += fmt::format(
      "; pkm compensate: value = error of {} (actual - nominal) over {}, mm (sign: pkm "
      "docs/compensation.md)\n",
      t.output_axis,
      t.input_axis);
  for (std::size_t i = 0; i < t.values.size(); ++i) {
    out += fmt::format("$AN_CEC[{},{}]={}\n", t.index, i, num(t.values[i]));
  }
  out += fmt::format("$AN_CEC_INPUT_AXIS[{}]=({})\n", t.index, t.input_axis);
  out += fmt::format("$AN_CEC_OUTPUT_AXIS[{}]=({})\n", t.index, t.output_axis);
  out += fmt::format("$AN_CEC_STEP[{}]={}\n", t.index, num(t.step));
  out += fmt::format("$AN_CEC_MIN[{}]={}\n", t.index, num(t.min));
  out += fmt::format("$AN_CEC_MAX[{}]={}\n", t.index, num(t.max));
  out += fmt::format("$AN_CEC_DIRECTION[{}]={}\n", t.index, t.direction);
  out += fmt::format("$AN_CEC_MULT_BY_TABLE[{}]={}\n", t.index, t.mult_by_table);
  out += fmt::format("$AN_CEC_IS_MODULO[{}]={}\nM17\n", t.index, t.modulo ? 1 : 0);
  return out;
}

SiemensCecTable parseSiemensCec(const std::string& text, const std::string& source) {
  SiemensCecTable t;
  std::optional<std::string> key;
  PointCollector points;
  bool has_in = false, has_out = false, has_step = false, has_min = false, has_max = false;
  std::size_t last = 0;
  for (const Assignment& a : readAssignments(text, source)) {
    last = a.line;
    if (a.name == "AN_CEC") {
      expectIndices(source, a, 2);
      sameKey(source, a, key, a.indices[0]);
      points.add(source, a, integer(source, a, a.indices[1]), number(source, a, a.value));
      t.index = static_cast<int>(integer(source, a, a.indices[0]));
      continue;
    }
    expectIndices(source, a, 1);
    sameKey(source, a, key, a.indices[0]);
    if (a.name == "AN_CEC_INPUT_AXIS") {
      t.input_axis = axisValue(source, a);
      has_in = true;
    } else if (a.name == "AN_CEC_OUTPUT_AXIS") {
      t.output_axis = axisValue(source, a);
      has_out = true;
    } else if (a.name == "AN_CEC_STEP") {
      t.step = number(source, a, a.value);
      has_step = true;
    } else if (a.name == "AN_CEC_MIN") {
      t.min = number(source, a, a.value);
      has_min = true;
    } else if (a.name == "AN_CEC_MAX") {
      t.max = number(source, a, a.value);
      has_max = true;
    } else if (a.name == "AN_CEC_DIRECTION") {
      t.direction = static_cast<int>(integer(source, a, a.value));
    } else if (a.name == "AN_CEC_MULT_BY_TABLE") {
      t.mult_by_table = static_cast<int>(integer(source, a, a.value));
    } else if (a.name == "AN_CEC_IS_MODULO") {
      const long long m = integer(source, a, a.value);
      if (m != 0 && m != 1) fail(source, a, "must be 0 or 1");
      t.modulo = m == 1;
    } else {
      fail(source, a, "unknown system variable in a CEC table");
    }
  }
  if (!has_in || !has_out || !has_step || !has_min || !has_max) {
    throw IoError(locate(
        source, last, "$AN_CEC_INPUT_AXIS, _OUTPUT_AXIS, _STEP, _MIN and _MAX are all required"));
  }
  t.values = points.values(source);
  return finish(std::move(t), source, last);
}

}  // namespace pkm::compensation
