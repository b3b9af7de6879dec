// Tracker registration files (io/registration_files.hpp; docs/formats.md).
#include "pkm/io/registration_files.hpp"

#include <fmt/format.h>

#include <set>

#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/io/number_format.hpp"
#include "pkm/io/text_table.hpp"

namespace pkm::io {

namespace sim = pkm::simulation;

namespace {

constexpr std::size_t kMinNests = 3;  // a rigid fit needs three points off one line

void appendVector(std::string& out, const Eigen::Vector3d& v) {
  for (Eigen::Index k = 0; k < 3; ++k) {
    out += ',';
    appendNumber(out, v[k]);
  }
}

}  // namespace

std::string registrationCsv(const Metadata& metadata,
                            const std::vector<sim::NestReading>& readings) {
  std::string out;
  for (const auto& [key, value] : metadata) out += fmt::format("# {}: {}\n", key, value);
  out += "nest,x_table,y_table,z_table,x,y,z\n";
  for (std::size_t k = 0; k < readings.size(); ++k) {
    out += std::to_string(k + 1);
    appendVector(out, readings[k].world);
    appendVector(out, readings[k].measured);
    out += '\n';
  }
  return out;
}

Metadata registrationMetadata(const std::string& scenario,
                              std::uint64_t seed,
                              const sim::TrackerSetup& setup) {
  const sim::TrackerNoise& n = setup.noise;
  return {
      {"format", "pkm.tracker-registration/1"},
      {"scenario", scenario},
      {"seed", std::to_string(seed)},
      {"measurement", setup.name},
      {"instrument", "laser tracker with an SMR in each fiducial nest (simulated)"},
      {"frame",
       "tracker (x, y, z in the tracker's own frame, from the placement of the measurement; "
       "x_table, y_table, z_table the nest's coordinates in the machine's world frame)"},
      {"noise",
       fmt::format("range sigma {} mm + {} ppm, angle sigma {} urad",
                   formatNumber(n.range_sigma),
                   formatNumber(n.range_ppm),
                   formatNumber(n.angle_sigma * kUradPerRad))},
      {"nests", std::to_string(setup.registration_nests.size())},
      {"columns", "nest; x_table,y_table,z_table mm (world); x,y,z mm (tracker)"},
  };
}

RegistrationFile parseRegistrationCsv(const NamedText& file) {
  const TextTable t = TextTable::parseData(file.text, file.name);
  if (const auto frame = t.meta("frame"); frame && !frame->starts_with("tracker"))
    t.failHeader(
        fmt::format("metadata 'frame: {}': a registration reads nests from the "
                    "tracker's own frame ('# frame: tracker')",
                    *frame));
  const std::size_t nest = t.column({"nest"});
  const std::size_t cols[6] = {t.column({"x_table", "x_table_mm"}),
                               t.column({"y_table", "y_table_mm"}),
                               t.column({"z_table", "z_table_mm"}),
                               t.column({"x", "x_mm"}),
                               t.column({"y", "y_mm"}),
                               t.column({"z", "z_mm"})};
  RegistrationFile out;
  out.source = file.name;
  out.metadata = t.metadata();
  std::set<std::string> seen;
  for (std::size_t r = 0; r < t.rows(); ++r) {
    const std::string name(t.text(r, nest));
    if (name.empty()) t.fail(r, "the nest has no name");
    if (!seen.insert(name).second) t.fail(r, fmt::format("nest '{}' appears twice", name));
    double v[6];
    for (std::size_t k = 0; k < 6; ++k) v[k] = t.number(r, cols[k]);
    out.nests.push_back(name);
    out.world.emplace_back(v[0], v[1], v[2]);
    out.measured.emplace_back(v[3], v[4], v[5]);
    out.lines.push_back(t.line(r));
  }
  if (out.nests.size() < kMinNests)
    t.fail(t.rows() - 1,
           fmt::format("{} nests: a registration needs at least {} nests off one line",
                       out.nests.size(),
                       kMinNests));
  return out;
}

}  // namespace pkm::io
