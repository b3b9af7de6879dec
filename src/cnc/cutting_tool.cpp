// The solid of a milling tool and its holder (cnc/cutting_tool.hpp).
#include "pkm/cnc/cutting_tool.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>

#include "pkm/core/error.hpp"

namespace pkm::cnc {

namespace {

constexpr double kMissed = std::numeric_limits<double>::infinity();
/// Below this, 1 − u_z² (resp. |u_z|) counts as zero: a vertical (resp. horizontal) axis.
constexpr double kAxisDegenerate = 1e-12;

bool positiveLength(double v) { return std::isfinite(v) && v > 0.0; }

/// The XY box of the disc of radius r about `c` whose normal is the unit `u`.
void addDisc(std::array<double, 4>& box,
             const std::array<double, 3>& c,
             const std::array<double, 3>& u,
             double r) {
  const double ex = r * std::sqrt(std::max(0.0, 1.0 - u[0] * u[0]));
  const double ey = r * std::sqrt(std::max(0.0, 1.0 - u[1] * u[1]));
  box[0] = std::min(box[0], c[0] - ex);
  box[1] = std::min(box[1], c[1] - ey);
  box[2] = std::max(box[2], c[0] + ex);
  box[3] = std::max(box[3], c[1] + ey);
}

std::array<double, 3> alongAxis(const std::array<double, 3>& p,
                                const std::array<double, 3>& u,
                                double s) {
  return {p[0] + s * u[0], p[1] + s * u[1], p[2] + s * u[2]};
}

void addCylinder(std::array<double, 4>& box, const SolidCylinder& c) {
  addDisc(box, c.from, c.axis, c.radius);
  addDisc(box, alongAxis(c.from, c.axis, c.length), c.axis, c.radius);
}

/// The lowest point of the cylinder anywhere: the lower of its end discs' lowest points.
double cylinderBottom(const SolidCylinder& c) {
  const double drop = c.radius * std::sqrt(std::max(0.0, 1.0 - c.axis[2] * c.axis[2]));
  return std::min(c.from[2], c.from[2] + c.length * c.axis[2]) - drop;
}

}  // namespace

const char* toString(ToolEnd end) { return end == ToolEnd::kBall ? "ball" : "flat"; }

ToolEnd toolEndOf(std::string_view comment) {
  std::string lower(comment);
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char ch) {
    return static_cast<char>(std::tolower(ch));
  });
  return lower.find("ball") != std::string::npos ? ToolEnd::kBall : ToolEnd::kFlat;
}

void CuttingTool::validate() const {
  const auto check = [this](double v, const char* what) {
    if (!positiveLength(v))
      throw InvalidArgument(
          fmt::format("tool T{}: the {} must be > 0 mm (got {})", number, what, v));
  };
  check(diameter, "diameter");
  check(length, "length");
  check(holder_diameter, "holder diameter");
  check(holder_length, "holder length");
  if (end == ToolEnd::kBall && diameter / 2.0 > length)
    throw InvalidArgument(
        fmt::format("tool T{}: a ball end of radius {} mm is longer than the tool ({} mm)",
                    number,
                    diameter / 2.0,
                    length));
}

CuttingTool cuttingToolOf(const ToolEntry& entry, const CuttingTool& holder) {
  CuttingTool t = holder;
  t.number = entry.number;
  t.diameter = entry.diameter;
  t.length = entry.offset[2];
  t.end = toolEndOf(entry.comment);
  t.validate();
  return t;
}

double lowestZ(const SolidCylinder& c, double x, double y) {
  const std::array<double, 3>& u = c.axis;
  const std::array<double, 3> q{x - c.from[0], y - c.from[1], -c.from[2]};
  const double qu = q[0] * u[0] + q[1] * u[1] + q[2] * u[2];
  // Inside the infinite cylinder: |q + z e_z|² − (q·u + z u_z)² ≤ r², i.e. a z² + b z + k ≤ 0.
  const double a = 1.0 - u[2] * u[2];
  const double b = 2.0 * (q[2] - qu * u[2]);
  const double k = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] - qu * qu - c.radius * c.radius;
  double lo = -kMissed, hi = kMissed;
  if (a < kAxisDegenerate) {
    if (k > 0.0) return kMissed;  // a vertical axis: the line is inside for every z or none
  } else {
    const double disc = b * b - 4.0 * a * k;
    if (disc < 0.0) return kMissed;
    const double root = std::sqrt(disc);
    lo = (-b - root) / (2.0 * a);
    hi = (-b + root) / (2.0 * a);
  }
  // Between the end planes: 0 ≤ q·u + z u_z ≤ length.
  if (std::abs(u[2]) < kAxisDegenerate) {
    if (qu < 0.0 || qu > c.length) return kMissed;
  } else {
    double s0 = -qu / u[2], s1 = (c.length - qu) / u[2];
    if (s0 > s1) std::swap(s0, s1);
    lo = std::max(lo, s0);
    hi = std::min(hi, s1);
  }
  return lo <= hi ? lo : kMissed;
}

double ToolSolid::cutterZ(double x, double y) const {
  double z = lowestZ(body, x, y);
  if (ball) {
    const double dx = x - ball_centre[0], dy = y - ball_centre[1];
    const double d2 = ball_radius * ball_radius - dx * dx - dy * dy;
    if (d2 >= 0.0) z = std::min(z, ball_centre[2] - std::sqrt(d2));
  }
  return z;
}

std::array<double, 4> ToolSolid::footprint(bool with_holder) const {
  std::array<double, 4> box{kMissed, kMissed, -kMissed, -kMissed};
  addCylinder(box, body);
  if (ball) {
    box[0] = std::min(box[0], ball_centre[0] - ball_radius);
    box[1] = std::min(box[1], ball_centre[1] - ball_radius);
    box[2] = std::max(box[2], ball_centre[0] + ball_radius);
    box[3] = std::max(box[3], ball_centre[1] + ball_radius);
  }
  if (with_holder) addCylinder(box, holder);
  return box;
}

double ToolSolid::bottom() const {
  const double z = cylinderBottom(body);
  return ball ? std::min(z, ball_centre[2] - ball_radius) : z;
}

double ToolSolid::holderBottom() const { return cylinderBottom(holder); }

ToolSolid toolSolid(const CuttingTool& tool, const ToolPose& pose) {
  ToolSolid s;
  const double r = tool.diameter / 2.0;
  s.ball = tool.end == ToolEnd::kBall;
  const double start = s.ball ? r : 0.0;
  s.body = {alongAxis(pose.tip, pose.axis, start), pose.axis, tool.length - start, r};
  if (s.ball) {
    s.ball_centre = s.body.from;
    s.ball_radius = r;
  }
  s.holder = {alongAxis(pose.tip, pose.axis, tool.length),
              pose.axis,
              tool.holder_length,
              tool.holder_diameter / 2.0};
  return s;
}

}  // namespace pkm::cnc
