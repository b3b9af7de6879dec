// `pkm analyze circle | circular | probe-offset`: least-squares and minimum-zone circles with
// roundness, ISO 230-4 circular deviation and hysteresis, and the touch-probe stylus offset from
// master-ring touches with spindle reversal (seed 003). docs/analysis.md, "Circles".
#include <fmt/format.h>

#include <cmath>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "analyze_common.hpp"
#include "cli_common.hpp"
#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/io/text_table.hpp"
#include "pkm/metrology/circle_fit.hpp"
#include "pkm/metrology/circular_test.hpp"
#include "pkm/metrology/min_zone_circle.hpp"
#include "pkm/metrology/probe_offset.hpp"

namespace pkm::cli {
namespace {

using Json = nlohmann::ordered_json;
using metrology::Point2;

/// A number with 9 significant digits for the tables, "-" when not finite.
std::string num9(double v) { return std::isfinite(v) ? fmt::format("{:.9g}", v) : "-"; }
Json pair(const Point2& p) { return Json::array({p.x(), p.y()}); }

/// Where a point came from, for the contact points.
struct Origin {
  std::string file;
  std::size_t line = 0;
};

/// x, y of every row of every file, concatenated.
void readXy(const std::vector<std::string>& files,
            std::vector<Point2>& points,
            std::vector<Origin>& origin) {
  for (const std::string& f : files) {
    const io::TextTable t = io::TextTable::read(f);
    const std::size_t cx = t.column({"x", "x_mm"});
    const std::size_t cy = t.column({"y", "y_mm"});
    for (std::size_t r = 0; r < t.rows(); ++r) {
      points.emplace_back(t.number(r, cx), t.number(r, cy));
      origin.push_back({t.source(), t.line(r)});
    }
  }
}

// --- circle ------------------------------------------------------------------------------------

struct CircleState {
  AnalyzeIo io;
};

void runCircle(const CircleState& st) {
  std::vector<Point2> p;
  std::vector<Origin> origin;
  readXy(st.io.data, p, origin);
  const metrology::CircleFit lsc = metrology::fitCircle(p);
  metrology::MinZoneOptions opt;
  opt.start = lsc.circle.center;
  const metrology::MinZoneCircle mzc = metrology::fitMinimumZoneCircle(p, opt);
  if (st.io.json) {
    Json contacts = Json::array();
    for (const metrology::ZoneContact& c : mzc.contacts)
      contacts.push_back(Json{{"circle", c.outer ? "outer" : "inner"},
                              {"x", c.point.x()},
                              {"y", c.point.y()},
                              {"index", c.index},
                              {"file", origin[c.index].file},
                              {"line", origin[c.index].line}});
    printJson(Json{{"center", pair(lsc.circle.center)},
                   {"radius", lsc.circle.radius},
                   {"diameter", 2.0 * lsc.circle.radius},
                   {"roundness_lsc", lsc.roundness},
                   {"roundness_mzc", mzc.roundness},
                   {"mzc_center", pair(mzc.center)},
                   {"mzc_inner_radius", mzc.inner_radius},
                   {"mzc_outer_radius", mzc.outer_radius},
                   {"mzc_contacts", std::move(contacts)},
                   {"mzc_certified", mzc.certified},
                   {"rms", lsc.rms},
                   {"points", p.size()}});
    return;
  }
  Output out;
  out.text() += fmt::format("circle ({} points)\n", p.size());
  out.text() += fmt::format("LSC centre\t{}\t{}\nLSC radius\t{}\nLSC diameter\t{}\n",
                            num9(lsc.circle.center.x()),
                            num9(lsc.circle.center.y()),
                            num9(lsc.circle.radius),
                            num9(2.0 * lsc.circle.radius));
  out.text() += fmt::format(
      "roundness LSC\t{}\nroundness MZC\t{}\n", num9(lsc.roundness), num9(mzc.roundness));
  out.text() += fmt::format("MZC centre\t{}\t{}\nMZC radii\t{}\t{}\nMZC certified\t{}\n",
                            num9(mzc.center.x()),
                            num9(mzc.center.y()),
                            num9(mzc.inner_radius),
                            num9(mzc.outer_radius),
                            mzc.certified ? "yes" : "no");
  for (const metrology::ZoneContact& c : mzc.contacts)
    out.text() += fmt::format("MZC contact\t{}\t{}\t{}\t{}:{}\n",
                              c.outer ? "outer" : "inner",
                              num9(c.point.x()),
                              num9(c.point.y()),
                              origin[c.index].file,
                              origin[c.index].line);
}

void addCircle(CLI::App& analyze) {
  auto st = std::make_shared<CircleState>();
  CLI::App* cmd = analyze.add_subcommand(
      "circle",
      "least-squares and minimum-zone circle and roundness; header x,y (files concatenated)");
  st->io.add(*cmd);
  cmd->callback([st] { runCircle(*st); });
}

const AnalyzeRegistration kRegisterCircle{60, &addCircle};

// --- circular (ISO 230-4) ----------------------------------------------------------------------

struct CircularState {
  AnalyzeIo io;
  std::string centre = "lsc";
  std::vector<double> nominal_center;
  std::optional<double> nominal_radius;
};

Json runJson(const metrology::CircularRun& r) {
  Json j{{"center", pair(r.center)}, {"radius", r.radius}, {"G", r.circular_deviation}};
  if (r.radial_deviation_max) {
    j["F_max"] = *r.radial_deviation_max;
    j["F_min"] = *r.radial_deviation_min;
    j["F_mean"] = *r.mean_radial_deviation;
  }
  return j;
}

void runCircular(const CircularState& st) {
  std::vector<Point2> cw, ccw;
  std::vector<io::TextTable> tables;
  for (const std::string& f : st.io.data) tables.push_back(io::TextTable::read(f));
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
      bool is_cw = i == 0;
      if (cd) {
        const std::string_view d = t.text(r, *cd);
        if (d == "cw" || d == "CW" || d == "-")
          is_cw = true;
        else if (d == "ccw" || d == "CCW" || d == "+")
          is_cw = false;
        else
          t.fail(r, fmt::format("direction must be cw or ccw, got '{}'", d));
      }
      (is_cw ? cw : ccw).emplace_back(t.number(r, cx), t.number(r, cy));
    }
  }
  metrology::CircularTestOptions opt;
  if (st.centre == "mzc")
    opt.centre = metrology::CircularCentre::kMinimumZone;
  else if (st.centre == "nominal")
    opt.centre = metrology::CircularCentre::kNominal;
  if (!st.nominal_center.empty()) {
    if (st.nominal_center.size() != 2) throw IoError("--nominal-center needs X,Y");
    opt.nominal_center = Point2(st.nominal_center[0], st.nominal_center[1]);
  }
  opt.nominal_radius = st.nominal_radius;
  const metrology::CircularTestResult r = metrology::evaluateCircularTest(cw, ccw, opt);
  if (st.io.json) {
    printJson(Json{{"centre", st.centre},
                   {"G_cw", r.cw.circular_deviation},
                   {"G_ccw", r.ccw.circular_deviation},
                   {"G_bidirectional", r.bidirectional_deviation},
                   {"H", r.hysteresis},
                   {"H_angle_deg", radToDeg(r.hysteresis_angle)},
                   {"common_center", pair(r.common_center)},
                   {"cw", runJson(r.cw)},
                   {"ccw", runJson(r.ccw)},
                   {"points_cw", cw.size()},
                   {"points_ccw", ccw.size()}});
    return;
  }
  Output out;
  out.text() += fmt::format("ISO 230-4 circular test ({} CW, {} CCW points, centre {})\n",
                            cw.size(),
                            ccw.size(),
                            st.centre);
  out.text() += fmt::format("G cw\t{}\nG ccw\t{}\nG(b)\t{}\nH\t{}\nH at deg\t{}\n",
                            num9(r.cw.circular_deviation),
                            num9(r.ccw.circular_deviation),
                            num9(r.bidirectional_deviation),
                            num9(r.hysteresis),
                            num9(radToDeg(r.hysteresis_angle)));
  if (r.cw.radial_deviation_max)
    out.text() += fmt::format("F cw max/min/mean\t{}\t{}\t{}\nF ccw max/min/mean\t{}\t{}\t{}\n",
                              num9(*r.cw.radial_deviation_max),
                              num9(*r.cw.radial_deviation_min),
                              num9(*r.cw.mean_radial_deviation),
                              num9(*r.ccw.radial_deviation_max),
                              num9(*r.ccw.radial_deviation_min),
                              num9(*r.ccw.mean_radial_deviation));
}

void addCircular(CLI::App& analyze) {
  auto st = std::make_shared<CircularState>();
  CLI::App* cmd = analyze.add_subcommand(
      "circular",
      "ISO 230-4 circular deviation G, G(b) and hysteresis H; header x,y,direction (cw/ccw), or "
      "two x,y files (CW, CCW)");
  st->io.add(*cmd, 1, 2);
  cmd->add_option("--centre", st->centre, "centre of G and H: lsc (default), mzc or nominal")
      ->check(CLI::IsMember({"lsc", "mzc", "nominal"}));
  cmd->add_option(
         "--nominal-center", st->nominal_center, "nominal centre X,Y (F, --centre nominal)")
      ->delimiter(',')
      ->expected(2);
  cmd->add_option("--nominal-radius", st->nominal_radius, "nominal radius R0 (enables F)")
      ->check(CLI::PositiveNumber);
  cmd->callback([st] { runCircular(*st); });
}

const AnalyzeRegistration kRegisterCircular{65, &addCircular};

// --- probe-offset (seed 003) -------------------------------------------------------------------

struct ProbeOffsetState {
  AnalyzeIo io;
  std::optional<double> ring_diameter;
  std::optional<double> stylus_diameter;
  std::string tool_direction = "-z";
};

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

/// Seed 003 eqs. 8-9 per run from labelled touches: x1, y1 from the ±x and ±y touches at turn 0,
/// x2 and y3 from the +x and +y touches at turn 180°. Returns {eq9, eq8} averaged over the runs
/// that have all six touches, or nullopt.
std::optional<std::pair<Eigen::Vector2d, Eigen::Vector2d>> paperOffset(
    const std::vector<Labelled>& touches, double ring_radius, double stylus_radius, int* runs) {
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
  *runs = 0;
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
    ++*runs;
  }
  if (*runs == 0) return std::nullopt;
  return std::pair{s9 / *runs, s8 / *runs};
}

void runProbeOffset(const ProbeOffsetState& st) {
  const double sign = st.tool_direction == "+z" ? 1.0 : -1.0;
  std::vector<metrology::ProbeTouch> touches;
  std::vector<Labelled> labelled;
  for (const std::string& f : st.io.data) {
    const io::TextTable t = io::TextTable::read(f);
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
  const metrology::ProbeOffsetFit fit = metrology::fitProbeOffset(touches);
  std::optional<double> stylus_radius;
  if (st.stylus_diameter) stylus_radius = *st.stylus_diameter / 2.0;
  std::optional<double> effective;
  if (st.ring_diameter) {
    effective = metrology::effectiveStylusRadius(*st.ring_diameter, fit.ball_path_radius);
    if (!stylus_radius) stylus_radius = effective;
  }
  int runs = 0;
  std::optional<std::pair<Eigen::Vector2d, Eigen::Vector2d>> paper;
  if (st.ring_diameter && !labelled.empty())
    paper = paperOffset(labelled, *st.ring_diameter / 2.0, *stylus_radius, &runs);
  const Eigen::Vector2d o = -fit.offset;
  if (st.io.json) {
    Json j{{"offset", pair(fit.offset)},
           {"o_probe", pair(o)},
           {"ring_center", pair(fit.ring_center)},
           {"ball_path_radius", fit.ball_path_radius},
           {"rms", fit.rms},
           {"touches", touches.size()},
           {"tool_direction", st.tool_direction}};
    if (effective) {
      j["effective_stylus_radius"] = *effective;
      j["effective_stylus_diameter"] = 2.0 * *effective;
    }
    if (paper) {
      j["eq9_o_probe"] = pair(paper->first);
      j["eq8_o_probe"] = pair(paper->second);
      j["eq_runs"] = runs;
    }
    printJson(j);
    return;
  }
  Output out;
  out.text() += fmt::format("probe offset ({} touches, least squares)\n", touches.size());
  out.text() += fmt::format(
      "offset d (spindle -> ball)\t{}\t{}\n", num9(fit.offset.x()), num9(fit.offset.y()));
  out.text() += fmt::format("o_probe = -d (seed 003 eq. 8)\t{}\t{}\n", num9(o.x()), num9(o.y()));
  out.text() += fmt::format("ring centre\t{}\t{}\nball path radius\t{}\nrms\t{}\n",
                            num9(fit.ring_center.x()),
                            num9(fit.ring_center.y()),
                            num9(fit.ball_path_radius),
                            num9(fit.rms));
  if (effective)
    out.text() += fmt::format("effective stylus diameter\t{}\n", num9(2.0 * *effective));
  if (paper) {
    out.text() += fmt::format(
        "eq. 9 o_probe ({} runs)\t{}\t{}\n", runs, num9(paper->first.x()), num9(paper->first.y()));
    out.text() += fmt::format("eq. 8 o_probe ({} runs)\t{}\t{}\n",
                              runs,
                              num9(paper->second.x()),
                              num9(paper->second.y()));
  }
}

void addProbeOffset(CLI::App& analyze) {
  auto st = std::make_shared<ProbeOffsetState>();
  CLI::App* cmd = analyze.add_subcommand(
      "probe-offset",
      "touch-probe stylus offset from master-ring touches at several spindle angles (seed 003); "
      "header spindle_deg,x,y [,drm_deg,touch,run]");
  st->io.add(*cmd);
  cmd->add_option("--ring-diameter", st->ring_diameter, "certified ring diameter (mm)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--stylus-diameter",
                  st->stylus_diameter,
                  "stylus ball diameter for eqs. 8-9 (default: the effective one)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--tool-direction",
                  st->tool_direction,
                  "tool direction, -z (default, vertical spindle) or +z: the sense of the angles")
      ->check(CLI::IsMember({"-z", "+z"}));
  cmd->callback([st] { runProbeOffset(*st); });
}

const AnalyzeRegistration kRegisterProbeOffset{70, &addProbeOffset};

}  // namespace
}  // namespace pkm::cli
