// The interpreter settings of a LinuxCNC INI (cnc/interpreter_ini.hpp), after the LinuxCNC 2.9 INI
// reference ("[RS274NGC] Section") and what `rs274 -i` does with them.
#include "pkm/cnc/interpreter_ini.hpp"

#include <fmt/format.h>

#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <string_view>

#include "pkm/cnc/parameters.hpp"
#include "pkm/core/error.hpp"
#include "pkm/core/text.hpp"

namespace pkm::cnc {

namespace {

bool hasLowerCase(std::string_view s) {
  for (const char c : s)
    if (std::islower(static_cast<unsigned char>(c)) != 0) return true;
  return false;
}

std::string lowerCase(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

/// `path` against the folder of the INI `ini_name` unless absolute.
std::string besideIni(const std::string& ini_name, std::string_view path) {
  const std::filesystem::path p(path);
  if (p.is_absolute()) return p.string();
  return (std::filesystem::path(ini_name).parent_path() / p).lexically_normal().string();
}

/// True when all of `s` is one finite number; it goes to `v`.
bool parseNumber(std::string_view s, double& v) {
  if (s.empty()) return false;
  const char* first = s.data() + (s.front() == '+' ? 1 : 0);
  const auto r = std::from_chars(first, s.data() + s.size(), v);
  return r.ec == std::errc() && r.ptr == s.data() + s.size() && std::isfinite(v);
}

/// The number of entry `e` of INI `name`; throws naming the line.
double numberOf(const std::string& name, const IniEntry& e) {
  double v = 0.0;
  if (!parseNumber(e.value, v))
    throw IoError(
        locate(name, e.line, fmt::format("[{}] {}: expected a number", e.section, e.key)));
  return v;
}

}  // namespace

Rs274ngcIni readRs274ngcIni(std::string_view text, const std::string& name) {
  Rs274ngcIni r;
  bool ini_vars = true;
  const std::vector<IniEntry> entries = parseIni(text, name);
  for (const IniEntry& e : entries) {
    const auto fail = [&](const std::string& what) { throw IoError(locate(name, e.line, what)); };
    if (e.section == "TRAJ" && e.key == "LINEAR_UNITS")
      r.inch_machine = e.value == "inch" || e.value == "in" || e.value == "imperial";
    if (e.section != "RS274NGC") continue;
    if (e.key == "RS274NGC_STARTUP_CODE") {
      r.startup_code = e.value;
      r.startup_source = fmt::format("{}:{}", name, e.line);
    } else if (e.key == "CENTER_ARC_RADIUS_TOLERANCE_MM") {
      r.arc.centre_mm = numberOf(name, e);
    } else if (e.key == "CENTER_ARC_RADIUS_TOLERANCE_INCH") {
      r.arc.centre_inch = numberOf(name, e);
    } else if (e.key == "PARAMETER_FILE") {
      r.parameter_file = besideIni(name, e.value);
    } else if (e.key == "SUBROUTINE_PATH") {
      std::string_view rest = e.value;
      while (!rest.empty()) {
        const auto colon = rest.find(':');
        const std::string_view dir = rest.substr(0, colon);
        if (!dir.empty()) r.subroutine_path.push_back(besideIni(name, dir));
        rest = colon == std::string_view::npos ? std::string_view() : rest.substr(colon + 1);
      }
    } else if (e.key == "INI_VARS") {
      ini_vars = numberOf(name, e) != 0.0;
    } else if (e.key == "REMAP") {
      // "REMAP = M6 modalgroup=6 ngc=change": a program that uses the code is refused.
      const auto words = splitWords(e.value);
      if (words.empty()) fail("[RS274NGC] REMAP without a code");
      r.remapped[lowerCase(words[0])] = fmt::format("{}:{}", name, e.line);
    }
    try {
      r.arc.validate();
    } catch (const InvalidArgument& x) {
      fail(x.what());
    }
  }
  if (ini_vars)
    for (const IniEntry& e : entries) {
      double v = 0.0;
      if (hasLowerCase(e.section) || hasLowerCase(e.key) || !parseNumber(e.value, v)) continue;
      r.values[lowerCase(e.section) + "]" + lowerCase(e.key)] = v;
    }
  return r;
}

void readParameterFile(std::string_view text_in,
                       const std::string& name,
                       bool inch_machine,
                       InterpreterOptions& options) {
  const std::vector<std::string_view> lines = splitLines(text_in);
  for (std::size_t k = 0; k < lines.size(); ++k) {
    const std::size_t line_no = k + 1;
    const std::string_view text = trimBlanks(lines[k]);
    if (text.empty()) continue;
    const auto words = splitWords(text);
    double index = 0.0;
    double value = 0.0;
    if (words.size() != 2 || !parseNumber(words[0], index) || !parseNumber(words[1], value) ||
        index != std::floor(index) || std::abs(index) > 1e6)
      throw IoError(locate(name, line_no, "expected 'NUMBER VALUE' (a LinuxCNC parameter file)"));
    const int n = static_cast<int>(index);
    if (n < 1 || n >= kParameterCount)
      throw IoError(locate(name, line_no, fmt::format("parameter number {} outside 1..5601", n)));
    options.initial_parameters[n] =
        isLengthParameter(n) && inch_machine ? value * kMmPerInch : value;
  }
}

}  // namespace pkm::cnc
