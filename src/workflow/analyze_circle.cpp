// `pkm analyze circle | circular | probe-offset` as workflows (workflow/analyze_circle.hpp).
#include "pkm/workflow/analyze_circle.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <map>
#include <string>
#include <utility>

#include "data_errors.hpp"
#include "pkm/core/error.hpp"
#include "pkm/core/parallel.hpp"
#include "pkm/core/units.hpp"
#include "pkm/io/number_table.hpp"
#include "pkm/io/text_table.hpp"
#include "pkm/metrology/circular_uncertainty.hpp"
#include "pkm/metrology/profile_uncertainty.hpp"

namespace pkm::workflow {
namespace {

using metrology::Point2;

void requireData(const std::vector<io::NamedText>& data) {
  if (data.empty()) throw IoError("give at least one data file");
}

void requirePositive(const std::optional<double>& v, const char* what) {
  if (v && !(std::isfinite(*v) && *v > 0.0))
    throw InvalidArgument(fmt::format("{} must be > 0, got {}", what, *v));
}

/// "cw"/"CW"/"-" or "ccw"/"CCW"/"+" of row r; throws pkm::IoError otherwise.
bool clockwise(const io::TextTable& t, std::size_t r, std::size_t col) {
  const std::string_view d = t.text(r, col);
  if (d == "cw" || d == "CW" || d == "-") return true;
  if (d == "ccw" || d == "CCW" || d == "+") return false;
  t.fail(r, fmt::format("direction must be cw or ccw, got '{}'", d));
}

/// Nearest multiple of 360° to `deg` removed: (−180, 180].
double wrapDeg(double deg) {
  double w = std::remainder(deg, 360.0);
  return w <= -180.0 ? w + 360.0 : w;
}

struct Labelled {
  std::string touch;
  long long run = 1;
  double turn_deg = 0.0;
  Point2 p;
};

/// Lee et al. (2019), eqs. 8-9 per run from labelled touches: x1, y1 from the ±x and ±y touches at
/// turn 0, x2 and y3 from the +x and +y touches at turn 180°; averaged over the runs that have all
/// six touches, or nullopt.
std::optional<io::PaperProbeOffset> paperOffset(const std::vector<Labelled>& touches,
                                                double ring_radius,
                                                double stylus_radius) {
  constexpr double kTurnToleranceDeg = 10.0;
  std::map<long long, std::map<std::string, Point2>> by_run;
  for (const Labelled& t : touches) {
    const double w = wrapDeg(t.turn_deg);
    const char* tag = std::abs(w) < kTurnToleranceDeg                     ? "@0"
                      : std::abs(std::abs(w) - 180.0) < kTurnToleranceDeg ? "@180"
                                                                          : nullptr;
    if (tag != nullptr) by_run[t.run][t.touch + tag] = t.p;
  }
  Eigen::Vector2d s9 = Eigen::Vector2d::Zero(), s8 = Eigen::Vector2d::Zero();
  int runs = 0;
  for (const auto& [run, m] : by_run) {
    const char* need[] = {"+x@0", "-x@0", "+y@0", "-y@0", "+x@180", "+y@180"};
    bool all = true;
    for (const char* n : need) all = all && m.count(n) > 0;
    if (!all) continue;
    const double x1 = 0.5 * (m.at("+x@0").x() + m.at("-x@0").x());
    const double y1 = 0.5 * (m.at("+y@0").y() + m.at("-y@0").y());
    s9 += metrology::probeOffsetEq9(
        x1, y1, m.at("+x@180").x(), m.at("+y@180").y(), ring_radius, stylus_radius);
    s8 += metrology::probeOffsetEq8(
        x1, y1, m.at("+x@180").x(), m.at("+y@180").y(), ring_radius, stylus_radius);
    ++runs;
  }
  if (runs == 0) return std::nullopt;
  return io::PaperProbeOffset{s9 / runs, s8 / runs, runs};
}

/// The touches of one input (angles signed by the tool direction) and its labelled touches.
void readTouches(const io::TextTable& t,
                 double sign,
                 std::vector<metrology::ProbeTouch>& touches,
                 std::vector<Labelled>& labelled) {
  const std::size_t cs = t.column({"spindle_deg"});
  const std::size_t cx = t.column({"x", "x_mm"});
  const std::size_t cy = t.column({"y", "y_mm"});
  const auto cd = t.findColumn({"drm_deg"});
  const auto ct = t.findColumn({"touch"});
  const auto cr = t.findColumn({"run"});
  for (std::size_t r = 0; r < t.rows(); ++r) {
    const double turn = t.number(r, cs) + (cd ? t.number(r, *cd) : 0.0);
    const Point2 p(t.number(r, cx), t.number(r, cy));
    touches.push_back({sign * degToRad(turn), p});
    if (ct) {
      const std::string label(t.text(r, *ct));
      if (label != "+x" && label != "-x" && label != "+y" && label != "-y")
        t.fail(r, fmt::format("touch must be +x, -x, +y or -y, got '{}'", label));
      labelled.push_back({label, cr ? t.integer(r, *cr) : 1, turn, p});
    }
  }
}

}  // namespace

/// Touches the probe-offset budget needs (five unknowns and one degree of freedom).
constexpr std::size_t kMinTouchesForUncertainty = 6;

void CircleRequest::validate() const {
  if (fit != "lsc" && fit != "mzc" && fit != "both")
    throw InvalidArgument(fmt::format("--fit '{}': give lsc, mzc or both", fit));
  if (points.empty() && data_files.empty()) requireData(data);
  if (!points.empty() && !(data.empty() && data_files.empty()))
    throw IoError("circle: give data tables or points, not both");
}

void CircularRequest::validate() const {
  requireData(data);
  if (data.size() > 2) throw IoError("circular: give one or two data files");
  requirePositive(nominal_radius, "the nominal radius");
}

void ProbeOffsetRequest::validate() const {
  requireData(data);
  requirePositive(ring_diameter, "the ring diameter");
  requirePositive(stylus_diameter, "the stylus diameter");
}

namespace {

/// A master ring's certificate in the file (`# ring form mm`): its form deviation replaces the
/// sources' probe.ring_form_mm. Throws pkm::IoError naming the file for a value that is not a
/// length >= 0.
void ringCertificate(const io::NumberTable& t, metrology::UncertaintySources& sources) {
  const std::optional<std::string> form = t.meta("ring form mm");
  if (!form) return;
  double v = std::nan("");
  try {
    std::size_t used = 0;
    v = std::stod(*form, &used);
    if (used != form->size()) v = std::nan("");
  } catch (const std::exception&) {
  }
  if (!(std::isfinite(v) && v >= 0.0))
    t.failHeader(fmt::format("metadata 'ring form mm' must be a length >= 0, got '{}'", *form));
  sources.probe.ring_form_mm = v;
}

/// The rows of a table of two columns as points, where they are.
std::span<const Point2> pointsOf(const io::NumberTable& t) {
  static_assert(sizeof(Point2) == 2 * sizeof(double));
  return {reinterpret_cast<const Point2*>(t.values().data()), t.rows()};
}

/// The fits `request` asks for of `p`, their budgets, into `report`.
void fitCircles(const CircleRequest& request, std::span<const Point2> p, io::CircleReport& report) {
  report.has_lsc = request.fit != "mzc";
  report.has_mzc = request.fit != "lsc";
  report.lsc = metrology::fitCircle(p);
  if (report.has_mzc) {
    metrology::MinZoneOptions opt;
    opt.start = report.lsc.circle.center;
    report.mzc = metrology::fitMinimumZoneCircle(p, opt);
  }
  if (!request.budget) return;
  report.uncertainty = metrology::circleUncertainty(report.lsc, report.mzc, request.uncertainty);
  // Only the budgets of what is reported.
  std::erase_if(report.uncertainty, [&](const metrology::UncertaintyBudget& b) {
    return b.quantity == "roundness_mzc" ? !report.has_mzc : !report.has_lsc;
  });
}

/// analyzeCircle after the request's check; the texts are moved out of `request`, names kept.
io::CircleReport circle(CircleRequest& request) {
  io::CircleReport report;
  if (!request.points.empty()) {
    for (std::size_t r = 0; r < request.points.size(); ++r)
      for (Eigen::Index c = 0; c < 2; ++c)
        if (!std::isfinite(request.points[r][c]))
          throw IoError(fmt::format(
              "{}: row {} column {} is not a finite number", request.points_name, r, c));
    report.sources.beginInput(request.points_name);
    io::LineNumbers lines;
    for (std::size_t r = 0; r < request.points.size(); ++r) lines.add(r + 1);
    report.sources.addLines(lines);
    fitCircles(request, request.points, report);
    return report;
  }
  // Each table read in one pass on the cores (io::NumberTable); a file named by path is mapped,
  // not copied.
  std::vector<io::NumberTable> tables;
  const std::vector<io::ColumnNames> columns = {{"x", "x_mm"}, {"y", "y_mm"}};
  for (const io::NamedText& in : request.data)
    tables.push_back(io::NumberTable::parse(in.text, in.name, columns));
  for (const std::string& path : request.data_files)
    tables.push_back(io::NumberTable::read(path, columns));
  std::size_t rows = 0;
  for (const io::NumberTable& t : tables) {
    report.sources.beginInput(t.source());
    ringCertificate(t, request.uncertainty);
    report.sources.addLines(t.lineNumbers());
    rows += t.rows();
  }
  // One table is fitted where it is (its rows are x, y pairs, as Point2's two doubles).
  if (tables.size() == 1) {
    fitCircles(request, pointsOf(tables.front()), report);
    return report;
  }
  std::vector<Point2> p;
  p.reserve(rows);
  for (const io::NumberTable& t : tables) {
    const std::span<const Point2> q = pointsOf(t);
    p.insert(p.end(), q.begin(), q.end());
  }
  fitCircles(request, p, report);
  return report;
}

io::CircularReport circular(const CircularRequest& request) {
  std::vector<Point2> cw, ccw;
  std::vector<io::TextTable> tables;
  for (const io::NamedText& in : request.data)
    tables.push_back(io::TextTable::parseData(in.text, in.name));
  const bool labelled = tables.front().findColumn({"direction"}).has_value();
  if (!labelled && tables.size() != 2)
    throw IoError(
        "circular: give one file with a 'direction' column (cw/ccw) or two files, CW then CCW");
  for (std::size_t i = 0; i < tables.size(); ++i) {
    const io::TextTable& t = tables[i];
    const std::size_t cx = t.column({"x", "x_mm"});
    const std::size_t cy = t.column({"y", "y_mm"});
    const std::optional<std::size_t> cd =
        labelled ? std::optional<std::size_t>(t.column({"direction"})) : std::nullopt;
    for (std::size_t r = 0; r < t.rows(); ++r) {
      const bool is_cw = cd ? clockwise(t, r, *cd) : i == 0;
      (is_cw ? cw : ccw).emplace_back(t.number(r, cx), t.number(r, cy));
    }
  }
  metrology::CircularTestOptions opt;
  opt.centre = request.centre;
  opt.nominal_center = request.nominal_center;
  opt.nominal_radius = request.nominal_radius;
  io::CircularReport report;
  report.result = metrology::evaluateCircularTest(cw, ccw, opt);
  report.points_cw = cw.size();
  report.points_ccw = ccw.size();
  report.uncertainty =
      metrology::circularTestUncertainty(cw, ccw, report.result, request.uncertainty);
  return report;
}

io::ProbeOffsetReport probeOffset(const ProbeOffsetRequest& request) {
  std::vector<metrology::ProbeTouch> touches;
  std::vector<Labelled> labelled;
  for (const io::NamedText& in : request.data)
    readTouches(io::TextTable::parseData(in.text, in.name),
                request.tool_plus_z ? 1.0 : -1.0,
                touches,
                labelled);
  io::ProbeOffsetReport report;
  report.fit = metrology::fitProbeOffset(touches);
  report.touches = touches.size();
  report.tool_plus_z = request.tool_plus_z;
  std::optional<double> stylus_radius;
  if (request.stylus_diameter) stylus_radius = *request.stylus_diameter / 2.0;
  if (request.ring_diameter) {
    report.effective_stylus_radius =
        metrology::effectiveStylusRadius(*request.ring_diameter, report.fit.ball_path_radius);
    if (!stylus_radius) stylus_radius = report.effective_stylus_radius;
    if (!labelled.empty())
      report.paper = paperOffset(labelled, *request.ring_diameter / 2.0, *stylus_radius);
  }
  if (touches.size() >= kMinTouchesForUncertainty)
    report.uncertainty =
        metrology::probeOffsetUncertainty(report.fit, touches, request.uncertainty);
  return report;
}

}  // namespace

io::CircleReport analyzeCircle(CircleRequest request) {
  request.validate();
  return detail::namingData({request.data}, [&] { return circle(request); });
}

io::CircularReport analyzeCircular(const CircularRequest& request) {
  request.validate();
  return detail::namingData({request.data}, [&] { return circular(request); });
}

io::ProbeOffsetReport analyzeProbeOffset(const ProbeOffsetRequest& request) {
  request.validate();
  return detail::namingData({request.data}, [&] { return probeOffset(request); });
}

}  // namespace pkm::workflow
