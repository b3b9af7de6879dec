/// @file
/// @brief The stock of the machining preview as a height field (a Z-map): one column of
/// material per square cell, from the stock's bottom up to the cell's height, which a tool only
/// lowers (docs/machining.md, "Why a height field"). A box or a vertical cylinder of stock.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pkm::cnc {

/// The raw stock, mm, in the program's machine coordinates.
struct StockShape {
  enum class Kind { kBox, kCylinder };
  Kind kind = Kind::kBox;
  std::array<double, 2> min{};     ///< box: lower XY corner
  std::array<double, 2> max{};     ///< box: upper XY corner
  std::array<double, 2> centre{};  ///< cylinder: axis XY
  double radius = 0.0;             ///< cylinder radius
  double bottom = 0.0;             ///< underside (on the table)
  double top = 0.0;                ///< top face
  /// Throws pkm::InvalidArgument for a non-finite value, an empty box, a radius not > 0 or a
  /// top not above the bottom.
  void validate() const;
  /// "box X0 Y0 X1 Y1 Z0 Z1" or "cylinder CX CY R Z0 Z1" (mm, for reports).
  [[nodiscard]] std::string describe() const;
};

/// The most cells a height field may have (about 32 MB of heights).
inline constexpr std::size_t kMaxStockCells = 4'000'000;

/// A height field over the stock's XY box: cell (i, j) covers x in [x0 + i·cell, x0 + (i+1)·cell)
/// and is sampled at its centre; cells outside a cylinder hold no material (height = bottom).
class HeightField {
 public:
  /// The field of `stock` with square cells of `cell` mm. Throws pkm::InvalidArgument as
  /// StockShape::validate, for a cell not > 0, or for more than kMaxStockCells cells.
  HeightField(const StockShape& stock, double cell);

  [[nodiscard]] std::size_t nx() const { return nx_; }
  [[nodiscard]] std::size_t ny() const { return ny_; }
  [[nodiscard]] double cell() const { return cell_; }
  [[nodiscard]] double x0() const { return x0_; }
  [[nodiscard]] double y0() const { return y0_; }
  [[nodiscard]] double bottom() const { return stock_.bottom; }
  [[nodiscard]] double top() const { return stock_.top; }
  [[nodiscard]] const StockShape& stock() const { return stock_; }
  /// Centre of cell (i, j), mm.
  [[nodiscard]] double cx(std::size_t i) const {
    return x0_ + (static_cast<double>(i) + 0.5) * cell_;
  }
  [[nodiscard]] double cy(std::size_t j) const {
    return y0_ + (static_cast<double>(j) + 0.5) * cell_;
  }
  /// Height of cell index k = j·nx + i, mm.
  [[nodiscard]] float height(std::size_t k) const { return h_[k]; }
  [[nodiscard]] const std::vector<float>& heights() const { return h_; }
  /// Whether cell k held material at the start (inside the stock's outline).
  [[nodiscard]] bool inside(std::size_t k) const { return inside_[k] != 0; }
  /// Lowers cell k to z (never below the bottom); returns the depth removed (≥ 0, mm).
  double lower(std::size_t k, double z);
  /// The range of cell indices [first, last] along x covering [a, b] (clamped; empty when
  /// first > last).
  [[nodiscard]] std::array<std::ptrdiff_t, 2> columns(double a, double b) const;
  /// The same along y.
  [[nodiscard]] std::array<std::ptrdiff_t, 2> rows(double a, double b) const;
  /// Calls f(k, x, y) for each cell k whose centre (x, y) may lie in [x0, x1] × [y0, y1] (the
  /// spans of columns() and rows()), row by row.
  template <typename F>
  void forEachCell(double x0, double y0, double x1, double y1, F&& f) const {
    const auto c = columns(x0, x1);
    const auto r = rows(y0, y1);
    for (std::ptrdiff_t j = r[0]; j <= r[1]; ++j)
      for (std::ptrdiff_t i = c[0]; i <= c[1]; ++i) {
        const auto ui = static_cast<std::size_t>(i), uj = static_cast<std::size_t>(j);
        f(uj * nx_ + ui, cx(ui), cy(uj));
      }
  }
  /// Material volume, mm³ (Σ (height − bottom) · cell²).
  [[nodiscard]] double volume() const;

 private:
  StockShape stock_;
  double cell_ = 1.0, x0_ = 0.0, y0_ = 0.0;
  std::size_t nx_ = 0, ny_ = 0;
  std::vector<float> h_;
  std::vector<std::uint8_t> inside_;
};

}  // namespace pkm::cnc
