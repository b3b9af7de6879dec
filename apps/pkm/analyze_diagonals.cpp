// `pkm analyze diagonals`: ISO 230-6 body diagonals (--method body), seed 001's shifted diagonals
// (--method shifted) and Wang's step diagonals (--method step), with the 2-D XY prediction
// compared against direct measurements (--compare). docs/analysis.md, "Diagonal methods".
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "analyze_common.hpp"
#include "cli_common.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/text_table.hpp"
#include "pkm/metrology/body_diagonals.hpp"
#include "pkm/metrology/plane_prediction.hpp"
#include "pkm/metrology/shifted_diagonal.hpp"
#include "pkm/metrology/step_diagonal.hpp"

namespace pkm::cli {
namespace {

using metrology::BodyDiagonal;
using Json = nlohmann::ordered_json;

struct DiagonalsState {
  AnalyzeIo io;
  std::string method = "body";
  std::vector<double> size;
  double coverage = 2.0;
  std::vector<std::string> compare;
};

constexpr double kCornerTolerance = 1e-3;     // mm: a line start that counts as a box corner
constexpr double kDirectionTolerance = 1e-6;  // a line direction that counts as a diagonal's

/// "(a, b, c)" from a measurement file's metadata.
std::optional<Eigen::Vector3d> metaVector(const io::TextTable& t, std::string_view key) {
  const auto v = t.meta(key);
  if (!v) return std::nullopt;
  std::string s = *v;
  for (char& c : s)
    if (c == '(' || c == ')' || c == ',') c = ' ';
  std::istringstream in(s);
  Eigen::Vector3d out;
  if (!(in >> out.x() >> out.y() >> out.z()))
    t.failHeader(fmt::format("metadata '{}' is not a 3-vector: '{}'", key, *v));
  return out;
}

/// A measurement file (`pkm simulate`): target, run, direction, reading and the line metadata.
struct LineFile {
  Eigen::Vector3d start, direction;
  std::vector<double> target, deviation;
  std::vector<int> run, dir, sub_step;
};

bool isLineFile(const io::TextTable& t) {
  return !t.findColumn({"diagonal"}) && t.findColumn({"target_mm", "target"}) &&
         t.findColumn({"reading_mm"});
}

LineFile readLineFile(const io::TextTable& t) {
  LineFile f;
  const auto start = metaVector(t, "line start");
  const auto direction = metaVector(t, "line direction");
  if (!start || !direction)
    t.failHeader("a measurement file needs '# line start' and '# line direction' metadata");
  f.start = *start;
  f.direction = *direction;
  const std::size_t ct = t.column({"target_mm", "target"});
  const std::size_t cr = t.column({"reading_mm"});
  const auto crun = t.findColumn({"run"});
  const auto cdir = t.findColumn({"direction"});
  const auto csub = t.findColumn({"sub_step"});
  for (std::size_t r = 0; r < t.rows(); ++r) {
    f.target.push_back(t.number(r, ct));
    f.deviation.push_back(t.number(r, cr) - f.target.back());
    f.run.push_back(crun ? static_cast<int>(t.integer(r, *crun)) : 1);
    f.dir.push_back(cdir ? t.direction(r, *cdir) : 1);
    f.sub_step.push_back(csub ? static_cast<int>(t.integer(r, *csub)) : 0);
  }
  if (f.target.empty()) t.failHeader("no readings");
  return f;
}

/// The body diagonal whose start corner is `start` (or nullopt).
std::optional<BodyDiagonal> diagonalAt(const Eigen::Vector3d& start, const Eigen::Vector3d& size) {
  for (BodyDiagonal d : metrology::kBodyDiagonals)
    if ((metrology::diagonalStart(d, size) - start).norm() < kCornerTolerance) return d;
  return std::nullopt;
}

/// The diagonal of a continuous or step measurement file that runs along a whole body diagonal.
BodyDiagonal identifyDiagonal(const io::TextTable& t,
                              const LineFile& f,
                              const Eigen::Vector3d& size) {
  const auto d = diagonalAt(f.start, size);
  if (!d ||
      (metrology::diagonalTravel(*d, size).normalized() - f.direction).norm() > kDirectionTolerance)
    t.failHeader(
        fmt::format("line start ({}, {}, {}) and direction are not a body diagonal "
                    "PPP/NPP/PNP/NNP of the box {} x {} x {}",
                    f.start.x(),
                    f.start.y(),
                    f.start.z(),
                    size.x(),
                    size.y(),
                    size.z()));
  return *d;
}

BodyDiagonal diagonalField(const io::TextTable& t, std::size_t row, std::size_t col) {
  const auto d = metrology::parseBodyDiagonal(t.text(row, col));
  if (!d) t.fail(row, fmt::format("diagonal '{}' is not PPP, NPP, PNP or NNP", t.text(row, col)));
  return *d;
}

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

// ---- body -------------------------------------------------------------------------------------

void runBody(const DiagonalsState& st, const Eigen::Vector3d& size, Output& out) {
  std::vector<metrology::BodyDiagonalSample> samples;
  bool runs_given = true;
  for (const std::string& path : st.io.data) {
    const io::TextTable t = io::TextTable::read(path);
    if (isLineFile(t)) {
      const LineFile f = readLineFile(t);
      const BodyDiagonal d = identifyDiagonal(t, f, size);
      for (std::size_t i = 0; i < f.target.size(); ++i)
        samples.push_back({d, f.target[i], f.deviation[i], f.run[i], f.dir[i]});
      continue;
    }
    const std::size_t cd = t.column({"diagonal"});
    const std::size_t cp = t.column({"position", "target", "target_mm"});
    const std::size_t cv = t.column({"deviation", "deviation_mm"});
    const auto crun = t.findColumn({"run"});
    const auto cdir = t.findColumn({"direction"});
    if (!crun) runs_given = false;
    for (std::size_t r = 0; r < t.rows(); ++r) {
      metrology::BodyDiagonalSample s{diagonalField(t, r, cd),
                                      t.number(r, cp),
                                      t.number(r, cv),
                                      crun ? static_cast<int>(t.integer(r, *crun)) : 0,
                                      cdir ? t.direction(r, *cdir) : 1};
      if (crun && s.run < 1) t.fail(r, "run must be >= 1");
      samples.push_back(s);
    }
  }
  if (!runs_given) {  // each row one reading: number them per (diagonal, position, direction)
    std::map<std::tuple<int, double, int>, int> count;
    for (auto& s : samples)
      s.run = ++count[{static_cast<int>(s.diagonal), s.position, s.direction}];
  }
  // ISO 230-2 needs ≥ 2 runs per target and direction on every diagonal.
  std::map<std::tuple<int, double, int>, int> per_target;
  for (const auto& s : samples)
    ++per_target[{static_cast<int>(s.diagonal), s.position, s.direction}];
  metrology::BodyDiagonalOptions options;
  options.iso.coverage_factor = st.coverage;
  options.iso230_2 = std::all_of(
      per_target.begin(), per_target.end(), [](const auto& kv) { return kv.second >= 2; });
  if (!options.iso230_2)
    printNotices({"ISO 230-2 statistics need at least 2 runs per target and direction; omitted"});
  const auto r = metrology::evaluateBodyDiagonals(samples, size, options);
  if (st.io.json) {
    Json j;
    j["method"] = "body";
    j["size"] = {size.x(), size.y(), size.z()};
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
    printJson(j);
    return;
  }
  auto& o = out.text();
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

// ---- comparison with direct measurements (2-D XY prediction) ----------------------------------

Json runCompare(const DiagonalsState& st, const metrology::PlaneErrorModel& model, Output& out) {
  Json list = Json::array();
  if (st.compare.empty()) return list;
  if (!st.io.json) out.text() += "# compare,file,quantity,points,rms_mm,max_abs_mm\n";
  for (const std::string& path : st.compare) {
    const io::TextTable t = io::TextTable::read(path);
    const LineFile f = readLineFile(t);
    if (std::abs(f.direction.z()) > kDirectionTolerance)
      t.failHeader("--compare: the line must lie in the XY plane");
    const std::string quantity = t.meta("quantity").value_or("linear");
    Eigen::Vector2d sensitive = f.direction.head<2>().normalized();
    const bool straightness = quantity == "straightness";
    if (straightness) {
      const auto lateral = metaVector(t, "lateral");
      if (!lateral) t.failHeader("--compare: a straightness file needs '# lateral' metadata");
      sensitive = lateral->head<2>().normalized();
    } else if (quantity != "linear") {
      t.failHeader(fmt::format("--compare: quantity '{}' is not linear or straightness", quantity));
    }
    // Mean deviation per target (a straightness file's reading is the deviation itself).
    std::map<double, std::pair<double, int>> mean;
    for (std::size_t i = 0; i < f.target.size(); ++i) {
      auto& m = mean[f.target[i]];
      m.first += straightness ? f.deviation[i] + f.target[i] : f.deviation[i];
      ++m.second;
    }
    std::vector<double> s, v;
    for (const auto& [target, m] : mean) {
      s.push_back(target);
      v.push_back(m.first / m.second);
    }
    const auto c = metrology::comparePlanePrediction(model,
                                                     f.start.head<2>(),
                                                     f.direction.head<2>().normalized(),
                                                     sensitive,
                                                     s,
                                                     v,
                                                     straightness);
    if (!st.io.json) {
      out.text() +=
          fmt::format("# compare,{},{},{},{},{}\n", path, quantity, s.size(), c.rms, c.max_abs);
      continue;
    }
    list.push_back({{"file", path},
                    {"quantity", quantity},
                    {"rms", c.rms},
                    {"max_abs", c.max_abs},
                    {"position", c.positions},
                    {"measured", c.measured},
                    {"predicted", c.predicted}});
  }
  return list;
}

// ---- step -------------------------------------------------------------------------------------

void runStep(const DiagonalsState& st, const Eigen::Vector3d& size, Output& out) {
  std::vector<metrology::StepDiagonalPass> passes;
  for (const std::string& path : st.io.data) {
    const io::TextTable t = io::TextTable::read(path);
    std::vector<BodyDiagonal> diag;
    std::vector<double> target, deviation;
    std::vector<int> run, dir, sub;
    std::vector<std::size_t> row_of;
    if (isLineFile(t)) {
      const LineFile f = readLineFile(t);
      diag.assign(f.target.size(), identifyDiagonal(t, f, size));
      target = f.target;
      deviation = f.deviation;
      run = f.run;
      dir = f.dir;
      sub = f.sub_step;
    } else {
      const std::size_t cd = t.column({"diagonal"});
      const std::size_t cp = t.column({"position", "target", "target_mm"});
      const std::size_t cs = t.column({"sub_step"});
      const std::size_t cv = t.column({"deviation", "deviation_mm"});
      const auto crun = t.findColumn({"run"});
      const auto cdir = t.findColumn({"direction"});
      for (std::size_t r = 0; r < t.rows(); ++r) {
        diag.push_back(diagonalField(t, r, cd));
        target.push_back(t.number(r, cp));
        sub.push_back(static_cast<int>(t.integer(r, cs)));
        deviation.push_back(t.number(r, cv));
        run.push_back(crun ? static_cast<int>(t.integer(r, *crun)) : 1);
        dir.push_back(cdir ? t.direction(r, *cdir) : 1);
      }
    }
    // Passes: consecutive rows of one (diagonal, run, direction); sub_step 1 opens a step.
    for (std::size_t r = 0; r < target.size(); ++r) {
      if (sub[r] < 1 || sub[r] > 3)
        t.fail(r, fmt::format("sub_step must be 1, 2 or 3 (X, Y, Z sub-moves), got {}", sub[r]));
      const bool new_pass =
          r == 0 || diag[r] != diag[r - 1] || run[r] != run[r - 1] || dir[r] != dir[r - 1];
      if (new_pass) passes.push_back({diag[r], {}});
      auto& steps = passes.back().steps;
      if (sub[r] == 1) steps.emplace_back();
      if (steps.empty() || (sub[r] > 1 && sub[r - 1] != sub[r] - 1))
        t.fail(r, "sub-steps of a step must come in the order 1, 2, 3");
      steps.back().deviation[static_cast<std::size_t>(sub[r] - 1)] = deviation[r];
      steps.back().target = target[r];
    }
  }
  const auto r = metrology::extractStepDiagonal(passes, size);
  const auto model = metrology::planeModel(r);
  Json compare = runCompare(st, model, out);
  static constexpr const char* kNames[3][3] = {
      {"EXX", "EYX", "EZX"}, {"EXY", "EYY", "EZY"}, {"EXZ", "EYZ", "EZZ"}};
  if (st.io.json) {
    Json j;
    j["method"] = "step";
    j["size"] = {size.x(), size.y(), size.z()};
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
    if (!compare.empty()) j["compare"] = compare;
    printJson(j);
    return;
  }
  auto& o = out.text();
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

// ---- shifted ----------------------------------------------------------------------------------

void runShifted(const DiagonalsState& st, const Eigen::Vector3d& size, Output& out) {
  std::vector<metrology::ShiftedDiagonalMeasurement> ms;
  for (const std::string& path : st.io.data) {
    const io::TextTable t = io::TextTable::read(path);
    if (isLineFile(t)) {
      const LineFile f = readLineFile(t);
      const auto d = diagonalAt(f.start, size);
      if (!d) t.failHeader("line start is not a start corner of a body diagonal");
      // Length error: mean deviation at the last target minus that at the first.
      const double lo = *std::min_element(f.target.begin(), f.target.end());
      const double hi = *std::max_element(f.target.begin(), f.target.end());
      double at_lo = 0.0, at_hi = 0.0;
      int n_lo = 0, n_hi = 0;
      for (std::size_t i = 0; i < f.target.size(); ++i) {
        if (f.target[i] == lo) at_lo += f.deviation[i], ++n_lo;
        if (f.target[i] == hi) at_hi += f.deviation[i], ++n_hi;
      }
      if (std::abs(lo) > kCornerTolerance) t.failHeader("the first target must be 0 (the corner)");
      const Eigen::Vector3d end = f.start + hi * f.direction;
      const Eigen::Vector3d diff = end - (f.start + metrology::diagonalTravel(*d, size));
      metrology::ShiftedDiagonalMeasurement m{*d, -1, 0.0, at_hi / n_hi - at_lo / n_lo};
      for (int a = 0; a < 3; ++a) {
        if (std::abs(diff[a]) <= kCornerTolerance) continue;
        if (m.axis >= 0) t.failHeader("the end point is shifted along more than one axis");
        m.axis = a;
        m.shift = diff[a];
      }
      ms.push_back(m);
      continue;
    }
    const std::size_t cd = t.column({"diagonal"});
    const std::size_t ca = t.column({"shift_axis"});
    const std::size_t cs = t.column({"shift", "shift_mm"});
    const std::size_t ce = t.column({"length_error", "length_error_mm"});
    for (std::size_t r = 0; r < t.rows(); ++r) {
      const std::string_view a = t.text(r, ca);
      int axis = -2;
      if (a == "-" || a == "none") axis = -1;
      if (a == "x" || a == "X") axis = 0;
      if (a == "y" || a == "Y") axis = 1;
      if (a == "z" || a == "Z") axis = 2;
      if (axis == -2) t.fail(r, fmt::format("shift_axis '{}' is not x, y, z or none", a));
      ms.push_back({diagonalField(t, r, cd), axis, t.number(r, cs), t.number(r, ce)});
    }
  }
  const auto r = metrology::evaluateShiftedDiagonals(ms, size);
  Json compare = runCompare(st, metrology::planeModel(r), out);
  if (st.io.json) {
    Json j;
    j["method"] = "shifted";
    j["size"] = {size.x(), size.y(), size.z()};
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
    if (!compare.empty()) j["compare"] = compare;
    printJson(j);
    return;
  }
  auto& o = out.text();
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

void runDiagonals(const DiagonalsState& st) {
  if (st.size.size() != 3) throw CLI::ValidationError("--size", "needs LX,LY,LZ");
  const Eigen::Vector3d size(st.size[0], st.size[1], st.size[2]);
  metrology::requireBoxSize(size);
  Output out;
  if (st.method == "body") {
    if (!st.compare.empty())
      throw CLI::ValidationError("--compare", "needs --method step or shifted");
    runBody(st, size, out);
  } else if (st.method == "step") {
    runStep(st, size, out);
  } else {
    runShifted(st, size, out);
  }
}

void addDiagonals(CLI::App& analyze) {
  auto st = std::make_shared<DiagonalsState>();
  CLI::App* cmd = analyze.add_subcommand(
      "diagonals",
      "diagonal displacement tests: ISO 230-6 body diagonals, shifted diagonals (seed 001), "
      "step diagonals (Wang)");
  st->io.add(*cmd);
  cmd->add_option("--method", st->method, "body (default), shifted or step")
      ->check(CLI::IsMember({"body", "shifted", "step"}));
  cmd->add_option("--size", st->size, "LX,LY,LZ: the box of the diagonals, mm")
      ->required()
      ->delimiter(',')
      ->expected(3);
  cmd->add_option("--coverage", st->coverage, "ISO 230-2 coverage factor k (default 2)");
  cmd->add_option("--compare",
                  st->compare,
                  "measurement files of XY lines (linear or straightness) to compare with the 2-D "
                  "prediction (step, shifted)")
      ->check(CLI::ExistingFile);
  cmd->callback([st] { runDiagonals(*st); });
}

const AnalyzeRegistration kRegisterDiagonals{50, &addDiagonals};

}  // namespace
}  // namespace pkm::cli
