// `pkm exechon ...`: ik (--wrist or --poses), fk, check, drm, describe (docs/formats.md), and
// linuxcnc-params (docs/linuxcnc.md).
#include <fmt/format.h>

#include <array>
#include <cmath>
#include <memory>
#include <optional>

#include "cli_common.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/csv.hpp"
#include "pkm/io/kinematics_csv.hpp"
#include "pkm/io/linuxcnc_exechon.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/io/number_format.hpp"
#include "pkm/kinematics/exechon_checks.hpp"
#include "pkm/kinematics/exechon_drm.hpp"
#include "pkm/kinematics/exechon_wrist.hpp"
#include "pkm/kinematics/hybrid_model.hpp"
#include "pkm/workflow/kinematics_path.hpp"

namespace pkm::cli {

namespace kin = pkm::kinematics;

namespace {

/// Options shared by the exechon commands.
struct ExechonState {
  std::string machine = "default";
  std::string wrist, poses, joints, circle, direction = "0,0,-1";
  double step_deg = 1.0;
  bool json = false;

  io::ExechonMachine load() const {
    io::ExechonMachine m = io::loadExechonMachine(machine);
    printNotices(m.notices);
    return m;
  }
};

void addMachineOption(CLI::App& cmd, ExechonState& st) {
  cmd.add_option("--machine,-m",
                 st.machine,
                 "Exechon machine: a JSON machine file or a built-in name (default: mxt700s-like)");
}

void appendCsv(std::string& out, double v) {
  io::appendNumber(out, v);
  out += ',';
}

/// "x,y,z" of finite numbers.
Eigen::Vector3d parseTriple(const std::string& text, const char* option) {
  Eigen::Vector3d v;
  std::size_t pos = 0;
  for (int i = 0; i < 3; ++i) {
    const std::size_t comma = text.find(',', pos);
    const std::string_view field = std::string_view(text).substr(
        pos, comma == std::string::npos ? std::string::npos : comma - pos);
    if ((comma == std::string::npos) != (i == 2) || !io::parseFiniteDouble(field, v[i]))
      throw IoError(
          fmt::format("{} '{}': expected three finite numbers separated by commas", option, text));
    pos = comma + 1;
  }
  return v;
}

void runIkWrist(const ExechonState& st) {
  const io::ExechonMachine machine = st.load();
  kin::ExechonData data(machine.model);
  io::CsvReader reader(st.wrist, {"sx", "sy", "sz"});
  Output out;
  out.text() += "q1,q2,q3,alpha,beta,h,status\n";
  std::array<double, 3> row{};
  while (reader.next(row)) {
    const workflow::ExechonWristStep w =
        workflow::solveWristPoint(machine.model, data, Eigen::Vector3d(row[0], row[1], row[2]));
    std::string& o = out.text();
    if (w.ik != kin::ExechonIkStatus::kOk) {
      o += fmt::format(",,,,,,{}\n", kin::toString(w.ik));
      continue;
    }
    for (int i = 0; i < 3; ++i) appendCsv(o, w.readings[i]);
    appendCsv(o, radToDeg(w.e[0]));
    appendCsv(o, radToDeg(w.e[1]));
    appendCsv(o, w.e[2]);
    o += w.status;
    o += '\n';
    out.maybeFlush();
  }
}

/// Tool pose rows: x,y,z,i,j,k and, for hybrid machines, optional x2,y2. Tool positions of hybrid
/// machines are in the work frame; the PKM gets the rest after X2 and Y2 (centred split when x2, y2
/// are not given).
struct PoseRows {
  io::CsvReader reader;
  bool has_x2y2 = false;
  explicit PoseRows(const std::string& path) : reader(path, {"x", "y", "z", "i", "j", "k"}) {
    const bool x2 = reader.addOptionalColumn("x2");
    const bool y2 = reader.addOptionalColumn("y2");
    if (x2 != y2) reader.fail("give both x2 and y2 columns, or neither");
    has_x2y2 = x2;
  }
};

/// The row's x2, y2 when the file has them.
std::optional<std::array<double, 2>> x2y2Of(const PoseRows& rows,
                                            const std::array<double, 8>& row) {
  if (!rows.has_x2y2) return std::nullopt;
  return std::array<double, 2>{row[6], row[7]};
}

void runIkPoses(const ExechonState& st) {
  const io::ExechonMachine machine = st.load();
  PoseRows rows(st.poses);
  if (rows.has_x2y2 && !machine.hybrid)
    rows.reader.fail("x2,y2 columns need a machine with a \"hybrid\" section");
  const bool hybrid = machine.hybrid.has_value();
  Output out;
  out.text() += hybrid ? "q1,q2,q3,c,a,drm,status,x2,y2\n" : "q1,q2,q3,c,a,drm,status\n";
  std::array<double, 8> row{};
  std::span<double> values(row.data(), rows.has_x2y2 ? 8 : 6);
  workflow::ExechonPosePath path(machine);
  while (rows.reader.next(values)) {
    const kin::ExechonToolPose target{{row[0], row[1], row[2]}, {row[3], row[4], row[5]}};
    const workflow::ExechonPoseStep step = path.solve(target, x2y2Of(rows, row));
    std::string& o = out.text();
    if (!step.solved) {
      o += fmt::format(",,,,,,{}", step.check.solver_status);
    } else {
      for (int i = 0; i < 3; ++i) appendCsv(o, step.joints.readings[i]);
      appendCsv(o, radToDeg(step.joints.c));
      appendCsv(o, radToDeg(step.joints.a));
      appendCsv(o, radToDeg(step.drm));
      o += step.status;
    }
    if (hybrid)
      o += fmt::format(
          ",{},{}", io::formatNumber(step.command.x2), io::formatNumber(step.command.y2));
    o += '\n';
    out.maybeFlush();
  }
}

void runFk(const ExechonState& st) {
  const io::ExechonMachine machine = st.load();
  io::CsvReader reader(st.joints, {"q1", "q2", "q3", "c", "a"});
  const bool x2 = reader.addOptionalColumn("x2");
  const bool y2 = reader.addOptionalColumn("y2");
  if (x2 != y2) reader.fail("give both x2 and y2 columns, or neither");
  if (x2 && !machine.hybrid) reader.fail("x2,y2 columns need a machine with a \"hybrid\" section");
  Output out;
  out.text() += "x,y,z,i,j,k,iterations,status\n";
  std::array<double, 7> row{};
  std::span<double> values(row.data(), x2 ? 7 : 5);
  workflow::ExechonFkPath path(machine);
  while (reader.next(values)) {
    kin::ExechonJoints joints;
    joints.readings = {row[0], row[1], row[2]};
    joints.c = degToRad(row[3]);
    joints.a = degToRad(row[4]);
    std::optional<std::array<double, 2>> x2y2;
    if (x2) x2y2 = std::array<double, 2>{row[5], row[6]};
    const workflow::FkStep s = path.solve(joints, x2y2);
    std::string& o = out.text();
    if (s.summary.ok()) {
      for (int i = 0; i < 3; ++i) appendCsv(o, s.tool_point[i]);
      for (int i = 0; i < 3; ++i) appendCsv(o, s.tool_direction[i]);
    } else {
      o += ",,,,,,";
    }
    o += fmt::format("{},{}\n", s.summary.iterations, kin::toString(s.summary.status));
    out.maybeFlush();
  }
}

void runCheck(const ExechonState& st) {
  const io::ExechonMachine machine = st.load();
  PoseRows rows(st.poses);
  if (rows.has_x2y2 && !machine.hybrid)
    rows.reader.fail("x2,y2 columns need a machine with a \"hybrid\" section");
  Output out;
  out.text() += io::exechonCheckCsvHeader();
  std::array<double, 8> row{};
  std::span<double> values(row.data(), rows.has_x2y2 ? 8 : 6);
  workflow::ExechonPosePath path(machine);
  std::size_t index = 0;
  while (rows.reader.next(values)) {
    const kin::ExechonToolPose target{{row[0], row[1], row[2]}, {row[3], row[4], row[5]}};
    const workflow::ExechonPoseStep step = path.solve(target, x2y2Of(rows, row));
    io::appendExechonCheckRow(out.text(), index++, step.status, step.check);
    out.maybeFlush();
  }
}

void runDrm(const ExechonState& st) {
  const io::ExechonMachine machine = st.load();
  const kin::ExechonModel& model = machine.model;
  std::array<double, 4> c{};
  {
    std::size_t pos = 0;
    for (std::size_t i = 0; i < 4; ++i) {
      const std::size_t comma = st.circle.find(',', pos);
      const std::string_view field = std::string_view(st.circle).substr(
          pos, comma == std::string::npos ? std::string::npos : comma - pos);
      if ((comma == std::string::npos) != (i == 3) || !io::parseFiniteDouble(field, c[i]))
        throw IoError(fmt::format("--circle '{}': expected cx,cy,cz,r", st.circle));
      pos = comma + 1;
    }
  }
  kin::DrmCircleOptions opt;
  opt.centre = {c[0], c[1], c[2]};
  opt.radius = c[3];
  opt.direction = parseTriple(st.direction, "--direction");
  opt.step = degToRad(st.step_deg);
  std::string why;
  if (!opt.isValid(&why)) throw IoError(fmt::format("invalid circle: {}", why));
  kin::ExechonData data(model);
  const kin::DrmCircleResult r = kin::sampleDrmCircle(model, data, opt);
  Output out;
  out.text() += io::drmCircleCsv(r);
  if (!r.ok()) {
    out.flush();
    throw IoError(fmt::format("the circle leaves the workspace at point {} ({})",
                              r.failed_index,
                              kin::toString(r.status)));
  }
}

}  // namespace

void addExechonCommands(CLI::App& app) {
  CLI::App* exe =
      app.add_subcommand("exechon", "Exechon tripod with C/A wrist (optionally on X2/Y2)");
  exe->require_subcommand(1);
  auto st = std::make_shared<ExechonState>();

  CLI::App* ik = exe->add_subcommand("ik",
                                     "inverse kinematics: --wrist (Zoppi frame S -> "
                                     "q1,q2,q3,alpha,beta,h) or --poses (tool x,y,z,i,j,k)");
  addMachineOption(*ik, *st);
  auto* wrist = ik->add_option(
      "--wrist,-w", st->wrist, "CSV with header sx,sy,sz (Zoppi base frame); - = stdin");
  auto* poses =
      ik->add_option("--poses,-p",
                     st->poses,
                     "CSV with header x,y,z,i,j,k (tool point and direction; optional x2,y2)");
  wrist->excludes(poses);
  ik->callback([st, wrist, poses] {
    if (wrist->count() == 0 && poses->count() == 0) throw CLI::RequiredError("--wrist or --poses");
    if (wrist->count() > 0)
      runIkWrist(*st);
    else
      runIkPoses(*st);
  });

  CLI::App* fk = exe->add_subcommand("fk", "forward kinematics: q1,q2,q3,c,a -> tool x,y,z,i,j,k");
  addMachineOption(*fk, *st);
  fk->add_option(
        "--joints,-j", st->joints, "CSV with header q1,q2,q3,c,a (optional x2,y2); - = stdin")
      ->required();
  fk->callback([st] { runFk(*st); });

  CLI::App* check =
      exe->add_subcommand("check", "per tool pose: strokes, angle limits, conditioning");
  addMachineOption(*check, *st);
  check->add_option("--poses,-p", st->poses, "CSV with header x,y,z,i,j,k (optional x2,y2)")
      ->required();
  check->callback([st] { runCheck(*st); });

  CLI::App* drm = exe->add_subcommand(
      "drm", "dependent rotational motion along a circle, with its 5th-order fit");
  addMachineOption(*drm, *st);
  drm->add_option("--circle", st->circle, "cx,cy,cz,r: centre (machine world frame) and radius")
      ->required();
  drm->add_option("--step", st->step_deg, "angle step in degrees (default 1)");
  drm->add_option("--direction", st->direction, "tool direction i,j,k (default 0,0,-1)");
  drm->callback([st] { runDrm(*st); });

  CLI::App* describe = exe->add_subcommand("describe", "write the machine as JSON");
  addMachineOption(*describe, *st);
  describe->callback([st] {
    Output out;
    out.text() += io::writeExechonJson(st->load());
  });

  CLI::App* kins = exe->add_subcommand(
      "linuxcnc-params", "write the parameter file of the LinuxCNC kinematics pkmexechonkins");
  addMachineOption(*kins, *st);
  kins->callback([st] {
    Output out;
    out.text() += io::linuxcncExechonParameters(st->load());
  });
}

}  // namespace pkm::cli
