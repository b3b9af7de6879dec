// `pkm linuxcnc config` as a workflow (workflow/linuxcnc_config.hpp).
#include "pkm/workflow/linuxcnc_config.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <span>
#include <system_error>

#include "pkm/compensation/linuxcnc_comp.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/atomic_file.hpp"
#include "pkm/io/linuxcnc_config.hpp"
#include "pkm/io/linuxcnc_hal.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/io/number_format.hpp"
#include "pkm/io/positioning_files.hpp"
#include "pkm/io/truth_file.hpp"

namespace pkm::workflow {

namespace fs = std::filesystem;

void LinuxcncConfigRequest::validate() const {
  if (machine.empty())
    throw InvalidArgument("--machine: give a machine file, a .hal file or a built-in name");
  if (out.empty()) throw InvalidArgument("--out: give the configuration folder");
  if (!comp_files.empty() && comp_file_type != 0 && comp_file_type != 1)
    throw InvalidArgument(
        "--comp-file-type: give 0 or 1, the --format the tables were written with "
        "(linuxcnc0 or linuxcnc1)");
  for (const LinuxcncCompInput& d : comp_data)
    if (std::none_of(comp_files.begin(), comp_files.end(), [&](const LinuxcncCompInput& c) {
          return c.joint == d.joint;
        }))
      throw InvalidArgument(fmt::format(
          "--comp-data {}={}: no --comp-file for joint {} to check", d.joint, d.path, d.joint));
}

namespace {

/// The [min, max] joint positions of every joint of the machine (±infinity for an open side).
using JointRanges = std::vector<std::array<double, 2>>;

/// Row `row` (0-based) of `file`'s first correction beyond `limit`, or -1.
long firstBeyond(const compensation::LinuxcncCompFile& file, double limit) {
  for (std::size_t i = 0; i < file.nominal.size(); ++i)
    if (std::abs(file.trim(i, 1)) > limit || std::abs(file.trim(i, -1)) > limit)
      return static_cast<long>(i);
  return -1;
}

}  // namespace

void checkCompPlausible(const compensation::LinuxcncCompFile& file,
                        const std::string& source,
                        int joint,
                        std::array<double, 2> range) {
  const double span = file.nominal.back() - file.nominal.front();
  const double travel =
      span > 0.0 ? span : (std::isfinite(range[1] - range[0]) ? range[1] - range[0] : 0.0);
  if (!(travel > 0.0)) return;
  const double limit = kCompMaxFractionOfTravel * travel;
  const long row = firstBeyond(file, limit);
  if (row < 0) return;
  const auto i = static_cast<std::size_t>(row);
  const double trim = std::abs(file.trim(i, 1)) > limit ? file.trim(i, 1) : file.trim(i, -1);
  compensation::LinuxcncCompFile other = file;
  other.type = 1 - file.type;
  const std::string hint =
      firstBeyond(other, limit) < 0
          ? fmt::format(
                "; read as COMP_FILE_TYPE {} its corrections are plausible: it looks like a type "
                "{} table ({}), give --comp-file-type {}",
                other.type,
                other.type,
                other.type == 0 ? "nominal, actual positions"
                                : "nominal, forward and reverse trims",
                other.type)
          : "";
  throw InvalidArgument(fmt::format(
      "{}:{}: joint {}'s correction at {} would be {} as COMP_FILE_TYPE {}, more than {} % of the "
      "joint's travel ({}, {} to {}){}; a wrong table would move the machine by that much (pass "
      "--no-comp-check to use it anyway)",
      source,
      row + 1,
      joint,
      io::formatNumber(file.nominal[i]),
      io::formatNumber(trim),
      file.type,
      io::formatNumber(100.0 * kCompMaxFractionOfTravel),
      io::formatNumber(travel),
      io::formatNumber(span > 0.0 ? file.nominal.front() : range[0]),
      io::formatNumber(span > 0.0 ? file.nominal.back() : range[1]),
      hint));
}

void checkCompSign(const compensation::LinuxcncCompFile& file,
                   const std::string& source,
                   int joint,
                   std::span<const metrology::PositioningSample> errors,
                   const std::string& errors_source) {
  double agree = 0.0, size = 0.0;
  for (const metrology::PositioningSample& e : errors) {
    const double wanted = -(e.measured - e.target);  // the correction that cancels the error
    const double trim = compensation::applyLinuxcncComp(file, e.target, e.direction) - e.target;
    agree += trim * wanted;
    size += wanted * wanted;
  }
  if (size > 0.0 && agree < 0.0)
    throw InvalidArgument(fmt::format(
        "{}:1: joint {}'s corrections have the sign of the errors measured in {} (correction = "
        "error instead of -error: the table would double them, not cancel them); write it again "
        "with `pkm compensate table` (pass --no-comp-check to use it anyway)",
        source,
        joint,
        errors_source));
}

namespace {

/// The errors of `path` (ISO 230-2 positioning data, mm) in the machine's length unit.
std::vector<metrology::PositioningSample> readErrors(const std::string& path, LengthUnit unit) {
  const std::vector<io::NamedText> data{io::readNamedText(path)};
  std::vector<metrology::PositioningSample> samples = io::readPositioningSamples(data);
  const double per_mm = unit == LengthUnit::kInch ? 1.0 / 25.4 : 1.0;
  for (metrology::PositioningSample& s : samples) {
    s.target *= per_mm;
    s.measured *= per_mm;
  }
  return samples;
}

/// The tables of the request, read, checked against the joints' ranges (unless skipped) and
/// named jointN.comp, with their INI references in `options`.
std::vector<io::NamedText> compTables(const LinuxcncConfigRequest& request,
                                      const JointRanges& ranges,
                                      LengthUnit unit,
                                      io::LinuxcncConfigOptions& options,
                                      std::vector<std::string>& notices) {
  std::vector<io::NamedText> tables;
  for (const LinuxcncCompInput& c : request.comp_files) {
    io::NamedText table = io::readNamedText(c.path);
    const compensation::LinuxcncCompFile file =
        compensation::parseLinuxcncComp(table.text, table.name, request.comp_file_type);
    if (c.joint >= 0 && static_cast<std::size_t>(c.joint) < ranges.size()) {
      if (request.check_comp_files) {
        checkCompPlausible(file, table.name, c.joint, ranges[static_cast<std::size_t>(c.joint)]);
        for (const LinuxcncCompInput& d : request.comp_data)
          if (d.joint == c.joint)
            checkCompSign(file, table.name, c.joint, readErrors(d.path, unit), d.path);
      } else {
        notices.push_back(fmt::format(
            "{}: --no-comp-check: its corrections were not checked for size or sign", table.name));
      }
    }
    const std::string name = fmt::format("joint{}.comp", c.joint);
    options.comp_files.push_back({c.joint, name, request.comp_file_type});
    tables.push_back({name, std::move(table.text)});
  }
  return tables;
}

/// The name of the configuration of machine `spec` whose model is called `name`: a genhexkins
/// `.hal` file's model is named after the file ("kinematics" for every LinuxCNC hexapod), so its
/// configuration is named after the folder that holds it (LinuxCNC's sample: "hexapod-sim").
std::string configurationName(const std::string& spec, const std::string& name) {
  if (!spec.ends_with(".hal")) return name;
  const std::string folder = fs::absolute(fs::path(spec)).parent_path().filename().string();
  return folder.empty() ? name : folder;
}

double orOpen(double v, double open) { return std::isfinite(v) ? v : open; }

/// truth.hal (the truth is checked: a hexapod truth in mm), added to `options`' HAL files; the
/// truth itself is copied as truth.json by configFiles.
io::NamedText truthFiles(const LinuxcncConfigRequest& request,
                         const io::HexapodMachine& machine,
                         io::LinuxcncConfigOptions& options) {
  if (machine.model.unit != LengthUnit::kMillimetre)
    throw InvalidArgument("--simulate-truth: the machine must be in mm (the truth is)");
  (void)io::readHexapodTruth(request.simulate_truth);  // refuses a malformed truth here
  options.extra_hal_files.push_back("truth.hal");
  std::vector<double> offsets;  // the INI's HOME_OFFSETs
  for (const io::PkmhexkinsJointValues& j : io::pkmhexkinsJointValues(machine))
    offsets.push_back(j.home);
  return {"truth.hal", io::linuxcncTruthHal(request.truth_program, "truth.json", offsets)};
}

/// linuxcncConfigFiles, also saying which kind of machine it was.
std::vector<io::NamedText> configFiles(const LinuxcncConfigRequest& request,
                                       std::vector<std::string>& notices,
                                       std::string& kind) {
  request.validate();
  io::LinuxcncConfigOptions options;
  options.display = request.display;
  constexpr double kOpen = std::numeric_limits<double>::infinity();
  std::vector<io::NamedText> files, tables;
  kind = io::machineTypeOf(request.machine) == "exechon" ? "exechon" : "hexapod";
  if (kind == "exechon") {
    const io::ExechonMachine m = io::loadExechonMachine(request.machine);
    notices.insert(notices.end(), m.notices.begin(), m.notices.end());
    if (m.hybrid)
      notices.push_back(
          "the machine's extending axes X2/Y2 are not part of this configuration: its world "
          "frame is the PKM frame P");
    JointRanges ranges;
    for (const kinematics::ExechonLeg& leg : m.model.legs)
      ranges.push_back({orOpen(leg.min_reading, -kOpen), orOpen(leg.max_reading, kOpen)});
    for (const kinematics::AngleRange* r : {&m.model.limits.c, &m.model.limits.a})
      ranges.push_back({std::isfinite(r->min) ? radToDeg(r->min) : -kOpen,
                        std::isfinite(r->max) ? radToDeg(r->max) : kOpen});
    if (!request.simulate_truth.empty())
      throw InvalidArgument("--simulate-truth: the simulated machine in the loop is a hexapod's");
    tables = compTables(request, ranges, m.model.unit, options, notices);
    files = io::exechonLinuxcncConfig(m, options);
  } else {
    io::HalReadOptions hal;
    if (!request.ini.empty()) hal.ini_path = request.ini;
    io::HexapodMachine m = io::loadHexapodMachine(request.machine, hal);
    io::requireRegisteredFrame(m, "pkm linuxcnc config");
    m.model.name = configurationName(request.machine, m.model.name);
    notices.insert(notices.end(), m.notices.begin(), m.notices.end());
    JointRanges ranges;
    for (const io::PkmhexkinsJointValues& j : io::pkmhexkinsJointValues(m))
      ranges.push_back({j.min_limit.value_or(-kOpen), j.max_limit.value_or(kOpen)});
    tables = compTables(request, ranges, m.model.unit, options, notices);
    if (!request.simulate_truth.empty()) tables.push_back(truthFiles(request, m, options));
    files = io::hexapodLinuxcncConfig(m, options, &notices);
  }
  files.insert(files.end(), tables.begin(), tables.end());
  if (!request.simulate_truth.empty())
    files.push_back({"truth.json", io::readTextFile(request.simulate_truth)});
  return files;
}

}  // namespace

std::vector<io::NamedText> linuxcncConfigFiles(const LinuxcncConfigRequest& request,
                                               std::vector<std::string>& notices) {
  std::string kind;
  return configFiles(request, notices, kind);
}

LinuxcncConfigResult writeLinuxcncConfig(const LinuxcncConfigRequest& request) {
  LinuxcncConfigResult result;
  const std::vector<io::NamedText> files = configFiles(request, result.notices, result.kind);
  const fs::path dir(request.out);
  if (fs::exists(dir) && !fs::is_directory(dir))
    throw InvalidArgument(fmt::format("{}: exists and is not a folder", request.out));
  if (!request.force)
    for (const io::NamedText& f : files)
      if (fs::exists(dir / f.name))
        throw InvalidArgument(
            fmt::format("{}: exists; pass --force to replace it (nothing was written)",
                        (dir / f.name).string()));
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw IoError(fmt::format("{}: cannot create the folder: {}", request.out, ec.message()));
  for (const io::NamedText& f : files) {
    const fs::path p = dir / f.name;
    io::writeFileAtomic(p, f.text, io::Overwrite::kAllow);
    result.files.push_back(p.string());
  }
  result.ini = result.files.front();
  return result;
}

}  // namespace pkm::workflow
