/// @file
/// @brief Helpers shared by the CLI command groups: buffered stdout, notices, exit codes.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "exit_codes.hpp"
#include "pkm/io/hexapod_machine.hpp"
#include "pkm/io/named_text.hpp"
#include "pkm/workflow/progress.hpp"

namespace pkm::cli {

/// Thrown by a command that has printed its result and must end the program with `code` (e.g. 1
/// for a missed campaign target); main() returns the code.
struct ExitCode {
  int code;
};

/// Buffers text for stdout and writes it in large blocks.
class Output {
 public:
  Output() { buffer_.reserve(kFlushBytes + 4096); }
  ~Output() { flush(); }
  Output(const Output&) = delete;
  Output& operator=(const Output&) = delete;
  std::string& text() { return buffer_; }
  /// Writes the buffer once it holds more than kFlushBytes.
  void maybeFlush() {
    if (buffer_.size() > kFlushBytes) flush();
  }
  void flush() {
    if (!buffer_.empty()) std::fwrite(buffer_.data(), 1, buffer_.size(), stdout);
    buffer_.clear();
    std::fflush(stdout);
  }
  /// Writes what the buffer holds, then `text` (without copying it into the buffer).
  void write(std::string_view text) {
    if (!buffer_.empty()) std::fwrite(buffer_.data(), 1, buffer_.size(), stdout);
    buffer_.clear();
    if (!text.empty()) std::fwrite(text.data(), 1, text.size(), stdout);
  }

 private:
  static constexpr std::size_t kFlushBytes = 1 << 20;
  std::string buffer_;
};

/// Writes `text` to standard output when `out` is empty, otherwise to the file `out` through
/// io::writeFileAtomic (a failed write leaves no partial file). Does not check for an existing
/// file.
void writeTextOutput(const std::string& out, const std::string& text);

/// Reads the CSV input `path` whole for a workflow, named as a streaming io::CsvReader names it:
/// "-" is standard input, named "-"; a file that cannot be opened throws pkm::IoError
/// "PATH: cannot open: REASON".
[[nodiscard]] io::NamedText readCsvInput(const std::string& path);

/// The folder of the running pkm program (from /proc/self/exe; empty when unknown): its sibling
/// programs (pkm-serve, pkm-truth) are there.
[[nodiscard]] std::filesystem::path programDirectory();

/// Prints each notice to stderr as "pkm: note: ...".
void printNotices(const std::vector<std::string>& notices);

/// A workflow's RunControl for a command: notices printed as "pkm: note: ...", progress messages
/// as one line rewritten in place on a terminal's standard error (nothing when it is not a
/// terminal). Call finish() after the workflow to end that line.
class CliRunControl {
 public:
  CliRunControl();
  CliRunControl(const CliRunControl&) = delete;
  CliRunControl& operator=(const CliRunControl&) = delete;
  [[nodiscard]] const workflow::RunControl& control() const { return control_; }
  /// Ends the progress line, if one was shown.
  void finish();

 private:
  workflow::RunControl control_;
  bool shown_ = false;
};

/// Adds --machine (-m) and --ini to `cmd`, stored in `spec` and `ini`.
void addMachineOptions(CLI::App& cmd, std::string& spec, std::string& ini);

/// Options every machine-using command shares.
struct MachineOption {
  std::string spec = "default";
  std::string ini;
  /// Adds --machine and --ini to `cmd`.
  void add(CLI::App& cmd);
  /// Loads the machine (throws pkm::IoError) and prints its notices.
  [[nodiscard]] io::HexapodMachine load() const;
};

/// Registers the command groups.
void addHexapodCommands(CLI::App& app);
void addDemoCommand(CLI::App& app);
void addExechonCommands(CLI::App& app);
void addVolumetricCommand(CLI::App& app);
void addSimulateCommand(CLI::App& app);
void addMachinesCommand(CLI::App& app);
void addCalibrateCommand(CLI::App& app);
void addPlanPosesCommand(CLI::App& app);

/// Adds one top-level command group to the application (for self-registering command files).
using CommandAdder = void (*)(CLI::App& app);
/// Registers a top-level command group: a command file defines, in an anonymous namespace,
/// `const pkm::cli::CommandRegistration kRegisterX{ORDER, "NAME", &addX};` (NAME: the subcommand
/// addX adds) and main() adds every registered group after the built-in ones, in increasing ORDER.
struct CommandRegistration {
  CommandRegistration(int order, const char* name, CommandAdder add);
};
/// Whether a registered command group is named `name`.
[[nodiscard]] bool isRegisteredCommand(std::string_view name);
/// Adds the registered command groups to `app` (called once by main()): all of them, or only the
/// one named `only` when that is given.
void addRegisteredCommands(CLI::App& app, std::string_view only = {});

/// Sets `footer` on `app` and every subcommand below it (each `--help` ends with it).
void setFooter(CLI::App& app, const std::string& footer);

}  // namespace pkm::cli
