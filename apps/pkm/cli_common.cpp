#include "cli_common.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "pkm/core/error.hpp"
#include "pkm/io/atomic_file.hpp"
#include "pkm/io/machine_loader.hpp"

namespace pkm::cli {

void writeTextOutput(const std::string& out, const std::string& text) {
  if (out.empty()) {
    std::fwrite(text.data(), 1, text.size(), stdout);
    std::fflush(stdout);
    return;
  }
  io::writeFileAtomic(out, text, io::Overwrite::kAllow);
}

io::NamedText readCsvInput(const std::string& path) {
  if (path == "-") return {"-", io::readNamedText("-").text};
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr)
    throw IoError(locate(path, 0, fmt::format("cannot open: {}", std::strerror(errno))));
  std::fclose(f);
  return io::readNamedText(path);
}

void printNotices(const std::vector<std::string>& notices) {
  for (const auto& n : notices) fmt::print(stderr, "pkm: note: {}\n", n);
}

CliRunControl::CliRunControl() {
  control_.notice = [](const std::string& n) { printNotices({n}); };
  if (::isatty(STDERR_FILENO) == 0) return;
  control_.progress = [this](const workflow::ProgressEvent& e) {
    fmt::print(stderr, "\rpkm: {}", e.message);
    shown_ = true;
  };
}

void CliRunControl::finish() {
  if (shown_) fmt::print(stderr, "\n");
  shown_ = false;
}

void MachineOption::add(CLI::App& cmd) { addMachineOptions(cmd, spec, ini); }

void addMachineOptions(CLI::App& cmd, std::string& spec, std::string& ini) {
  cmd.add_option(
      "--machine,-m",
      spec,
      "machine: a JSON machine file, a LinuxCNC .hal file, or a built-in name (default: the "
      "embedded default machine)");
  cmd.add_option("--ini",
                 ini,
                 "LinuxCNC INI file for a .hal machine ([TRAJ] HOME, LINEAR_UNITS, joint limits)");
}

io::HexapodMachine MachineOption::load() const {
  io::HalReadOptions hal;
  if (!ini.empty()) hal.ini_path = ini;
  io::HexapodMachine m = io::loadHexapodMachine(spec, hal);
  printNotices(m.notices);
  return m;
}

void addMachinesCommand(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("machines", "list the built-in machines and error sets");
  cmd->callback([] {
    Output out;
    out.text() += "name,kind\n";
    for (const char* type : {"hexapod", "exechon"})
      for (const auto& n : io::builtinMachineNames(type))
        out.text() += fmt::format("{},{}\n", n, type);
    for (const auto& n : io::builtinErrorNames())
      out.text() += fmt::format("{},geometric_errors\n", n);
  });
}

void setFooter(CLI::App& app, const std::string& footer) {
  app.footer(footer);
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) setFooter(*sub, footer);
}

std::filesystem::path programDirectory() {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::filesystem::path{} : self.parent_path();
}

}  // namespace pkm::cli
