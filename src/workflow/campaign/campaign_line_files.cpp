// Laser measurement files of a campaign step read back into line data (campaign_steps.hpp,
// readLineFolder): the same files `pkm simulate` writes, or a user's in that format.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <regex>

#include "campaign_steps.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/environment_records.hpp"
#include "pkm/io/measurement_files.hpp"
#include "pkm/io/text_table.hpp"

namespace pkm::workflow::campaign {

namespace sim = pkm::simulation;
namespace fs = std::filesystem;

namespace {

std::string metaOf(const io::Metadata& m, const std::string& key) {
  for (const auto& [k, v] : m)
    if (k == key) return v;
  return {};
}

/// "(a, b, c, ...)" as numbers; throws naming the file.
Eigen::VectorXd vectorOf(const std::string& text, const std::string& file, const std::string& key) {
  static const std::regex number(R"([-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?)");
  if (text.size() < 2 || text.front() != '(' || text.back() != ')')
    throw IoError(
        fmt::format("{}: metadata '{}' must be '(a, b, ...)', got '{}'", file, key, text));
  std::vector<double> v;
  std::string inner = text.substr(1, text.size() - 2);
  std::size_t pos = 0;
  while (pos <= inner.size()) {
    const std::size_t comma = std::min(inner.find(',', pos), inner.size());
    std::string field = inner.substr(pos, comma - pos);
    field.erase(0, field.find_first_not_of(' '));
    field.erase(field.find_last_not_of(' ') + 1);
    if (!std::regex_match(field, number))
      throw IoError(fmt::format("{}: metadata '{}': '{}' is not a number", file, key, field));
    v.push_back(std::stod(field));
    pos = comma + 1;
  }
  return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

sim::LineQuantity quantityOf(const std::string& text, const std::string& file) {
  for (sim::LineQuantity q :
       {sim::LineQuantity::kLinear, sim::LineQuantity::kStraightness, sim::LineQuantity::kAngular})
    if (text == sim::toString(q)) return q;
  throw IoError(fmt::format(
      "{}: metadata 'quantity' '{}' is not linear, straightness or angular", file, text));
}

}  // namespace

std::string dataFolder(const StepContext& ctx) {
  const Json& data = ctx.spec["data"];
  if (!data.is_object() || !data.contains("folder") || !data["folder"].is_string())
    throw IoError(fmt::format("{}: \"data\" must be {{\"folder\": DIR}} (laser measurement files)",
                              ctx.source));
  return data["folder"].get<std::string>();
}

LineFiles readLineFolder(const StepContext& ctx, const std::string& folder) {
  fs::path dir(folder);
  if (dir.is_relative()) dir = ctx.base_dir / dir;
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw IoError(fmt::format("{}: {}: no such folder", ctx.source, dir.string()));
  std::vector<std::string> paths;
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (e.is_regular_file() && e.path().extension() == ".csv") paths.push_back(e.path().string());
  std::sort(paths.begin(), paths.end());
  LineFiles out;
  std::map<std::string, std::size_t> index;  // measurement -> position in results
  for (const std::string& path : paths) {
    const io::TextTable table = io::TextTable::read(path);
    if (table.meta("format").value_or("") != "pkm.measurement/1") continue;
    // The files' environment records and set-up metadata (docs/formats.md).
    out.data.records.merge(io::environmentRecords(table));
    const io::LineRunFile f = io::readLineRunCsv(path);
    const std::string name = metaOf(f.metadata, "measurement");
    if (name.empty()) throw IoError(fmt::format("{}: metadata 'measurement' is missing", path));
    out.paths.push_back(path);
    auto it = index.find(name);
    if (it == index.end()) {
      sim::LineSetup s;
      s.name = name;
      s.quantity = quantityOf(metaOf(f.metadata, "quantity"), path);
      s.line.start = vectorOf(metaOf(f.metadata, "line start"), path, "line start");
      s.line.direction = vectorOf(metaOf(f.metadata, "line direction"), path, "line direction");
      if (s.line.start.size() != s.line.direction.size())
        throw IoError(fmt::format("{}: 'line start' and 'line direction' differ in size", path));
      std::smatch m;
      const std::string noise = metaOf(f.metadata, "noise");
      static const std::regex noise_re(R"(sigma ([0-9.eE+-]+) (mm|urad), ([0-9.eE+-]+) ppm)");
      if (std::regex_search(noise, m, noise_re)) {
        const double scale = m[2] == "urad" ? 1e-6 : 1.0;
        s.noise.sigma = std::stod(m[1]) * scale;
        s.noise.sigma_ppm = std::stod(m[3]);
      }
      out.setups.push_back(std::move(s));
      it = index.emplace(name, out.data.results.size()).first;
      out.data.results.push_back({&out.setups.back(), {}});
    }
    sim::MeasurementResult& result = out.data.results[it->second];
    const double scale = f.reading_unit == "urad" ? 1e-6 : 1.0;
    for (std::size_t k = 0; k < f.readings.size(); ++k) {
      auto run = std::find_if(result.runs.begin(), result.runs.end(), [&](const sim::LineRun& r) {
        return r.run == f.runs[k];
      });
      if (run == result.runs.end()) {
        result.runs.push_back({f.runs[k], {}});
        run = std::prev(result.runs.end());
      }
      sim::LineReading r = f.readings[k];
      r.reading *= scale;
      run->readings.push_back(r);
    }
  }
  if (out.data.results.empty())
    throw IoError(fmt::format(
        "{}: {}: no measurement file (# format: pkm.measurement/1)", ctx.source, dir.string()));
  auto setup = out.setups.begin();  // the set-ups are in the order of the results
  for (const sim::MeasurementResult& r : out.data.results) {
    double lo = INFINITY, hi = -INFINITY;
    for (const sim::LineRun& run : r.runs)
      for (const sim::LineReading& x : run.readings) {
        lo = std::min(lo, x.target);
        hi = std::max(hi, x.target);
      }
    setup->cycle.first = lo;
    setup->cycle.last = hi;
    setup->cycle.runs = static_cast<int>(r.runs.size());
    ++setup;
  }
  return out;
}

}  // namespace pkm::workflow::campaign
