// `pkm analyze squareness` as a workflow (workflow/analyze_positioning.hpp): face diagonals from
// u,v tables or simulator diagonal files, PDGE tables from position tables or simulator linear and
// straightness files (MXT700S parallelism paper, eqs 4-10).
#include <fmt/format.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <utility>

#include "analyze_diagonal_uncertainty.hpp"
#include "data_errors.hpp"
#include "pkm/core/error.hpp"
#include "pkm/geometry/error_table.hpp"
#include "pkm/io/positioning_files.hpp"
#include "pkm/io/text_table.hpp"
#include "pkm/workflow/analyze_positioning.hpp"

namespace pkm::workflow {
namespace {

/// "(a, b, c)" metadata as numbers.
std::vector<double> metaNumbers(const io::TextTable& t, const char* key) {
  const auto v = t.meta(key);
  if (!v) t.failHeader(fmt::format("a measurement file needs '# {}' metadata", key));
  std::string s = *v;
  for (char& c : s) {
    if (c == '(' || c == ')' || c == ',') c = ' ';
  }
  std::istringstream in(s);
  std::vector<double> out;
  for (double x = 0.0; in >> x;) out.push_back(x);
  return out;
}

/// The profile of a simulator linear or straightness file over the position of its one moving
/// axis (start + s·direction), ascending; a straightness run's slope removed.
io::Profile pdgeProfile(const io::TextTable& t) {
  const std::string quantity = t.meta("quantity").value_or("linear");
  if (quantity != "linear" && quantity != "straightness") {
    t.failHeader(
        fmt::format("--pdge: a {} file is not a positioning or straightness table", quantity));
  }
  const std::vector<io::TextTable> one{t};
  io::Profile p = io::meanProfile(one, quantity == "linear");
  const std::vector<double> start = metaNumbers(t, "line start");
  const std::vector<double> dir = metaNumbers(t, "line direction");
  std::size_t axis = dir.size();
  for (std::size_t k = 0; k < dir.size(); ++k) {
    if (dir[k] == 0.0) continue;
    if (axis != dir.size() || start.size() != dir.size()) {
      t.failHeader("--pdge: a measurement file must move exactly one axis");
    }
    axis = k;
  }
  if (axis == dir.size()) t.failHeader("--pdge: a measurement file must move exactly one axis");
  for (double& x : p.position) x = start[axis] + x * dir[axis];
  if (dir[axis] < 0.0) {
    std::reverse(p.position.begin(), p.position.end());
    std::reverse(p.value.begin(), p.value.end());
  }
  if (quantity == "straightness") {
    // The slope of a straightness run is beam misalignment plus squareness: remove it.
    const metrology::ReferenceLine line = metrology::leastSquaresLine(p.position, p.value);
    for (std::size_t k = 0; k < p.position.size(); ++k) p.value[k] -= line.at(p.position[k]);
  }
  return p;
}

metrology::PdgeTerm readPdge(const PdgeInput& in) {
  const io::TextTable t = io::TextTable::parseData(in.table.text, in.table.name);
  io::Profile p;
  if (io::isMeasurementFile(t)) {
    p = pdgeProfile(t);
  } else {
    const std::size_t cp = t.column({"position"}), cd = t.column({"deviation"});
    for (std::size_t r = 0; r < t.rows(); ++r) {
      p.position.push_back(t.number(r, cp));
      p.value.push_back(t.number(r, cd));
    }
  }
  Eigen::MatrixXd values(static_cast<Eigen::Index>(p.value.size()), 1);
  for (std::size_t k = 0; k < p.value.size(); ++k) {
    values(static_cast<Eigen::Index>(k), 0) = p.value[k];
  }
  try {
    return {geometry::ErrorTable1d(p.position, values), in.argument, in.component, 1.0, 0.0};
  } catch (const InvalidArgument& e) {
    throw IoError(fmt::format("{}: {}", t.source(), e.what()));
  }
}

/// A u,v,deviation table as one diagonal.
metrology::FaceDiagonal plainDiagonal(const io::TextTable& t, const std::array<double, 2>& start) {
  metrology::FaceDiagonal d;
  d.start_a = start[0];
  d.start_b = start[1];
  const std::size_t cu = t.column({"u"}), cv = t.column({"v"}), cd = t.column({"deviation"});
  for (std::size_t r = 0; r < t.rows(); ++r) {
    d.points.push_back({t.number(r, cu), t.number(r, cv), t.number(r, cd)});
  }
  return d;
}

/// The indices of the two moving axes of a simulator diagonal file: by name, or the non-zero
/// components of the line direction.
std::vector<std::size_t> movingAxes(const io::TextTable& first,
                                    const std::vector<double>& dir,
                                    const std::vector<std::string>& axes) {
  std::vector<std::string> names;
  if (const auto meta = first.meta("axes")) {
    std::stringstream in(*meta);
    for (std::string n; std::getline(in, n, ',');) names.push_back(n);
  }
  if (!names.empty() && names.size() != dir.size()) {
    first.failHeader("'# line start', '# line direction' and '# axes' differ in size");
  }
  std::vector<std::size_t> moving;
  if (!axes.empty()) {
    for (const std::string& n : axes) {
      std::size_t k = 0;
      while (k < names.size() && names[k] != n) ++k;
      if (k == names.size()) first.failHeader(fmt::format("--axes: no axis '{}' in '# axes'", n));
      moving.push_back(k);
    }
  } else {
    for (std::size_t k = 0; k < dir.size(); ++k) {
      if (dir[k] != 0.0) moving.push_back(k);
    }
  }
  if (moving.size() != 2) {
    first.failHeader("a face diagonal moves exactly two axes (or give --axes A,B)");
  }
  return moving;
}

/// The runs of one simulator diagonal measurement, averaged per target.
metrology::FaceDiagonal simulatorDiagonal(const std::vector<io::TextTable>& runs,
                                          const std::vector<std::string>& axes) {
  const io::TextTable& first = runs.front();
  const std::vector<double> start = metaNumbers(first, "line start");
  const std::vector<double> dir = metaNumbers(first, "line direction");
  if (start.size() != dir.size()) {
    first.failHeader("'# line start', '# line direction' and '# axes' differ in size");
  }
  const std::vector<std::size_t> moving = movingAxes(first, dir, axes);
  const io::Profile p = io::meanProfile(runs, true);
  metrology::FaceDiagonal d{{}, start[moving[0]], start[moving[1]]};
  for (std::size_t k = 0; k < p.position.size(); ++k) {
    const double s = p.position[k];
    d.points.push_back({s * dir[moving[0]], s * dir[moving[1]], p.value[k]});
  }
  return d;
}

std::vector<metrology::FaceDiagonal> readDiagonals(const SquarenessRequest& request) {
  std::vector<metrology::FaceDiagonal> diagonals;
  // Simulator diagonal files, grouped by measurement (runs averaged per target).
  std::map<std::string, std::vector<io::TextTable>> sim;
  std::vector<std::string> sim_order;
  std::size_t plain = 0;
  for (const io::NamedText& in : request.data) {
    io::TextTable t = io::TextTable::parseData(in.text, in.name);
    if (io::isMeasurementFile(t)) {
      const std::string key = t.meta("measurement").value_or(in.name);
      if (!sim.count(key)) sim_order.push_back(key);
      sim[key].push_back(std::move(t));
      continue;
    }
    const std::array<double, 2> start =
        plain < request.start.size() ? request.start[plain] : std::array<double, 2>{0.0, 0.0};
    ++plain;
    diagonals.push_back(plainDiagonal(t, start));
  }
  for (const std::string& key : sim_order)
    diagonals.push_back(simulatorDiagonal(sim[key], request.axes));
  return diagonals;
}

}  // namespace

void SquarenessRequest::validate() const {
  if (data.empty()) throw IoError("give at least one data file");
  for (const PdgeInput& p : pdge)
    if ((p.argument != 0 && p.argument != 1) || (p.component != 0 && p.component != 1))
      throw InvalidArgument(
          fmt::format("{}: a PDGE table's axes must be 0 (u) or 1 (v)", p.table.name));
  for (const auto& s : start)
    if (!std::isfinite(s[0]) || !std::isfinite(s[1]))
      throw InvalidArgument("--start: the start positions must be finite");
}

namespace {

io::SquarenessReport squareness(const SquarenessRequest& request) {
  const std::vector<metrology::FaceDiagonal> diagonals = readDiagonals(request);
  std::vector<metrology::PdgeTerm> pdge;
  for (const PdgeInput& in : request.pdge) pdge.push_back(readPdge(in));
  io::SquarenessReport report;
  const metrology::FaceDiagonalOptions fit{.fit_scale = request.fit_scale,
                                           .first_moves_work = request.first_moves_work,
                                           .second_moves_work = request.second_moves_work};
  report.result = metrology::fitFaceDiagonalSquareness(diagonals, pdge, fit);
  detail::SquarenessBudgets budgets = detail::faceSquarenessBudget(
      diagonals, pdge, fit, report.result, request.uncertainty, request.monte_carlo);
  report.uncertainty = std::move(budgets.linear);
  report.monte_carlo = std::move(budgets.monte_carlo);
  report.diagonals = diagonals.size();
  report.pdge_tables = pdge.size();
  return report;
}

}  // namespace

io::SquarenessReport analyzeSquareness(const SquarenessRequest& request) {
  request.validate();
  return detail::namingData({request.data}, [&] { return squareness(request); });
}

}  // namespace pkm::workflow
