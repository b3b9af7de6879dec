// `pkm gcode make KIND [--PARAM V ...]`: a composite machining command (sphere, circular pocket,
// drilling pattern, face mill) as a whole G-code program (docs/gcode.md "gcode make";
// cnc::shapeProgram). The options come from the library's parameter table.
#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <memory>

#include "cli_common.hpp"
#include "pkm/cnc/shapes.hpp"
#include "pkm/io/atomic_file.hpp"

namespace pkm::cli {

namespace {

struct MakeArgs {
  std::map<std::string, double> values;       ///< by parameter name, as given
  std::map<std::string, CLI::Option*> given;  ///< by parameter name
  double feed = 600.0;
  std::string out;
  bool force = false;
};

/// "tool_radius" as the option "--tool-radius".
std::string optionName(std::string name) {
  std::replace(name.begin(), name.end(), '_', '-');
  return "--" + name;
}

void runMake(const std::string& kind, MakeArgs& a) {
  cnc::ShapeSpec spec{kind, {}};
  for (const auto& [name, option] : a.given)
    if (option->count() > 0) spec.values[name] = a.values[name];
  const std::string text = cnc::shapeProgram(spec, a.feed);
  if (a.out.empty()) {
    writeTextOutput("", text);
    return;
  }
  io::writeFileAtomic(a.out, text, a.force ? io::Overwrite::kAllow : io::Overwrite::kRefuse);
}

}  // namespace

void addGcodeMakeCommand(CLI::App& gcode) {
  CLI::App* make = gcode.add_subcommand(
      "make",
      "write a composite machining command as a G-code program: sphere (finished with a ball "
      "end), pocket (circular), drill (holes on a circle), face (zig-zag)");
  make->require_subcommand(1);
  for (const std::string& kind : cnc::shapeKinds()) {
    auto a = std::make_shared<MakeArgs>();
    CLI::App* k =
        make->add_subcommand(kind, fmt::format("a {} (docs/gcode.md \"gcode make\")", kind));
    for (const cnc::ShapeParameter& p : cnc::shapeParameters(kind)) {
      a->values[p.name] = p.value;
      a->given[p.name] = k->add_option(optionName(p.name),
                                       a->values[p.name],
                                       fmt::format("{} (default {:g})", p.meaning, p.value));
    }
    k->add_option("--feed", a->feed, "feed rate, mm/min (default 600)");
    k->add_option("--out", a->out, "write the program to FILE instead of standard output");
    k->add_flag("--force", a->force, "overwrite an existing --out file");
    k->callback([kind, a] { runMake(kind, *a); });
  }
}

}  // namespace pkm::cli
