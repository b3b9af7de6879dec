#include "pkm/kinematics/exechon_drm.hpp"

#include <fmt/format.h>

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "pkm/core/error.hpp"

namespace pkm::kinematics {

namespace {
constexpr double kTwoPi = 2.0 * std::numbers::pi;
/// cos 25°: x is too close to the direction to span the circle's plane.
constexpr double kParallelCos = 0.9063077870366499;
}  // namespace

double dependentRotation(const Eigen::Matrix3d& world_R_tool,
                         const Eigen::Matrix3d& world_R_tool_reference) {
  // The upper-left 2×2 of M = reference⁻¹·R (only these four entries are needed).
  const auto& ref = world_R_tool_reference;
  const double m00 = ref.col(0).dot(world_R_tool.col(0)), m01 = ref.col(0).dot(world_R_tool.col(1)),
               m10 = ref.col(1).dot(world_R_tool.col(0)), m11 = ref.col(1).dot(world_R_tool.col(1));
  const double y = m10 - m01, x = m00 + m11;
  return (x == 0.0 && y == 0.0) ? 0.0 : std::atan2(y, x);
}

ExechonIkStatus dependentRotation(const ExechonModel& model,
                                  ExechonData& data,
                                  const ExechonToolPose& pose,
                                  const ExechonToolPose& reference,
                                  double* phi) {
  ExechonIkStatus status = toolInverseKinematics(model, data, reference);
  if (status != ExechonIkStatus::kOk) return status;
  const Eigen::Matrix3d world_R_reference = data.world_R_tool;
  status = toolInverseKinematics(model, data, pose, configurationOf(data));
  if (status == ExechonIkStatus::kOk)
    *phi = dependentRotation(data.world_R_tool, world_R_reference);
  return status;
}

bool DrmCircleOptions::isValid(std::string* why) const {
  auto fail = [why](const std::string& msg) {
    if (why != nullptr) *why = msg;
    return false;
  };
  if (!centre.allFinite()) return fail("centre is not finite");
  if (!direction.allFinite() || !(direction.norm() > 0.0))
    return fail("direction must be finite and non-zero");
  if (!(radius > 0.0) || !std::isfinite(radius))
    return fail(fmt::format("radius must be finite and > 0 (got {})", radius));
  if (!(step > 0.0 && step <= kTwoPi / 5.0))
    return fail(fmt::format("step must be in (0, 2·pi/5] rad (got {})", step));
  return true;
}

std::array<double, 6> fitDrmPolynomial(const std::vector<double>& theta,
                                       const std::vector<double>& phi) {
  PKM_CHECK(theta.size() == phi.size() && theta.size() >= 6,
            "fitDrmPolynomial needs as many theta as phi values, at least 6 (got {} and {})",
            theta.size(),
            phi.size());
  const auto n = static_cast<Eigen::Index>(theta.size());
  Eigen::MatrixXd V(n, 6);
  Eigen::VectorXd b(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double t = theta[static_cast<std::size_t>(i)];
    PKM_CHECK(std::isfinite(t) && std::isfinite(phi[static_cast<std::size_t>(i)]),
              "fitDrmPolynomial: value {} is not finite",
              i);
    double power = 1.0;
    for (int j = 0; j < 6; ++j, power *= t) V(i, j) = power;
    b[i] = phi[static_cast<std::size_t>(i)];
  }
  const Eigen::VectorXd c = V.colPivHouseholderQr().solve(b);
  std::array<double, 6> out{};
  for (int j = 0; j < 6; ++j) out[static_cast<std::size_t>(j)] = c[j];
  return out;
}

double evaluateDrmPolynomial(const std::array<double, 6>& c, double theta) {
  double value = 0.0;
  for (auto it = c.rbegin(); it != c.rend(); ++it) value = value * theta + *it;
  return value;
}

DrmCircleResult sampleDrmCircle(const ExechonModel& model,
                                ExechonData& data,
                                const DrmCircleOptions& options) {
  std::string why;
  PKM_CHECK(options.isValid(&why), "invalid DrmCircleOptions: {}", why);
  DrmCircleResult out;
  const Eigen::Vector3d u = options.direction.normalized();
  Eigen::Vector3d x =
      std::abs(u.x()) > kParallelCos ? Eigen::Vector3d::UnitY() : Eigen::Vector3d::UnitX();
  x = (x - x.dot(u) * u).normalized();
  const Eigen::Vector3d y = u.cross(x);

  out.status = toolInverseKinematics(model, data, {options.centre, u});
  if (!out.ok()) return out;
  const Eigen::Matrix3d world_R_reference = data.world_R_tool;
  ExechonConfiguration previous = configurationOf(data);
  const int n = std::max(5, static_cast<int>(std::ceil(kTwoPi / options.step - 1e-9)));
  out.theta.reserve(static_cast<std::size_t>(n + 1));
  out.phi.reserve(static_cast<std::size_t>(n + 1));
  for (int k = 0; k <= n; ++k) {
    const double theta = kTwoPi * k / n;
    const Eigen::Vector3d p =
        options.centre + options.radius * (std::cos(theta) * x + std::sin(theta) * y);
    out.status = toolInverseKinematics(model, data, {p, u}, previous);
    if (!out.ok()) {
      out.failed_index = k;
      return out;
    }
    previous = configurationOf(data);
    double phi = dependentRotation(data.world_R_tool, world_R_reference);
    if (!out.phi.empty()) phi = out.phi.back() + std::remainder(phi - out.phi.back(), kTwoPi);
    out.theta.push_back(theta);
    out.phi.push_back(phi);
    out.max_abs_phi = std::max(out.max_abs_phi, std::abs(phi));
  }
  out.coefficients = fitDrmPolynomial(out.theta, out.phi);
  for (std::size_t i = 0; i < out.theta.size(); ++i)
    out.max_fit_deviation =
        std::max(out.max_fit_deviation,
                 std::abs(out.phi[i] - evaluateDrmPolynomial(out.coefficients, out.theta[i])));
  return out;
}

}  // namespace pkm::kinematics
