// The stock of the machining preview as a height field (cnc/height_field.hpp).
#include "pkm/cnc/height_field.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "pkm/core/error.hpp"

namespace pkm::cnc {

void StockShape::validate() const {
  const bool finite = std::isfinite(min[0]) && std::isfinite(min[1]) && std::isfinite(max[0]) &&
                      std::isfinite(max[1]) && std::isfinite(centre[0]) &&
                      std::isfinite(centre[1]) && std::isfinite(radius) && std::isfinite(bottom) &&
                      std::isfinite(top);
  if (!finite) throw InvalidArgument("stock: every dimension must be a finite number");
  if (!(top > bottom))
    throw InvalidArgument(
        fmt::format("stock: the top ({} mm) must be above the bottom ({} mm)", top, bottom));
  if (kind == Kind::kBox && !(max[0] > min[0] && max[1] > min[1]))
    throw InvalidArgument(fmt::format(
        "stock: the box X {}..{} Y {}..{} mm is empty", min[0], max[0], min[1], max[1]));
  if (kind == Kind::kCylinder && !(radius > 0.0))
    throw InvalidArgument(
        fmt::format("stock: the cylinder radius must be > 0 mm (got {})", radius));
}

std::string StockShape::describe() const {
  if (kind == Kind::kCylinder)
    return fmt::format("cylinder centre X {:g} Y {:g} radius {:g} Z {:g}..{:g} mm",
                       centre[0],
                       centre[1],
                       radius,
                       bottom,
                       top);
  return fmt::format(
      "box X {:g}..{:g} Y {:g}..{:g} Z {:g}..{:g} mm", min[0], max[0], min[1], max[1], bottom, top);
}

HeightField::HeightField(const StockShape& stock, double cell) : stock_(stock), cell_(cell) {
  stock_.validate();
  if (!(std::isfinite(cell) && cell > 0.0))
    throw InvalidArgument(fmt::format("stock: the cell size must be > 0 mm (got {})", cell));
  std::array<double, 2> lo = stock.min, hi = stock.max;
  if (stock.kind == StockShape::Kind::kCylinder) {
    lo = {stock.centre[0] - stock.radius, stock.centre[1] - stock.radius};
    hi = {stock.centre[0] + stock.radius, stock.centre[1] + stock.radius};
  }
  const double cols = std::ceil((hi[0] - lo[0]) / cell), rows = std::ceil((hi[1] - lo[1]) / cell);
  if (!(cols * rows <= static_cast<double>(kMaxStockCells)))
    throw InvalidArgument(fmt::format(
        "stock: {:g} x {:g} cells of {:g} mm are more than the {} a preview may have; choose a "
        "larger cell",
        cols,
        rows,
        cell,
        kMaxStockCells));
  nx_ = std::max<std::size_t>(1, static_cast<std::size_t>(cols));
  ny_ = std::max<std::size_t>(1, static_cast<std::size_t>(rows));
  x0_ = lo[0];
  y0_ = lo[1];
  h_.assign(nx_ * ny_, static_cast<float>(stock.top));
  inside_.assign(nx_ * ny_, 1);
  if (stock.kind != StockShape::Kind::kCylinder) return;
  for (std::size_t j = 0; j < ny_; ++j)
    for (std::size_t i = 0; i < nx_; ++i) {
      const double dx = cx(i) - stock.centre[0], dy = cy(j) - stock.centre[1];
      if (dx * dx + dy * dy <= stock.radius * stock.radius) continue;
      h_[j * nx_ + i] = static_cast<float>(stock.bottom);
      inside_[j * nx_ + i] = 0;
    }
}

double HeightField::lower(std::size_t k, double z) {
  const double target = std::max(z, stock_.bottom);
  const double now = h_[k];
  if (!(target < now)) return 0.0;
  h_[k] = static_cast<float>(target);
  return now - target;
}

namespace {

/// Cells [first, last] of `n` whose centres x0 + (i + ½)·cell may lie in [a, b] (one more on
/// each side; clamped, so safe for any finite or infinite bounds).
std::array<std::ptrdiff_t, 2> span(double a, double b, double x0, double cell, std::size_t n) {
  const double top = static_cast<double>(n) - 1.0;
  const double first = std::clamp(std::floor((a - x0) / cell - 0.5), 0.0, top + 1.0);
  const double last = std::clamp(std::ceil((b - x0) / cell - 0.5), -1.0, top);
  if (std::isnan(first) || std::isnan(last)) return {1, 0};
  return {static_cast<std::ptrdiff_t>(first), static_cast<std::ptrdiff_t>(last)};
}

}  // namespace

std::array<std::ptrdiff_t, 2> HeightField::columns(double a, double b) const {
  return span(a, b, x0_, cell_, nx_);
}

std::array<std::ptrdiff_t, 2> HeightField::rows(double a, double b) const {
  return span(a, b, y0_, cell_, ny_);
}

double HeightField::volume() const {
  double v = 0.0;
  for (const float h : h_) v += static_cast<double>(h) - stock_.bottom;
  return v * cell_ * cell_;
}

}  // namespace pkm::cnc
