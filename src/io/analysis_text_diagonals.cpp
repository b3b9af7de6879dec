// The table of `pkm analyze diagonals` (analysis_text.hpp): body, step and shifted.
#include <fmt/format.h>

#include <cmath>
#include <string>

#include "io/detail/uncertainty_json.hpp"
#include "pkm/io/analysis_text.hpp"

namespace pkm::io {
namespace {

using metrology::BodyDiagonal;

void bodyText(const metrology::BodyDiagonalResult& r, std::string& o) {
  o += "diagonal,readings,length_error_mm,residual_rms_mm,E_mm,M_mm,A_mm,R_mm,B_mm\n";
  for (BodyDiagonal d : metrology::kBodyDiagonals) {
    const auto& e = r.diagonals[static_cast<std::size_t>(d)];
    const double nan = std::nan("");
    o += fmt::format("{},{},{},{},{},{},{},{},{}\n",
                     metrology::toString(d),
                     e.readings,
                     e.length_error,
                     e.residual_rms,
                     e.iso ? e.iso->E : nan,
                     e.iso ? e.iso->M : nan,
                     e.iso ? e.iso->A : nan,
                     e.iso ? e.iso->R : nan,
                     e.iso ? e.iso->B : nan);
  }
  o += fmt::format("# squareness_xy,{}\n# squareness_xz,{}\n# squareness_yz,{}\n# scale,{}\n",
                   r.solution.squareness_xy,
                   r.solution.squareness_xz,
                   r.solution.squareness_yz,
                   r.solution.scale);
}

void compareText(const std::vector<DiagonalComparison>& compare, std::string& o) {
  if (compare.empty()) return;
  o += "# compare,file,quantity,points,rms_mm,max_abs_mm\n";
  for (const DiagonalComparison& d : compare) {
    const metrology::PlaneComparison& c = d.comparison;
    o += fmt::format(
        "# compare,{},{},{},{},{}\n", d.file, d.quantity, c.positions.size(), c.rms, c.max_abs);
  }
}

void stepText(const metrology::StepDiagonalResult& r, std::string& o) {
  o += "axis,position,E_x,E_y,E_z,Q\n";
  for (std::size_t q = 0; q < 3; ++q) {
    const auto& a = r.axes[q];
    for (std::size_t i = 0; i < a.positions.size(); ++i)
      o += fmt::format("{},{},{},{},{},{}\n",
                       "XYZ"[q],
                       a.positions[i],
                       a.components[0][i],
                       a.components[1][i],
                       a.components[2][i],
                       a.residual[i]);
  }
  o += fmt::format(
      "# squareness_xy,{}\n# squareness_xz,{}\n# squareness_yz,{}\n# residual_max,{}\n"
      "# note: model-based estimates (additive model, no angular/Abbe terms)\n",
      r.squareness_xy,
      r.squareness_xz,
      r.squareness_yz,
      r.residual_max);
}

void shiftedText(const metrology::ShiftedDiagonalResult& r, std::string& o) {
  o += "component,value_mm\n";
  for (std::size_t jj = 0; jj < 3; ++jj)
    for (std::size_t i = 0; i < 3; ++i)
      o += fmt::format("e_{}({}),{}\n", "xyz"[jj], "xyz"[i], r.components[jj][i]);
  o += fmt::format("# squareness_xy,{}\n# squareness_xz,{}\n# squareness_yz,{}\n",
                   r.squareness[0],
                   r.squareness[1],
                   r.squareness[2]);
  o +=
      fmt::format("# scale_x,{}\n# scale_y,{}\n# scale_z,{}\n", r.scale[0], r.scale[1], r.scale[2]);
}

}  // namespace

std::string analysisText(const DiagonalsReport& report) {
  std::string o;
  if (report.body) bodyText(*report.body, o);
  compareText(report.compare, o);
  if (report.step) stepText(*report.step, o);
  if (report.shifted) shiftedText(*report.shifted, o);
  // The table is CSV with '#' notes: the uncertainty lines are notes too.
  const std::string u = detail::uncertaintyText(report.uncertainty) +
                        detail::monteCarloText(report.uncertainty, report.monte_carlo);
  for (std::size_t b = 0, e = 0; b < u.size(); b = e + 1) {
    e = u.find('\n', b);
    o += "# " + u.substr(b, e - b) + "\n";
  }
  return o;
}

}  // namespace pkm::io
