// `pkm analyze circle | circular | probe-offset`: least-squares and minimum-zone circles with
// roundness, ISO 230-4 circular deviation and hysteresis, and the touch-probe stylus offset from
// master-ring touches with spindle reversal (Lee et al. 2019), through
// pkm/workflow/analyze_circle.hpp. docs/analysis.md, "Circles".
#include "pkm/workflow/analyze_circle.hpp"

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "analyze_common.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/named_text.hpp"

namespace pkm::cli {
namespace {

// --- circle ------------------------------------------------------------------------------------

struct CircleState {
  AnalyzeIo io;
  UncertaintyArgs uncertainty;
  std::string fit = "both";
};

void addCircle(CLI::App& analyze) {
  auto st = std::make_shared<CircleState>();
  CLI::App* cmd = analyze.add_subcommand(
      "circle",
      "least-squares and minimum-zone circle and roundness; header x,y (files concatenated)");
  st->io.add(*cmd);
  st->uncertainty.add(*cmd);
  cmd->add_option("--fit",
                  st->fit,
                  "lsc: the least-squares circle alone (the fastest), mzc: the minimum-zone "
                  "circle alone, both (default)");
  cmd->callback([st] {
    workflow::CircleRequest q;
    q.uncertainty = st->uncertainty.parsed();
    q.fit = st->fit;
    q.data_files = st->io.data;
    printReport(st->io, workflow::analyzeCircle(std::move(q)));
  });
}

const AnalyzeRegistration kRegisterCircle{60, &addCircle};

// --- circular (ISO 230-4) ----------------------------------------------------------------------

struct CircularState {
  AnalyzeIo io;
  UncertaintyArgs uncertainty;
  std::string centre = "lsc";
  std::vector<double> nominal_center;
  std::optional<double> nominal_radius;
};

void runCircular(const CircularState& st) {
  workflow::CircularRequest request;
  request.data = io::readNamedTexts(st.io.data);
  if (st.centre == "mzc")
    request.centre = metrology::CircularCentre::kMinimumZone;
  else if (st.centre == "nominal")
    request.centre = metrology::CircularCentre::kNominal;
  if (!st.nominal_center.empty()) {
    if (st.nominal_center.size() != 2) throw IoError("--nominal-center needs X,Y");
    request.nominal_center = metrology::Point2(st.nominal_center[0], st.nominal_center[1]);
  }
  request.nominal_radius = st.nominal_radius;
  request.uncertainty = st.uncertainty.parsed();
  printReport(st.io, workflow::analyzeCircular(request));
}

void addCircular(CLI::App& analyze) {
  auto st = std::make_shared<CircularState>();
  CLI::App* cmd = analyze.add_subcommand(
      "circular",
      "ISO 230-4 circular deviation G, G(b) and hysteresis H; header x,y,direction (cw/ccw), or "
      "two x,y files (CW, CCW)");
  st->io.add(*cmd, 1, 2);
  st->uncertainty.add(*cmd);
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

// --- probe-offset (Lee et al. 2019) ------------------------------------------------------------

struct ProbeOffsetState {
  AnalyzeIo io;
  std::optional<double> ring_diameter;
  std::optional<double> stylus_diameter;
  std::string tool_direction = "-z";
  UncertaintyArgs uncertainty;
};

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
  st->uncertainty.add(*cmd);
  cmd->callback([st] {
    printReport(st->io,
                workflow::analyzeProbeOffset({io::readNamedTexts(st->io.data),
                                              st->ring_diameter,
                                              st->stylus_diameter,
                                              st->tool_direction == "+z",
                                              st->uncertainty.parsed()}));
  });
}

const AnalyzeRegistration kRegisterProbeOffset{70, &addProbeOffset};

}  // namespace
}  // namespace pkm::cli
