// `pkm analyze iso230-2 | straightness | parallelism | squareness`: ISO 230-2 positioning,
// straightness about end-point / least-squares / minimum-zone lines, parallelism from two
// straightness runs along one beam and face-diagonal squareness (seed 000 §3).
// docs/analysis.md, "Positioning".
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "analyze_common.hpp"
#include "cli_common.hpp"
#include "pkm/core/error.hpp"
#include "pkm/geometry/error_table.hpp"
#include "pkm/io/text_table.hpp"
#include "pkm/metrology/face_diagonal.hpp"
#include "pkm/metrology/iso230_2.hpp"
#include "pkm/metrology/parallelism.hpp"
#include "pkm/metrology/straightness.hpp"
#include "positioning_input.hpp"

namespace pkm::cli {
namespace {

using Json = nlohmann::ordered_json;

// --- shared readers -----------------------------------------------------------------------

// isMeasurementFile, Profile, meanProfile, readStraightness: positioning_input.hpp.

std::string num(double v) { return std::isfinite(v) ? fmt::format("{:.6g}", v) : "-"; }

// --- iso230-2 ------------------------------------------------------------------------------

struct Iso230_2State {
  AnalyzeIo io;
  double coverage = 2.0;
};

Json targetJson(const metrology::TargetStatistics& t) {
  return Json{{"target", t.target},
              {"mean_up", t.mean_up},
              {"mean_down", t.mean_down},
              {"mean", t.mean},
              {"reversal", t.reversal},
              {"s_up", t.s_up},
              {"s_down", t.s_down},
              {"repeatability_up", t.repeatability_up},
              {"repeatability_down", t.repeatability_down},
              {"repeatability", t.repeatability},
              {"runs_up", t.runs_up},
              {"runs_down", t.runs_down}};
}

void runIso230_2(const Iso230_2State& st) {
  const std::vector<metrology::PositioningSample> samples = readPositioningSamples(st.io.data);
  const metrology::Iso230_2Result r =
      metrology::evaluateIso230_2(samples, {.coverage_factor = st.coverage});
  if (st.io.json) {
    Json j{{"B", r.B},
           {"B_mean", r.B_mean},
           {"R_up", r.R_up},
           {"R_down", r.R_down},
           {"R", r.R},
           {"E_up", r.E_up},
           {"E_down", r.E_down},
           {"E", r.E},
           {"M", r.M},
           {"A_up", r.A_up},
           {"A_down", r.A_down},
           {"A", r.A},
           {"bidirectional", r.bidirectional},
           {"coverage_factor", st.coverage}};
    Json targets = Json::array();
    for (const auto& t : r.targets) targets.push_back(targetJson(t));
    j["targets"] = std::move(targets);
    printJson(j);
    return;
  }
  Output out;
  out.text() +=
      fmt::format("ISO 230-2 positioning ({} targets, k = {})\n", r.targets.size(), st.coverage);
  out.text() += "target\tmean_up\tmean_down\treversal\ts_up\ts_down\tR_up\tR_down\tR\n";
  for (const auto& t : r.targets) {
    out.text() += fmt::format("{}\t{}\t{}\t{}\t{}\t{}\t{}\t{}\t{}\n",
                              num(t.target),
                              num(t.mean_up),
                              num(t.mean_down),
                              num(t.reversal),
                              num(t.s_up),
                              num(t.s_down),
                              num(t.repeatability_up),
                              num(t.repeatability_down),
                              num(t.repeatability));
  }
  for (const auto& [name, v] : std::vector<std::pair<const char*, double>>{{"B", r.B},
                                                                           {"B_mean", r.B_mean},
                                                                           {"R_up", r.R_up},
                                                                           {"R_down", r.R_down},
                                                                           {"R", r.R},
                                                                           {"E_up", r.E_up},
                                                                           {"E_down", r.E_down},
                                                                           {"E", r.E},
                                                                           {"M", r.M},
                                                                           {"A_up", r.A_up},
                                                                           {"A_down", r.A_down},
                                                                           {"A", r.A}}) {
    out.text() += fmt::format("{}\t{}\n", name, num(v));
  }
}

void addIso230_2(CLI::App& analyze) {
  auto st = std::make_shared<Iso230_2State>();
  CLI::App* cmd = analyze.add_subcommand(
      "iso230-2",
      "ISO 230-2 positioning accuracy and repeatability; header target,direction,run,measured "
      "(or pkm simulate measurement files)");
  st->io.add(*cmd);
  cmd->add_option("--coverage", st->coverage, "coverage factor k (ISO 230-2:2014: 2)")
      ->check(CLI::PositiveNumber);
  cmd->callback([st] { runIso230_2(*st); });
}

const AnalyzeRegistration kRegisterIso230_2{10, &addIso230_2};

// --- straightness --------------------------------------------------------------------------

struct StraightnessState {
  AnalyzeIo io;
  std::string reference = "lsq";
};

void runStraightness(const StraightnessState& st) {
  const auto reference = metrology::parseStraightnessReference(st.reference);
  const Profile p = readStraightness(st.io.data);
  const metrology::StraightnessResult r =
      metrology::evaluateStraightness(p.position, p.value, reference);
  if (st.io.json) {
    Json j{{"reference", std::string(metrology::toString(reference))},
           {"slope", r.line.slope},
           {"intercept", r.line.intercept},
           {"straightness", r.straightness},
           {"points", p.position.size()}};
    if (!r.contact_points.empty()) {
      Json contacts = Json::array();
      for (std::size_t k : r.contact_points) {
        contacts.push_back(Json{
            {"position", p.position[k]}, {"deviation", p.value[k]}, {"residual", r.residuals[k]}});
      }
      j["contact_points"] = std::move(contacts);
    }
    Json residuals = Json::array();
    for (std::size_t k = 0; k < p.position.size(); ++k) {
      residuals.push_back(Json::array({p.position[k], r.residuals[k]}));
    }
    j["residuals"] = std::move(residuals);
    printJson(j);
    return;
  }
  Output out;
  out.text() += fmt::format("straightness ({} reference line, {} points)\n",
                            metrology::toString(reference),
                            p.position.size());
  out.text() += fmt::format("slope\t{}\nintercept\t{}\nstraightness\t{}\n",
                            num(r.line.slope),
                            num(r.line.intercept),
                            num(r.straightness));
  for (std::size_t k : r.contact_points) {
    out.text() += fmt::format("contact\t{}\t{}\n", num(p.position[k]), num(r.residuals[k]));
  }
}

void addStraightness(CLI::App& analyze) {
  auto st = std::make_shared<StraightnessState>();
  CLI::App* cmd = analyze.add_subcommand(
      "straightness",
      "straightness about a reference line; header position,deviation (or pkm simulate "
      "straightness files, averaged per target)");
  st->io.add(*cmd);
  cmd->add_option("--reference", st->reference, "reference line: endpoint, lsq or minzone")
      ->check(CLI::IsMember({"endpoint", "lsq", "minzone"}));
  cmd->callback([st] { runStraightness(*st); });
}

const AnalyzeRegistration kRegisterStraightness{20, &addStraightness};

// --- parallelism ---------------------------------------------------------------------------

struct ParallelismState {
  std::vector<std::string> reference, axis;
  int reference_sign = 1, axis_sign = 1;
  std::string line = "lsq";
  std::string plane = "horizontal";
  std::optional<double> szX2;
  bool json = false;
};

void runParallelism(const ParallelismState& st) {
  const Profile ref = readStraightness(st.reference);
  const Profile axis = readStraightness(st.axis);
  const metrology::ParallelismResult r =
      metrology::evaluateParallelism({ref.position, ref.value, st.reference_sign},
                                     {axis.position, axis.value, st.axis_sign},
                                     {metrology::parseStraightnessReference(st.line)});
  const bool horizontal = st.plane == "horizontal";
  const char* diff_key = horizontal ? "dgamma" : "dalpha";
  std::optional<std::pair<const char*, double>> square;
  if (!horizontal) {
    square = {"sxP", metrology::pkmSquarenessFromSlopes(0.0, r.slope_difference, 0.0).sxP};
  } else if (st.szX2) {
    square = {"szP", metrology::pkmSquarenessFromSlopes(r.slope_difference, 0.0, *st.szX2).szP};
  }
  if (st.json) {
    Json j{{"plane", st.plane},
           {"line", st.line},
           {"reference_slope", r.reference_slope},
           {"axis_slope", r.axis_slope},
           {"slope_difference", r.slope_difference},
           {diff_key, r.slope_difference},
           {"parallelism", r.parallelism},
           {"max_deviation", r.max_deviation}};
    if (square) j[square->first] = square->second;
    Json profile = Json::array();
    for (std::size_t k = 0; k < axis.position.size(); ++k) {
      profile.push_back(Json::array({axis.position[k], r.deviations[k]}));
    }
    j["deviations"] = std::move(profile);
    printJson(j);
    return;
  }
  Output out;
  out.text() += fmt::format("parallelism ({} plane, {} representative lines)\n", st.plane, st.line);
  out.text() += fmt::format(
      "reference_slope\t{}\naxis_slope\t{}\n{}\t{}\nparallelism\t{}\n"
      "max_deviation\t{}\n",
      num(r.reference_slope),
      num(r.axis_slope),
      diff_key,
      num(r.slope_difference),
      num(r.parallelism),
      num(r.max_deviation));
  if (square) out.text() += fmt::format("{}\t{}\n", square->first, num(square->second));
}

void addParallelism(CLI::App& analyze) {
  auto st = std::make_shared<ParallelismState>();
  CLI::App* cmd = analyze.add_subcommand(
      "parallelism",
      "parallelism of an axis to a reference axis from two straightness runs along one beam "
      "(seed 000 §3.1); header position,deviation (or pkm simulate straightness files)");
  cmd->add_option("--reference", st->reference, "straightness file(s) of the reference axis")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--axis", st->axis, "straightness file(s) of the axis")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--reference-sign",
                  st->reference_sign,
                  "+1 or -1: the reference run's positions along (+1) or against (-1) the beam")
      ->check(CLI::IsMember({-1, 1}));
  cmd->add_option("--axis-sign", st->axis_sign, "+1 or -1, as --reference-sign for the axis run")
      ->check(CLI::IsMember({-1, 1}));
  cmd->add_option("--line", st->line, "representative lines: endpoint or lsq (default)")
      ->check(CLI::IsMember({"endpoint", "lsq", "minzone"}));
  cmd->add_option(
         "--plane", st->plane, "horizontal (slope difference dgamma) or vertical (dalpha = sxP)")
      ->check(CLI::IsMember({"horizontal", "vertical"}));
  cmd->add_option("--szX2", st->szX2, "szX2 in rad (horizontal plane: also report szP)");
  cmd->add_flag("--json", st->json, "print one JSON object instead of a table");
  cmd->callback([st] { runParallelism(*st); });
}

const AnalyzeRegistration kRegisterParallelism{30, &addParallelism};

// --- squareness (face diagonals) ------------------------------------------------------------

struct SquarenessState {
  AnalyzeIo io;
  std::vector<std::string> start, pdge;
  std::string axes;
  bool scale = false, first_work = false, second_work = false;
};

std::vector<double> parseList(const std::string& text, std::size_t count, const char* what) {
  std::vector<double> v;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    try {
      std::size_t used = 0;
      v.push_back(std::stod(item, &used));
      if (used != item.size() || !std::isfinite(v.back())) throw std::invalid_argument(item);
    } catch (const std::exception&) {
      throw InvalidArgument(fmt::format("{}: '{}' is not a list of {} numbers", what, text, count));
    }
  }
  if (v.size() != count) {
    throw InvalidArgument(fmt::format("{}: '{}' is not a list of {} numbers", what, text, count));
  }
  return v;
}

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

/// A PDGE term from `AC=FILE`: A, C in {u, v} (table over the first/second axis position,
/// displacing along the first/second axis).
metrology::PdgeTerm readPdge(const std::string& spec) {
  const auto eq = spec.find('=');
  const std::string key = spec.substr(0, eq);
  if (eq == std::string::npos || key.size() != 2 || (key[0] != 'u' && key[0] != 'v') ||
      (key[1] != 'u' && key[1] != 'v')) {
    throw InvalidArgument(
        fmt::format("--pdge '{}': expected uu=FILE, uv=FILE, vv=FILE or vu=FILE", spec));
  }
  const io::TextTable t = io::TextTable::read(spec.substr(eq + 1));
  Profile p;
  if (isMeasurementFile(t)) {
    const std::string quantity = t.meta("quantity").value_or("linear");
    if (quantity != "linear" && quantity != "straightness") {
      t.failHeader(
          fmt::format("--pdge: a {} file is not a positioning or straightness table", quantity));
    }
    const std::vector<io::TextTable> one{t};
    p = meanProfile(one, quantity == "linear");
    // The table is over the axis position start + s·direction of the one moving axis.
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
    return {geometry::ErrorTable1d(p.position, values),
            key[0] == 'u' ? 0 : 1,
            key[1] == 'u' ? 0 : 1,
            1.0,
            0.0};
  } catch (const InvalidArgument& e) {
    throw IoError(fmt::format("{}: {}", t.source(), e.what()));
  }
}

void runSquareness(const SquarenessState& st) {
  std::vector<metrology::FaceDiagonal> diagonals;
  // Simulator diagonal files, grouped by measurement (runs averaged per target).
  std::map<std::string, std::vector<io::TextTable>> sim;
  std::vector<std::string> sim_order;
  std::size_t plain = 0;
  for (const std::string& f : st.io.data) {
    io::TextTable t = io::TextTable::read(f);
    if (isMeasurementFile(t)) {
      const std::string key = t.meta("measurement").value_or(f);
      if (!sim.count(key)) sim_order.push_back(key);
      sim[key].push_back(std::move(t));
      continue;
    }
    metrology::FaceDiagonal d;
    if (plain < st.start.size()) {
      const auto s = parseList(st.start[plain], 2, "--start");
      d.start_a = s[0];
      d.start_b = s[1];
    }
    ++plain;
    const std::size_t cu = t.column({"u"}), cv = t.column({"v"}), cd = t.column({"deviation"});
    for (std::size_t r = 0; r < t.rows(); ++r) {
      d.points.push_back({t.number(r, cu), t.number(r, cv), t.number(r, cd)});
    }
    diagonals.push_back(std::move(d));
  }
  for (const std::string& key : sim_order) {
    const io::TextTable& first = sim[key].front();
    const std::vector<double> start = metaNumbers(first, "line start");
    const std::vector<double> dir = metaNumbers(first, "line direction");
    std::vector<std::string> names;
    if (const auto axes = first.meta("axes")) {
      std::stringstream in(*axes);
      for (std::string n; std::getline(in, n, ',');) names.push_back(n);
    }
    if (start.size() != dir.size() || (!names.empty() && names.size() != dir.size())) {
      first.failHeader("'# line start', '# line direction' and '# axes' differ in size");
    }
    std::vector<std::size_t> moving;
    if (!st.axes.empty()) {
      std::stringstream in(st.axes);
      for (std::string n; std::getline(in, n, ',');) {
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
    const Profile p = meanProfile(sim[key], true);
    metrology::FaceDiagonal d{{}, start[moving[0]], start[moving[1]]};
    for (std::size_t k = 0; k < p.position.size(); ++k) {
      const double s = p.position[k];
      d.points.push_back({s * dir[moving[0]], s * dir[moving[1]], p.value[k]});
    }
    diagonals.push_back(std::move(d));
  }
  std::vector<metrology::PdgeTerm> pdge;
  for (const std::string& spec : st.pdge) pdge.push_back(readPdge(spec));
  const metrology::FaceDiagonalResult r =
      metrology::fitFaceDiagonalSquareness(diagonals,
                                           pdge,
                                           {.fit_scale = st.scale,
                                            .first_moves_work = st.first_work,
                                            .second_moves_work = st.second_work});
  if (st.io.json) {
    Json j{{"squareness", r.squareness},
           {"residual_rms", r.residual_rms},
           {"diagonals", diagonals.size()},
           {"points", r.points_used}};
    if (r.scale) {
      j["scale"] = Json::array({(*r.scale)[0], (*r.scale)[1]});
      j["scale_model"] = r.scale_per_axis ? "per_axis" : "common";
    }
    printJson(j);
    return;
  }
  Output out;
  out.text() +=
      fmt::format("face-diagonal squareness ({} diagonals, {} readings, {} PDGE tables)\n",
                  diagonals.size(),
                  r.points_used,
                  pdge.size());
  out.text() +=
      fmt::format("squareness\t{} rad\nresidual_rms\t{}\n", num(r.squareness), num(r.residual_rms));
  if (r.scale) {
    out.text() += fmt::format("scale\t{}\t{}\t({})\n",
                              num((*r.scale)[0]),
                              num((*r.scale)[1]),
                              r.scale_per_axis ? "per axis" : "common");
  }
}

void addSquareness(CLI::App& analyze) {
  auto st = std::make_shared<SquarenessState>();
  CLI::App* cmd = analyze.add_subcommand(
      "squareness",
      "squareness from face-diagonal displacement (seed 000 eqs 4-10); --data once per "
      "diagonal, header u,v,deviation (or pkm simulate diagonal files)");
  st->io.add(*cmd);
  cmd->add_option("--start",
                  st->start,
                  "A,B: axis positions at the start of each u,v diagonal, in --data order "
                  "(default 0,0); used to look up the PDGE tables");
  cmd->add_option("--pdge",
                  st->pdge,
                  "AC=FILE: a measured PDGE table over axis A (u: first, v: second) displacing "
                  "along axis C; header position,deviation or a pkm simulate linear or "
                  "straightness file");
  cmd->add_option("--axes", st->axes, "A,B: the two axes of simulator diagonal files");
  cmd->add_flag("--scale", st->scale, "also fit the scale errors (needs two diagonals)");
  cmd->add_flag(
      "--first-moves-work", st->first_work, "the first axis moves the work, not the tool");
  cmd->add_flag("--second-moves-work",
                st->second_work,
                "the second axis moves the work, not the tool (seed 000: Y2)");
  cmd->callback([st] { runSquareness(*st); });
}

const AnalyzeRegistration kRegisterSquareness{40, &addSquareness};

}  // namespace
}  // namespace pkm::cli
