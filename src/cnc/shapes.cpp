// The composite machining commands as G-code (cnc/shapes.hpp).
#include "pkm/cnc/shapes.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "pkm/core/error.hpp"

namespace pkm::cnc {
namespace {

/// Clearance of the approach and retract moves above the work, mm.
constexpr double kShapeClearance = 2.0;
/// The sphere's approach and retract above its pole, mm.
constexpr double kSphereClearance = 5.0;
/// Most holes of a drilling pattern and levels of a sphere.
constexpr double kMaxCount = 10'000.0;

/// A coordinate as the page has always written it: at most 4 decimals, no trailing zeros, never
/// "-0".
std::string shapeNum(double v) {
  std::string s = fmt::format("{:.4f}", v);
  s.erase(s.find_last_not_of('0') + 1);
  if (s.back() == '.') s.pop_back();
  return s == "-0" ? "0" : s;
}

const std::map<std::string, std::vector<ShapeParameter>>& shapeTable() {
  static const std::map<std::string, std::vector<ShapeParameter>> t{
      {"sphere",
       {{"radius", 20, "sphere radius, mm"},
        {"x", 0, "centre X, mm"},
        {"y", 0, "centre Y, mm"},
        {"z", 180, "centre Z (the equator's height), mm"},
        {"tool_radius", 3, "ball radius of the tool, mm"},
        {"levels", 6, "number of circles from the equator up"}}},
      {"pocket",
       {{"x", 0, "centre X, mm"},
        {"y", 0, "centre Y, mm"},
        {"radius", 15, "radius of the tool centre's largest circle, mm"},
        {"top", 200, "top of the work, mm"},
        {"depth", 4, "depth below the top, mm"},
        {"stepover", 4, "radial step between circles, mm"},
        {"stepdown", 2, "depth of each pass, mm"}}},
      {"drill",
       {{"holes", 6, "number of holes"},
        {"x", 0, "circle centre X, mm"},
        {"y", 0, "circle centre Y, mm"},
        {"radius", 30, "circle radius, mm"},
        {"top", 200, "top of the work, mm"},
        {"depth", 8, "depth below the top, mm"}}},
      {"face",
       {{"x0", -30, "start X, mm"},
        {"x1", 30, "end X, mm"},
        {"y0", -30, "start Y, mm"},
        {"y1", 30, "end Y, mm"},
        {"z", 195, "height of the faced surface, mm"},
        {"step", 10, "distance between rows, mm"}}},
  };
  return t;
}

/// The values of `spec` with defaults filled in, checked for unknown names and finiteness.
std::map<std::string, double> resolveShape(const ShapeSpec& spec) {
  const std::vector<ShapeParameter>& params = shapeParameters(spec.kind);
  std::map<std::string, double> v;
  for (const ShapeParameter& p : params) v[p.name] = p.value;
  for (const auto& [name, value] : spec.values) {
    if (!v.contains(name)) {
      std::string known;
      for (const ShapeParameter& p : params) known += (known.empty() ? "" : ", ") + p.name;
      throw InvalidArgument(
          fmt::format("{}: unknown parameter '{}' (known: {})", spec.kind, name, known));
    }
    if (!std::isfinite(value))
      throw InvalidArgument(fmt::format("{}: {} must be a finite number", spec.kind, name));
    v[name] = value;
  }
  return v;
}

void requirePositive(const ShapeSpec& s, const std::map<std::string, double>& v, const char* name) {
  if (!(v.at(name) > 0.0))
    throw InvalidArgument(fmt::format("{}: {} must be > 0 (got {:g})", s.kind, name, v.at(name)));
}

int wholeCount(const ShapeSpec& s, const std::map<std::string, double>& v, const char* name) {
  const double n = v.at(name);
  if (!(n >= 1.0 && n <= kMaxCount && n == std::floor(n)))
    throw InvalidArgument(fmt::format(
        "{}: {} must be a whole number from 1 to {:g} (got {:g})", s.kind, name, kMaxCount, n));
  return static_cast<int>(n);
}

/// Appends a line, refusing more than kMaxShapeLines.
void addLine(std::vector<std::string>& out, const std::string& kind, std::string line) {
  if (out.size() >= kMaxShapeLines)
    throw InvalidArgument(
        fmt::format("{}: more than {} lines; choose a larger step", kind, kMaxShapeLines));
  out.push_back(std::move(line));
}

std::vector<std::string> sphereShape(const ShapeSpec& s, const std::map<std::string, double>& v) {
  requirePositive(s, v, "radius");
  requirePositive(s, v, "tool_radius");
  const int levels = wholeCount(s, v, "levels");
  const double r = v.at("tool_radius"), rt = v.at("radius") + r;  // the tool-centre sphere
  const double cx = v.at("x"), cy = v.at("y"), cz = v.at("z");
  const double safe = cz + v.at("radius") + kSphereClearance;
  std::vector<std::string> out;
  addLine(
      out, s.kind, fmt::format("G0 X{} Y{} Z{}", shapeNum(cx + rt), shapeNum(cy), shapeNum(safe)));
  addLine(out, s.kind, fmt::format("G1 Z{}", shapeNum(cz - r)));
  for (int k = 0; k < levels; ++k) {
    const double phi = std::numbers::pi / 2.0 * k / levels;
    const double rho = rt * std::cos(phi), up = rt * std::sin(phi);
    addLine(out,
            s.kind,
            fmt::format("G17 G3 X{} Y{} I{} J0", shapeNum(cx + rho), shapeNum(cy), shapeNum(-rho)));
    // Up the meridian to the next level (or the pole) about the tool-centre sphere's centre.
    const double next = std::numbers::pi / 2.0 * (k + 1) / levels;
    const double x = k + 1 < levels ? cx + rt * std::cos(next) : cx;
    const double z = (k + 1 < levels ? cz + rt * std::sin(next) : cz + rt) - r;
    addLine(out,
            s.kind,
            fmt::format(
                "G18 G2 X{} Z{} I{} K{}", shapeNum(x), shapeNum(z), shapeNum(-rho), shapeNum(-up)));
  }
  addLine(out, s.kind, fmt::format("G17 G0 Z{}", shapeNum(safe)));
  return out;
}

std::vector<std::string> pocketShape(const ShapeSpec& s, const std::map<std::string, double>& v) {
  for (const char* p : {"radius", "depth", "stepover", "stepdown"}) requirePositive(s, v, p);
  const double cx = v.at("x"), cy = v.at("y"), R = v.at("radius"), top = v.at("top");
  const double so = v.at("stepover"), dz = v.at("stepdown"), bottom = top - v.at("depth");
  std::vector<std::string> out;
  addLine(
      out,
      s.kind,
      fmt::format("G0 X{} Y{} Z{}", shapeNum(cx), shapeNum(cy), shapeNum(top + kShapeClearance)));
  for (double z = top - dz;; z -= dz) {
    const bool last = z <= bottom;
    addLine(out,
            s.kind,
            fmt::format("G1 X{} Y{} Z{}", shapeNum(cx), shapeNum(cy), shapeNum(last ? bottom : z)));
    for (double r = std::min(so, R);; r = std::min(r + so, R)) {
      addLine(out, s.kind, fmt::format("G1 X{} Y{}", shapeNum(cx + r), shapeNum(cy)));
      addLine(out,
              s.kind,
              fmt::format("G3 X{} Y{} I{} J0", shapeNum(cx + r), shapeNum(cy), shapeNum(-r)));
      if (r >= R) break;
    }
    if (last) break;
  }
  addLine(out, s.kind, fmt::format("G0 Z{}", shapeNum(top + kShapeClearance)));
  return out;
}

std::vector<std::string> drillShape(const ShapeSpec& s, const std::map<std::string, double>& v) {
  const int holes = wholeCount(s, v, "holes");
  requirePositive(s, v, "depth");
  if (!(v.at("radius") >= 0.0)) throw InvalidArgument("drill: radius must be >= 0");
  const double top = v.at("top");
  std::vector<std::string> out;
  for (int k = 0; k < holes; ++k) {
    const double a = 2.0 * std::numbers::pi * k / holes;
    const double x = v.at("x") + v.at("radius") * std::cos(a);
    const double y = v.at("y") + v.at("radius") * std::sin(a);
    addLine(
        out,
        s.kind,
        fmt::format("G0 X{} Y{} Z{}", shapeNum(x), shapeNum(y), shapeNum(top + kShapeClearance)));
    addLine(out, s.kind, fmt::format("G1 Z{}", shapeNum(top - v.at("depth"))));
    addLine(out, s.kind, fmt::format("G0 Z{}", shapeNum(top + kShapeClearance)));
  }
  return out;
}

std::vector<std::string> faceShape(const ShapeSpec& s, const std::map<std::string, double>& v) {
  requirePositive(s, v, "step");
  const double x0 = v.at("x0"), x1 = v.at("x1"), y0 = v.at("y0"), y1 = v.at("y1"), z = v.at("z");
  if (!(x1 >= x0 && y1 >= y0)) throw InvalidArgument("face: x1 and y1 must be >= x0 and y0");
  std::vector<std::string> out;
  addLine(out,
          s.kind,
          fmt::format("G0 X{} Y{} Z{}", shapeNum(x0), shapeNum(y0), shapeNum(z + kShapeClearance)));
  addLine(out, s.kind, fmt::format("G1 Z{}", shapeNum(z)));
  bool forward = true;
  const double step = v.at("step");
  for (double k = 0.0;; k += 1.0) {
    const double y = std::min(y0 + k * step, y1);
    addLine(out, s.kind, fmt::format("G1 Y{}", shapeNum(y)));
    addLine(out, s.kind, fmt::format("G1 X{}", shapeNum(forward ? x1 : x0)));
    forward = !forward;
    if (y >= y1) break;
  }
  addLine(out, s.kind, fmt::format("G0 Z{}", shapeNum(z + kShapeClearance)));
  return out;
}

}  // namespace

const std::vector<std::string>& shapeKinds() {
  static const std::vector<std::string> kinds{"sphere", "pocket", "drill", "face"};
  return kinds;
}

const std::vector<ShapeParameter>& shapeParameters(std::string_view kind) {
  const auto it = shapeTable().find(std::string(kind));
  if (it == shapeTable().end())
    throw InvalidArgument(fmt::format("unknown shape '{}' (sphere, pocket, drill or face)", kind));
  return it->second;
}

std::vector<std::string> shapeLines(const ShapeSpec& spec) {
  const std::map<std::string, double> v = resolveShape(spec);
  if (spec.kind == "sphere") return sphereShape(spec, v);
  if (spec.kind == "pocket") return pocketShape(spec, v);
  if (spec.kind == "drill") return drillShape(spec, v);
  return faceShape(spec, v);
}

std::string shapeProgram(const ShapeSpec& spec, double feed) {
  if (!(std::isfinite(feed) && feed > 0.0))
    throw InvalidArgument(fmt::format("the feed must be > 0 mm/min (got {:g})", feed));
  std::string out = fmt::format("G21 G90 G17 F{} (pkm gcode make {})\n", shapeNum(feed), spec.kind);
  for (const std::string& l : shapeLines(spec)) out += l + '\n';
  return out + "M2\n";
}

}  // namespace pkm::cnc
