// `pkm analyze iso230-2 | straightness | parallelism | squareness`: ISO 230-2 positioning,
// straightness about end-point / least-squares / minimum-zone lines, parallelism from two
// straightness runs along one beam and face-diagonal squareness (MXT700S parallelism paper, §3),
// through pkm/workflow/analyze_positioning.hpp. docs/analysis.md, "Positioning".
#include "pkm/workflow/analyze_positioning.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "analyze_common.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/named_text.hpp"

namespace pkm::cli {
namespace {

// --- iso230-2 ------------------------------------------------------------------------------

struct Iso230_2State {
  AnalyzeIo io;
  PositioningColumnArgs columns;
  double coverage = 2.0;
  bool strict = false;
  UncertaintyArgs uncertainty;
  std::vector<std::string> tolerances;
};

/// `NAME=VALUE` items (E=0.02) as (name, tolerance); throws pkm::InvalidArgument for a bad item.
std::vector<std::pair<std::string, double>> parseTolerances(const std::vector<std::string>& items) {
  std::vector<std::pair<std::string, double>> out;
  for (const std::string& item : items) {
    const auto eq = item.find('=');
    double v = NAN;
    try {
      std::size_t used = 0;
      if (eq != std::string::npos) v = std::stod(item.substr(eq + 1), &used);
      if (eq == std::string::npos || used != item.size() - eq - 1) v = NAN;
    } catch (const std::exception&) {
      v = NAN;
    }
    if (!std::isfinite(v))
      throw InvalidArgument(
          fmt::format("--tolerance '{}': expected NAME=VALUE, e.g. E=0.02", item));
    out.emplace_back(item.substr(0, eq), v);
  }
  return out;
}

void addIso230_2(CLI::App& analyze) {
  auto st = std::make_shared<Iso230_2State>();
  CLI::App* cmd = analyze.add_subcommand(
      "iso230-2",
      "ISO 230-2 positioning accuracy and repeatability; columns target, run, direction and "
      "measured or error, recognised by name with their units (docs/formats.md, \"Instrument "
      "exports\"), Renishaw .rtl files, or pkm simulate measurement files");
  st->io.add(*cmd);
  st->columns.add(*cmd);
  cmd->add_option("--coverage", st->coverage, "coverage factor k (ISO 230-2:2014: 2)")
      ->check(CLI::PositiveNumber);
  cmd->add_flag("--strict",
                st->strict,
                "refuse data that miss the ISO 230-2 test conditions or look implausible");
  st->uncertainty.add(*cmd);
  cmd->add_option("--tolerance",
                  st->tolerances,
                  "NAME=VALUE[,...]: upper tolerance of E, M, A, B or R (mm), decided per "
                  "ISO 14253-1 with the expanded uncertainty")
      ->delimiter(',');
  cmd->callback([st] {
    workflow::Iso230_2Request request;
    request.data = io::readNamedTexts(st->io.data);
    request.columns = st->columns.parsed();
    request.machine = st->columns.machine;
    request.ini = st->columns.ini;
    request.coverage = st->coverage;
    request.strict = st->strict;
    request.uncertainty = st->uncertainty.parsed();
    request.tolerances = parseTolerances(st->tolerances);
    printReport(st->io, workflow::analyzeIso230_2(request));
  });
}

const AnalyzeRegistration kRegisterIso230_2{10, &addIso230_2};

// --- straightness --------------------------------------------------------------------------

struct StraightnessState {
  AnalyzeIo io;
  UncertaintyArgs uncertainty;
  std::string reference = "lsq";
};

void addStraightness(CLI::App& analyze) {
  auto st = std::make_shared<StraightnessState>();
  CLI::App* cmd = analyze.add_subcommand(
      "straightness",
      "straightness about a reference line; header position,deviation (or pkm simulate "
      "straightness files, averaged per target)");
  st->io.add(*cmd);
  cmd->add_option("--reference", st->reference, "reference line: endpoint, lsq or minzone")
      ->check(CLI::IsMember({"endpoint", "lsq", "minzone"}));
  st->uncertainty.add(*cmd);
  cmd->callback([st] {
    const auto reference = metrology::parseStraightnessReference(st->reference);
    printReport(st->io,
                workflow::analyzeStraightness(
                    {io::readNamedTexts(st->io.data), reference, st->uncertainty.parsed()}));
  });
}

const AnalyzeRegistration kRegisterStraightness{20, &addStraightness};

// --- parallelism ---------------------------------------------------------------------------

struct ParallelismState {
  std::vector<std::string> reference, axis;
  int reference_sign = 1, axis_sign = 1;
  std::string line = "lsq";
  std::string plane = "horizontal";
  std::optional<double> szX2;
  AnalyzeIo io;  // only --json: the files are --reference and --axis
  UncertaintyArgs uncertainty;
};

void runParallelism(const ParallelismState& st) {
  workflow::ParallelismRequest request;
  request.reference = io::readNamedTexts(st.reference);
  request.axis = io::readNamedTexts(st.axis);
  request.reference_sign = st.reference_sign;
  request.axis_sign = st.axis_sign;
  request.line = metrology::parseStraightnessReference(st.line);
  request.plane = st.plane == "horizontal" ? io::ParallelismPlane::kHorizontal
                                           : io::ParallelismPlane::kVertical;
  request.szX2 = st.szX2;
  request.uncertainty = st.uncertainty.parsed();
  printReport(st.io, workflow::analyzeParallelism(request));
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
  cmd->add_flag("--json", st->io.json, "print one JSON object instead of a table");
  st->uncertainty.add(*cmd);
  cmd->callback([st] { runParallelism(*st); });
}

const AnalyzeRegistration kRegisterParallelism{30, &addParallelism};

// --- squareness (face diagonals) ------------------------------------------------------------

struct SquarenessState {
  AnalyzeIo io;
  std::vector<std::string> start, pdge;
  std::string axes;
  bool scale = false, first_work = false, second_work = false;
  UncertaintyArgs uncertainty;
};

/// "A,B" as two finite numbers; throws pkm::InvalidArgument naming the option.
std::array<double, 2> parsePair(const std::string& text, const char* what) {
  std::vector<double> v;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    try {
      std::size_t used = 0;
      v.push_back(std::stod(item, &used));
      if (used != item.size() || !std::isfinite(v.back())) throw std::invalid_argument(item);
    } catch (const std::exception&) {
      throw InvalidArgument(fmt::format("{}: '{}' is not a list of 2 numbers", what, text));
    }
  }
  if (v.size() != 2)
    throw InvalidArgument(fmt::format("{}: '{}' is not a list of 2 numbers", what, text));
  return {v[0], v[1]};
}

/// `AC=FILE`: A, C in {u, v} (table over the first/second axis position, displacing along the
/// first/second axis), the file read.
workflow::PdgeInput readPdgeSpec(const std::string& spec) {
  const auto eq = spec.find('=');
  const std::string key = spec.substr(0, eq);
  if (eq == std::string::npos || key.size() != 2 || (key[0] != 'u' && key[0] != 'v') ||
      (key[1] != 'u' && key[1] != 'v')) {
    throw InvalidArgument(
        fmt::format("--pdge '{}': expected uu=FILE, uv=FILE, vv=FILE or vu=FILE", spec));
  }
  return {key[0] == 'u' ? 0 : 1, key[1] == 'u' ? 0 : 1, io::readNamedText(spec.substr(eq + 1))};
}

void runSquareness(const SquarenessState& st) {
  workflow::SquarenessRequest request;
  request.data = io::readNamedTexts(st.io.data);
  for (const std::string& s : st.start) request.start.push_back(parsePair(s, "--start"));
  for (const std::string& spec : st.pdge) request.pdge.push_back(readPdgeSpec(spec));
  std::stringstream axes(st.axes);
  for (std::string n; std::getline(axes, n, ',');) request.axes.push_back(n);
  request.fit_scale = st.scale;
  request.first_moves_work = st.first_work;
  request.second_moves_work = st.second_work;
  request.uncertainty = st.uncertainty.parsed();
  printReport(st.io, workflow::analyzeSquareness(request));
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
  st->uncertainty.add(*cmd);
  cmd->callback([st] { runSquareness(*st); });
}

const AnalyzeRegistration kRegisterSquareness{40, &addSquareness};

}  // namespace
}  // namespace pkm::cli
