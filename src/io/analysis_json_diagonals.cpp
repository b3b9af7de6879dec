// The JSON document of `pkm analyze diagonals` (analysis_report.hpp): body, step and shifted.
#include <fmt/format.h>

#include <nlohmann/json.hpp>
#include <string>

#include "io/detail/uncertainty_json.hpp"
#include "pkm/io/analysis_report.hpp"

namespace pkm::io {
namespace {

using Json = nlohmann::ordered_json;
using metrology::BodyDiagonal;

Json isoJson(const metrology::Iso230_2Result& r) {
  Json j;
  j["B"] = r.B;
  j["B_mean"] = r.B_mean;
  j["R_up"] = r.R_up;
  j["R_down"] = r.R_down;
  j["R"] = r.R;
  j["E_up"] = r.E_up;
  j["E_down"] = r.E_down;
  j["E"] = r.E;
  j["M"] = r.M;
  j["A_up"] = r.A_up;
  j["A_down"] = r.A_down;
  j["A"] = r.A;
  Json targets = Json::array();
  for (const auto& t : r.targets)
    targets.push_back({{"target", t.target},
                       {"mean_up", t.mean_up},
                       {"mean_down", t.mean_down},
                       {"reversal", t.reversal},
                       {"s_up", t.s_up},
                       {"s_down", t.s_down},
                       {"R_up", t.repeatability_up},
                       {"R_down", t.repeatability_down},
                       {"R", t.repeatability},
                       {"mean", t.mean}});
  j["targets"] = targets;
  return j;
}

void addSquareness(Json& j, double xy, double xz, double yz) {
  j["squareness_xy"] = xy;
  j["squareness_xz"] = xz;
  j["squareness_yz"] = yz;
  j["iso230_1"] = {{"EC0Y", xy}, {"EB0Z", -xz}, {"EA0Z", yz}};
}

Json compareJson(const std::vector<DiagonalComparison>& compare) {
  Json list = Json::array();
  for (const DiagonalComparison& d : compare) {
    const metrology::PlaneComparison& c = d.comparison;
    list.push_back({{"file", d.file},
                    {"quantity", d.quantity},
                    {"rms", c.rms},
                    {"max_abs", c.max_abs},
                    {"position", c.positions},
                    {"measured", c.measured},
                    {"predicted", c.predicted}});
  }
  return list;
}

void bodyJson(const metrology::BodyDiagonalResult& r, Json& j) {
  j["length"] = r.length;
  addSquareness(j, r.solution.squareness_xy, r.solution.squareness_xz, r.solution.squareness_yz);
  j["scale"] = r.solution.scale;
  j["K"] = r.solution.K;
  Json diags;
  for (BodyDiagonal d : metrology::kBodyDiagonals) {
    const auto& e = r.diagonals[static_cast<std::size_t>(d)];
    Json dj = {{"readings", e.readings},
               {"slope", e.slope},
               {"length_error", e.length_error},
               {"residual_rms", e.residual_rms}};
    if (e.iso) dj.update(isoJson(*e.iso));
    diags[metrology::toString(d)] = dj;
  }
  j["diagonals"] = diags;
}

void stepJson(const metrology::StepDiagonalResult& r, Json& j) {
  static constexpr const char* kNames[3][3] = {
      {"EXX", "EYX", "EZX"}, {"EXY", "EYY", "EZY"}, {"EXZ", "EYZ", "EZZ"}};
  addSquareness(j, r.squareness_xy, r.squareness_xz, r.squareness_yz);
  j["residual_max"] = r.residual_max;
  Json axes;
  for (std::size_t q = 0; q < 3; ++q) {
    const auto& a = r.axes[q];
    Json aj = {{"position", a.positions}, {"Q", a.residual}};
    for (std::size_t c = 0; c < 3; ++c) {
      aj[kNames[q][c]] = a.components[c];
      aj[fmt::format("{}_slope", kNames[q][c])] = a.slopes[c];
      aj[fmt::format("{}_straightness", kNames[q][c])] = a.straightness[c];
    }
    axes[std::string(1, "xyz"[q])] = aj;
  }
  j["axes"] = axes;
}

void shiftedJson(const metrology::ShiftedDiagonalResult& r, Json& j) {
  addSquareness(j, r.squareness[0], r.squareness[1], r.squareness[2]);
  j["scale"] = {{"x", r.scale[0]}, {"y", r.scale[1]}, {"z", r.scale[2]}};
  j["squareness_eq6"] = r.squareness_eq6;
  j["squareness_eq6_scaled"] = r.squareness_eq6_scaled;
  j["asymmetry"] = r.asymmetry;
  Json comp;
  for (std::size_t jj = 0; jj < 3; ++jj)
    for (std::size_t i = 0; i < 3; ++i)
      comp[fmt::format("e_{}({})", "xyz"[jj], "xyz"[i])] = r.components[jj][i];
  j["components"] = comp;
  Json te;
  for (BodyDiagonal d : metrology::kBodyDiagonals)
    te[metrology::toString(d)] = r.travel_errors[static_cast<std::size_t>(d)];
  j["travel_errors"] = te;
}

}  // namespace

const char* toString(DiagonalMethod method) {
  switch (method) {
    case DiagonalMethod::kBody:
      return "body";
    case DiagonalMethod::kShifted:
      return "shifted";
    case DiagonalMethod::kStep:
      return "step";
  }
  return "body";
}

std::string analysisJson(const DiagonalsReport& report) {
  Json j;
  j["method"] = toString(report.method);
  j["size"] = {report.size.x(), report.size.y(), report.size.z()};
  if (report.body) bodyJson(*report.body, j);
  if (report.step) stepJson(*report.step, j);
  if (report.shifted) shiftedJson(*report.shifted, j);
  if (!report.compare.empty()) j["compare"] = compareJson(report.compare);
  j["uncertainty"] = detail::uncertaintyJson(report.uncertainty, report.monte_carlo);
  return j.dump(2) + "\n";
}

}  // namespace pkm::io
