/// @file
/// @brief ISO 230-6 body-diagonal displacement tests: the four body diagonals of a box, ISO 230-2
/// statistics per diagonal and the closed-form first-order solution for the three squareness
/// errors and the volumetric scale (ISO 230-6; the closed form is given in docs/analysis.md,
/// "--method body").
#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>
#include <span>
#include <string_view>

#include "pkm/metrology/iso230_2.hpp"

namespace pkm::metrology {

/// The four body diagonals of the box [0, Lx]×[0, Ly]×[0, Lz] (ASME B5.54 / ISO 230-6 names, each
/// letter the sign of the X, Y, Z travel; all go +Z): PPP from (0,0,0), NPP from (Lx,0,0), PNP
/// from (0,Ly,0), NNP from (Lx,Ly,0), each ending at the opposite corner with z = Lz.
enum class BodyDiagonal { kPPP = 0, kNPP = 1, kPNP = 2, kNNP = 3 };

/// The four diagonals in index order (PPP, NPP, PNP, NNP).
inline constexpr std::array<BodyDiagonal, 4> kBodyDiagonals = {
    BodyDiagonal::kPPP, BodyDiagonal::kNPP, BodyDiagonal::kPNP, BodyDiagonal::kNNP};

/// "PPP", "NPP", "PNP" or "NNP".
[[nodiscard]] const char* toString(BodyDiagonal diagonal);
/// The diagonal named `name` (exact, upper case), or nullopt.
[[nodiscard]] std::optional<BodyDiagonal> parseBodyDiagonal(std::string_view name);
/// The travel signs (sx, sy, +1) of the diagonal.
[[nodiscard]] Eigen::Vector3d travelSigns(BodyDiagonal diagonal);
/// The start corner of the diagonal in the box `size` (Lx, Ly, Lz), mm.
[[nodiscard]] Eigen::Vector3d diagonalStart(BodyDiagonal diagonal, const Eigen::Vector3d& size);
/// The nominal travel vector end − start = (sx·Lx, sy·Ly, Lz), mm.
[[nodiscard]] Eigen::Vector3d diagonalTravel(BodyDiagonal diagonal, const Eigen::Vector3d& size);

/// Throws pkm::InvalidArgument unless the three box lengths are finite and > 0.
void requireBoxSize(const Eigen::Vector3d& size);

/// First-order squareness and scale from the four body-diagonal length errors.
struct BodyDiagonalSolution {
  double squareness_xy = 0.0;  ///< ∠(+X,+Y) − 90°, rad (= ISO 230-1 EC0Y)
  double squareness_xz = 0.0;  ///< ∠(+X,+Z) − 90°, rad (= −EB0Z)
  double squareness_yz = 0.0;  ///< ∠(+Y,+Z) − 90°, rad (= +EA0Z)
  /// K = kx·Lx² + ky·Ly² + kz·Lz², mm² (the only scale combination the diagonals observe).
  double K = 0.0;
  /// The volumetric scale K / D² (dimensionless; equals k when kx = ky = kz = k).
  double scale = 0.0;
};

/// The closed form (first order in the errors; no angular or Abbe terms; docs/analysis.md):
///   D·ΔD_PPP = K − EC0Y·Lx·Ly + EB0Z·Lx·Lz − EA0Z·Ly·Lz, and the three sign patterns of NPP, PNP,
///   NNP, solved as EC0Y = D(−ΔPPP + ΔNPP + ΔPNP − ΔNNP)/(4·Lx·Ly),
///   EB0Z = D(ΔPPP − ΔNPP + ΔPNP − ΔNNP)/(4·Lx·Lz), EA0Z = D(−ΔPPP − ΔNPP + ΔPNP + ΔNNP)/(4·Ly·Lz),
///   K = D·ΣΔ/4, D = |(Lx, Ly, Lz)|.
/// `length_errors` are ΔD (measured minus nominal full length, mm) in kBodyDiagonals order. The
/// truncation error is second order: O(ε²·L) in each ΔD for errors of size ε (rad or ratio).
/// Throws pkm::InvalidArgument for a bad size or non-finite length errors.
[[nodiscard]] BodyDiagonalSolution solveBodyDiagonals(const Eigen::Vector3d& size,
                                                      const std::array<double, 4>& length_errors);

/// One reading along a body diagonal.
struct BodyDiagonalSample {
  BodyDiagonal diagonal = BodyDiagonal::kPPP;
  double position = 0.0;   ///< commanded distance travelled from the start corner, mm
  double deviation = 0.0;  ///< measured minus commanded displacement, mm
  int run = 1;             ///< ISO 230-2 run number (≥ 1)
  int direction = 1;       ///< approach direction ±1
};

/// Options of evaluateBodyDiagonals.
struct BodyDiagonalOptions {
  /// Evaluate ISO 230-2 per diagonal (needs ≥ 2 runs per target and direction).
  bool iso230_2 = true;
  Iso230_2Options iso;  ///< coverage factor
};

/// The evaluation of one diagonal.
struct DiagonalEvaluation {
  int readings = 0;                   ///< number of samples
  double slope = 0.0;                 ///< least-squares slope of deviation over position (mm/mm)
  double length_error = 0.0;          ///< ΔD = slope · D, mm
  double residual_rms = 0.0;          ///< RMS of the residuals from the least-squares line, mm
  std::optional<Iso230_2Result> iso;  ///< ISO 230-2 statistics (targets = positions)
};

/// All four diagonals and the squareness/scale solution.
struct BodyDiagonalResult {
  std::array<DiagonalEvaluation, 4> diagonals;  ///< in kBodyDiagonals order
  BodyDiagonalSolution solution;                ///< from the four length errors
  double length = 0.0;                          ///< nominal diagonal length D, mm
};

/// Evaluates a body-diagonal test (ISO 230-6): per diagonal, the least-squares line of deviation
/// over position (its slope times D is the length error ΔD used by solveBodyDiagonals, so that
/// every reading counts and a constant datum offset does not), and when options.iso230_2 the ISO
/// 230-2 statistics with the positions as targets. Throws pkm::InvalidArgument when a diagonal has
/// fewer than 2 distinct positions, a value is not finite, a position lies outside [−1 mm, D + 1
/// mm] or the ISO 230-2 evaluation rejects the runs.
[[nodiscard]] BodyDiagonalResult evaluateBodyDiagonals(std::span<const BodyDiagonalSample> samples,
                                                       const Eigen::Vector3d& size,
                                                       const BodyDiagonalOptions& options = {});

}  // namespace pkm::metrology
