// Registry of self-registering top-level command groups (cli_common.hpp: CommandRegistration).
#include <algorithm>
#include <vector>

#include "cli_common.hpp"

namespace pkm::cli {
namespace {

struct Entry {
  int order;
  CommandAdder add;
};

std::vector<Entry>& registry() {
  static std::vector<Entry> entries;
  return entries;
}

}  // namespace

CommandRegistration::CommandRegistration(int order, CommandAdder add) {
  registry().push_back({order, add});
}

void addRegisteredCommands(CLI::App& app) {
  std::vector<Entry> entries = registry();
  std::stable_sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
    return a.order < b.order;
  });
  for (const Entry& e : entries) e.add(app);
}

}  // namespace pkm::cli
