/// @file
/// @brief Internal: parsing JSON machine and error files with errors located as "FILE:LINE:
/// /pointer: message" (shared by the hexapod, Exechon and geometric-error readers).
#pragma once

#include <fmt/format.h>

#include <Eigen/Core>
#include <cctype>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>

#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/io/json_locator.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"

namespace pkm::io::detail {

using nlohmann::json;

/// 1-based line of the first number token `token` outside strings in `text`; 0 if none.
inline std::size_t lineOfNumber(const std::string& text, const std::string& token) {
  if (token.empty()) return 0;
  const auto numberChar = [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '+' || c == '-';
  };
  std::size_t line = 1;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') ++line;
    if (in_string) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (text.compare(i, token.size(), token) == 0 && (i == 0 || !numberChar(text[i - 1])) &&
               (i + token.size() == text.size() || !numberChar(text[i + token.size()]))) {
      return line;
    }
  }
  return 0;
}

/// Parses `text`; throws pkm::IoError "SOURCE:LINE: invalid JSON: ..." on a syntax error or a
/// number out of the range of a double.
inline json parseJson(const std::string& text, const std::string& source) {
  try {
    return json::parse(text);
  } catch (const json::parse_error& e) {
    const std::size_t byte = std::min<std::size_t>(e.byte, text.size());
    const std::size_t line =
        1 + static_cast<std::size_t>(
                std::count(text.begin(),
                           text.begin() + static_cast<std::ptrdiff_t>(byte > 0 ? byte - 1 : 0),
                           '\n'));
    std::string what = e.what();
    if (const auto p = what.find("syntax error"); p != std::string::npos) what = what.substr(p);
    throw IoError(locate(source, line, "invalid JSON: " + what));
  } catch (const json::out_of_range& e) {
    // A number too large for a double ("1e999"): nlohmann reports the token but not its position.
    std::string what = e.what();
    const auto q1 = what.find('\'');
    const auto q2 = what.rfind('\'');
    const std::string token =
        q1 != std::string::npos && q2 > q1 ? what.substr(q1 + 1, q2 - q1 - 1) : std::string();
    throw IoError(
        locate(source,
               lineOfNumber(text, token),
               fmt::format("number {} is not finite (out of the range of a double)", token)));
  }
}

/// Typed access to a parsed JSON document that reports errors as "SOURCE:LINE: POINTER: message".
class JsonDoc {
 public:
  JsonDoc(const std::string& text, std::string source)
      : source_(std::move(source)), locator_(text) {}

  [[noreturn]] void fail(const std::string& pointer, const std::string& what) const {
    throw IoError(locate(source_,
                         locator_.line(pointer),
                         fmt::format("{}: {}", pointer.empty() ? "/" : pointer, what)));
  }

  void onlyKeys(const json& obj,
                const std::string& ptr,
                std::initializer_list<const char*> keys) const {
    if (!obj.is_object()) fail(ptr, "expected an object");
    for (const auto& item : obj.items()) {
      bool known = false;
      for (const char* k : keys) known = known || item.key() == k;
      if (!known) fail(ptr + "/" + item.key(), fmt::format("unknown key '{}'", item.key()));
    }
  }

  double number(const json& v, const std::string& ptr) const {
    if (!v.is_number()) fail(ptr, "expected a number");
    const double x = v.get<double>();
    if (!std::isfinite(x)) fail(ptr, "number is not finite");
    return x;
  }

  double number(const json& obj, const std::string& ptr, const char* key, double fallback) const {
    return obj.contains(key) ? number(obj[key], ptr + "/" + key) : fallback;
  }

  Eigen::Vector3d vec3(const json& v, const std::string& ptr) const {
    if (!v.is_array() || v.size() != 3) fail(ptr, "expected an array of 3 numbers");
    return {number(v[0], ptr + "/0"), number(v[1], ptr + "/1"), number(v[2], ptr + "/2")};
  }

  /// [min, max] with null meaning unbounded on that side (±infinity); `scale` multiplies finite
  /// values (e.g. degrees to radians). Fails when min > max.
  std::pair<double, double> range(const json& v, const std::string& ptr, double scale = 1.0) const {
    if (!v.is_array() || v.size() != 2) fail(ptr, "expected [min, max] (null = unbounded)");
    const double lo = v[0].is_null() ? -INFINITY : scale * number(v[0], ptr + "/0");
    const double hi = v[1].is_null() ? INFINITY : scale * number(v[1], ptr + "/1");
    if (lo > hi) fail(ptr, "min is larger than max");
    return {lo, hi};
  }

  /// +1 or -1.
  int sign(const json& obj, const std::string& ptr, const char* key, int fallback) const {
    if (!obj.contains(key)) return fallback;
    const double v = number(obj[key], ptr + "/" + key);
    if (v != 1.0 && v != -1.0) fail(ptr + "/" + key, "must be 1 or -1");
    return static_cast<int>(v);
  }

  /// A required key's value.
  const json& required(const json& obj, const std::string& ptr, const char* key) const {
    if (!obj.contains(key)) fail(ptr, fmt::format("missing key '{}'", key));
    return obj[key];
  }

  std::string string(const json& obj,
                     const std::string& ptr,
                     const char* key,
                     const std::string& fallback) const {
    if (!obj.contains(key)) return fallback;
    if (!obj[key].is_string()) fail(ptr + "/" + key, "expected a string");
    return obj[key].get<std::string>();
  }

 private:
  std::string source_;
  JsonLocator locator_;
};

/// Checks "schema" (absent or `schema`) and returns the "units" ("mm" default, or "inch").
inline LengthUnit readSchemaAndUnits(const JsonDoc& doc, const json& root, const char* schema) {
  if (const std::string s = doc.string(root, "", "schema", schema); s != schema)
    doc.fail("/schema",
             fmt::format("unsupported schema \"{}\" (this version reads \"{}\")", s, schema));
  const std::string units = doc.string(root, "", "units", "mm");
  const auto unit = lengthUnitFromString(units);
  if (!unit)
    doc.fail("/units", fmt::format("units must be \"mm\" or \"inch\" (got \"{}\")", units));
  return *unit;
}

/// Reads {"tolerance": .., "max_iterations": ..} at "/forward_kinematics" into `fk`.
inline void readFkOptions(const JsonDoc& doc, const json& f, kinematics::FkOptions& fk) {
  const std::string ptr = "/forward_kinematics";
  doc.onlyKeys(f, ptr, {"tolerance", "max_iterations"});
  fk.tolerance = doc.number(f, ptr, "tolerance", fk.tolerance);
  const double it = doc.number(f, ptr, "max_iterations", fk.max_iterations);
  if (it != std::floor(it) || it < 1 || it > 1e6)
    doc.fail(ptr + "/max_iterations", "must be an integer in [1, 1e6]");
  fk.max_iterations = static_cast<int>(it);
  std::string why;
  if (!fk.isValid(&why)) doc.fail(ptr, why);
}

}  // namespace pkm::io::detail
