// `pkm analyze diagonals`: ISO 230-6 body diagonals (--method body), Hwang et al.'s ("Analysis of
// multi-axis volumetric errors") shifted diagonals (--method shifted) and Wang's step diagonals
// (--method step), with the 2-D XY prediction compared against direct measurements (--compare),
// through pkm/workflow/analyze_diagonals.hpp. docs/analysis.md, "Diagonal methods".
#include "pkm/workflow/analyze_diagonals.hpp"

#include <memory>
#include <string>
#include <vector>

#include "analyze_common.hpp"
#include "cli_common.hpp"
#include "pkm/io/named_text.hpp"

namespace pkm::cli {
namespace {

struct DiagonalsState {
  AnalyzeIo io;
  std::string method = "body";
  std::vector<double> size;
  double coverage = 2.0;
  std::vector<std::string> compare;
  UncertaintyArgs uncertainty;
};

void runDiagonals(const DiagonalsState& st) {
  if (st.size.size() != 3) throw CLI::ValidationError("--size", "needs LX,LY,LZ");
  workflow::DiagonalsRequest request;
  request.method = st.method == "body"   ? io::DiagonalMethod::kBody
                   : st.method == "step" ? io::DiagonalMethod::kStep
                                         : io::DiagonalMethod::kShifted;
  request.size = Eigen::Vector3d(st.size[0], st.size[1], st.size[2]);
  request.coverage = st.coverage;
  request.data = io::readNamedTexts(st.io.data);
  if (request.method == io::DiagonalMethod::kBody && !st.compare.empty()) {
    request.validate();  // the box first, as before the option check
    throw CLI::ValidationError("--compare", "needs --method step or shifted");
  }
  request.compare = io::readNamedTexts(st.compare);
  request.uncertainty = st.uncertainty.parsed();
  CliRunControl control;
  const io::DiagonalsReport report = workflow::analyzeDiagonals(request, control.control());
  control.finish();
  printReport(st.io, report);
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
  st->uncertainty.add(*cmd);
  cmd->callback([st] { runDiagonals(*st); });
}

const AnalyzeRegistration kRegisterDiagonals{50, &addDiagonals};

}  // namespace
}  // namespace pkm::cli
