// Registry of self-registering top-level command groups (cli_common.hpp: CommandRegistration).
#include <algorithm>
#include <string_view>
#include <vector>

#include "cli_common.hpp"

namespace pkm::cli {
namespace {

struct Entry {
  int order;
  const char* name;
  CommandAdder add;
};

std::vector<Entry>& registry() {
  static std::vector<Entry> entries;
  return entries;
}

}  // namespace

CommandRegistration::CommandRegistration(int order, const char* name, CommandAdder add) {
  registry().push_back({order, name, add});
}

bool isRegisteredCommand(std::string_view name) {
  return std::any_of(
      registry().begin(), registry().end(), [name](const Entry& e) { return e.name == name; });
}

void addRegisteredCommands(CLI::App& app, std::string_view only) {
  std::vector<Entry> entries = registry();
  std::stable_sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
    return a.order < b.order;
  });
  for (const Entry& e : entries)
    if (only.empty() || e.name == only) e.add(app);
}

}  // namespace pkm::cli
