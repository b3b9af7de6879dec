// Subroutine files (LinuxCNC 2.9 G-code reference, "O Codes", "Calling Files"): a call to a sub
// the program does not define runs the sub of that name from NAME.ngc, found in the working
// folder (as rs274 looks for it) or in the INI's SUBROUTINE_PATH.
#include <fmt/format.h>

#include <filesystem>

#include "interpreter_impl.hpp"
#include "pkm/cnc/gcode_error.hpp"

namespace pkm::cnc {

namespace fs = std::filesystem;

Interpreter::Impl::Outcome Interpreter::Impl::callExternal(std::size_t line,
                                                           const std::string& name,
                                                           const std::vector<double>& args,
                                                           MoveSink& sink) {
  std::vector<fs::path> folders;
  if (options.search_working_folder) folders.emplace_back(".");
  for (const std::string& d : options.subroutine_path) folders.emplace_back(d);
  fs::path found;
  for (const fs::path& d : folders) {
    std::error_code ec;
    if (fs::is_regular_file(d / (name + ".ngc"), ec)) {
      found = d / (name + ".ngc");
      break;
    }
  }
  if (found.empty())
    throw GcodeError(
        fmt::format("call to undefined subroutine {}: the program does not define it "
                    "and no {}.ngc was found ({} folder{} searched)",
                    oLabel(name),
                    name,
                    folders.size(),
                    folders.size() == 1 ? "" : "s"));
  if (external_depth >= options.max_call_depth)
    throw GcodeError(fmt::format("subroutine calls nested deeper than {}", options.max_call_depth));
  auto& slot = sub_files[found.string()];
  if (!slot) slot = std::make_unique<Program>(Program::load(found.string()));
  const Program& file = *slot;
  const std::size_t start = file.findSub(name);
  if (start == kNoBlock)
    throw GcodeError(fmt::format("{} does not define {} sub", found.string(), oLabel(name)));
  params.pushCall(args);
  if (external_depth == 0) external_call_line = line;  // motions in the file report this line
  // The depth goes back down however the sub ends (an error leaves the interpreter reusable).
  struct Depth {
    std::size_t& depth;
    explicit Depth(std::size_t& d) : depth(d) { ++depth; }
    ~Depth() { --depth; }
    Depth(const Depth&) = delete;
    Depth& operator=(const Depth&) = delete;
  } const guard(external_depth);
  const Outcome outcome = runProgram(file, start + 1, sink, true);
  if (outcome == Outcome::kFellOff)
    throw GcodeError(
        fmt::format("{}: {} sub ran past the end of the file", found.string(), oLabel(name)));
  return outcome;
}

}  // namespace pkm::cnc
