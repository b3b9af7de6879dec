/// @file
/// @brief JSON pieces shared by the calibration summaries (calibration_report.cpp,
/// exechon_calibration_report.cpp): residual and error statistics, frames, identifiability.
#pragma once

#include <nlohmann/json.hpp>
#include <vector>

#include "pkm/calibration/hexapod_calibration.hpp"
#include "pkm/calibration/identifiability.hpp"
#include "pkm/calibration/uncertainty.hpp"
#include "pkm/core/units.hpp"
#include "pkm/geometry/rigid_fit.hpp"
#include "pkm/geometry/so3.hpp"

namespace pkm::io::detail {

using ordered_json = nlohmann::ordered_json;

inline ordered_json vectorJson(const double* data, int n) {
  return std::vector<double>(data, data + n);
}

inline ordered_json residualJson(const calibration::ResidualStatistics& s) {
  return {
      {"equations", s.equations}, {"rms", s.rms}, {"max", s.max}, {"fk_failures", s.fk_failures}};
}

inline ordered_json tcpJson(const calibration::TcpErrorStatistics& s) {
  return {{"samples", s.samples}, {"mean", s.mean}, {"p95", s.p95}, {"max", s.max}};
}

/// A rigid transform as {"position": [x, y, z], "rpy_deg": [r, p, y]} (machine-file style).
inline ordered_json frameJson(const geometry::RigidTransform& f) {
  const Eigen::Vector3d rpy = geometry::rpyFromRotation(f.linear());
  return {{"position", {f.translation().x(), f.translation().y(), f.translation().z()}},
          {"rpy_deg", {radToDeg(rpy.x()), radToDeg(rpy.y()), radToDeg(rpy.z())}}};
}

/// {"parameters", "rank", "condition_number", "unidentifiable": [{name: coefficient}]}.
inline ordered_json identifiabilityJson(const calibration::Identifiability& id) {
  ordered_json j;
  j["parameters"] = id.parameters;
  j["rank"] = id.rank;
  j["condition_number"] = id.condition_number;
  j["unidentifiable"] = ordered_json::array();
  for (const auto& c : id.combinations) {
    ordered_json terms = ordered_json::object();
    for (const auto& [name, coef] : c.terms) terms[name] = coef;
    j["unidentifiable"].push_back(terms);
  }
  return j;
}

/// {"converged", "termination", "iterations", "initial_cost", "final_cost", "seconds"}.
template <class Summary>
ordered_json solverJson(const Summary& s) {
  return {{"converged", s.converged},
          {"termination", s.termination},
          {"iterations", s.iterations},
          {"initial_cost", s.initial_cost},
          {"final_cost", s.final_cost},
          {"seconds", s.seconds}};
}

/// [{"source", "residual"}] of the observations with the largest residuals.
template <class Worst>
ordered_json worstJson(const std::vector<Worst>& worst) {
  ordered_json j = ordered_json::array();
  for (const auto& w : worst) j.push_back({{"source", w.source}, {"residual", w.residual}});
  return j;
}

}  // namespace pkm::io::detail
