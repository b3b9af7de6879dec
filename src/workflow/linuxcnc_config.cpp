// `pkm linuxcnc config` as a workflow (workflow/linuxcnc_config.hpp).
#include "pkm/workflow/linuxcnc_config.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <system_error>

#include "pkm/compensation/linuxcnc_comp.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/atomic_file.hpp"
#include "pkm/io/linuxcnc_config.hpp"
#include "pkm/io/machine_loader.hpp"

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
}

namespace {

/// linuxcncConfigFiles, also saying which kind of machine it was.
std::vector<io::NamedText> configFiles(const LinuxcncConfigRequest& request,
                                       std::vector<std::string>& notices,
                                       std::string& kind) {
  request.validate();
  io::LinuxcncConfigOptions options;
  options.display = request.display;
  std::vector<io::NamedText> tables;
  for (const LinuxcncCompInput& c : request.comp_files) {
    io::NamedText table = io::readNamedText(c.path);
    (void)compensation::parseLinuxcncComp(table.text, table.name, request.comp_file_type);
    const std::string name = fmt::format("joint{}.comp", c.joint);
    options.comp_files.push_back({c.joint, name, request.comp_file_type});
    tables.push_back({name, std::move(table.text)});
  }
  std::vector<io::NamedText> files;
  kind = io::machineTypeOf(request.machine) == "exechon" ? "exechon" : "hexapod";
  if (kind == "exechon") {
    const io::ExechonMachine m = io::loadExechonMachine(request.machine);
    notices.insert(notices.end(), m.notices.begin(), m.notices.end());
    if (m.hybrid)
      notices.push_back(
          "the machine's extending axes X2/Y2 are not part of this configuration: its world "
          "frame is the PKM frame P");
    files = io::exechonLinuxcncConfig(m, options);
  } else {
    io::HalReadOptions hal;
    if (!request.ini.empty()) hal.ini_path = request.ini;
    const io::HexapodMachine m = io::loadHexapodMachine(request.machine, hal);
    io::requireRegisteredFrame(m, "pkm linuxcnc config");
    notices.insert(notices.end(), m.notices.begin(), m.notices.end());
    files = io::hexapodLinuxcncConfig(m, options);
  }
  files.insert(files.end(), tables.begin(), tables.end());
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
