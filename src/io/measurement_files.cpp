#include "pkm/io/measurement_files.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <sstream>

#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/io/csv.hpp"
#include "pkm/io/number_format.hpp"

namespace pkm::io {

namespace sim = pkm::simulation;

namespace {

/// The largest run number a measurement file may give (an int; no instrument numbers more).
constexpr int kMaxRun = 1'000'000'000;

}  // namespace

std::string lineRunCsv(sim::LineQuantity quantity,
                       const Metadata& metadata,
                       const sim::LineRun& run) {
  std::string out;
  for (const auto& [key, value] : metadata) out += fmt::format("# {}: {}\n", key, value);
  const bool angular = quantity == sim::LineQuantity::kAngular;
  bool steps = false;
  for (const sim::LineReading& r : run.readings) steps = steps || r.sub_step != 0;
  const bool sensed = std::any_of(
      run.readings.begin(), run.readings.end(), [](const auto& r) { return r.sensed.recorded; });
  out += angular ? "target_mm,run,direction,reading_urad" : "target_mm,run,direction,reading_mm";
  if (steps) out += ",sub_step";
  if (sensed) out += ",air_temperature_c,air_pressure_pa,air_humidity_rh,material_temperature_c";
  out += '\n';
  for (const sim::LineReading& r : run.readings) {
    appendNumber(out, r.target);
    out += fmt::format(",{},{},", run.run, r.direction > 0 ? '+' : '-');
    appendNumber(out, angular ? r.reading * kUradPerRad : r.reading);
    if (steps) out += fmt::format(",{}", r.sub_step);
    if (sensed) {
      const sim::SensedConditions& c = r.sensed;
      // The compensation unit's display resolution: 0.01 °C, 1 Pa, 0.1 %RH.
      out += fmt::format(",{:.3f},{:.1f},{:.2f},{:.3f}",
                         c.air_temperature_c,
                         c.air_pressure_pa,
                         c.air_humidity_rh,
                         c.material_temperature_c);
    }
    out += '\n';
  }
  return out;
}

std::string dialGaugeCsv(const Metadata& metadata,
                         const std::vector<sim::DialGaugeStation>& stations) {
  std::string out;
  for (const auto& [key, value] : metadata) out += fmt::format("# {}: {}\n", key, value);
  out +=
      "station,x_mm,y_mm,z_mm,a_deg,b_deg,c_deg,l0_mm,l1_mm,l2_mm,l3_mm,l4_mm,l5_mm,g0_mm,g1_mm,g2_"
      "mm,"
      "iterations,converged\n";
  for (const sim::DialGaugeStation& s : stations) {
    out += std::to_string(s.station);
    for (Eigen::Index i = 0; i < 6; ++i) {
      out += ',';
      appendNumber(out, i < 3 ? s.command[i] : radToDeg(s.command[i]));
    }
    for (Eigen::Index i = 0; i < s.lengths.size(); ++i) {
      out += ',';
      appendNumber(out, s.lengths[i]);
    }
    for (const double g : s.readings) {
      out += ',';
      appendNumber(out, g);
    }
    out += fmt::format(",{},{}\n", s.iterations, s.converged ? 1 : 0);
  }
  return out;
}

LineRunFile parseLineRunCsv(const std::string& text, const std::string& source) {
  LineRunFile file;
  std::array<int, 5> column{-1, -1, -1, -1, -1};  // target, run, direction, reading, sub_step
  std::size_t fields_expected = 0;
  std::istringstream in(text);
  std::size_t line_no = 0;
  bool header = false;
  for (std::string raw; std::getline(in, raw);) {
    ++line_no;
    std::string_view line = trimBlanks(raw);
    if (line_no == 1 && line.starts_with("\xEF\xBB\xBF")) line.remove_prefix(3);
    if (line.empty()) continue;
    const auto fail = [&](const std::string& what) {
      throw IoError(locate(source, line_no, what));
    };
    if (line.front() == '#') {
      const std::string_view body = trimBlanks(line.substr(1));
      const std::size_t colon = body.find(':');
      if (!header && colon != std::string_view::npos)
        file.metadata.emplace_back(trimBlanks(body.substr(0, colon)),
                                   trimBlanks(body.substr(colon + 1)));
      continue;
    }
    const std::vector<std::string_view> fields = splitFields(line);
    if (!header) {
      for (std::size_t i = 0; i < fields.size(); ++i) {
        const std::string_view f = fields[i];
        const auto idx = static_cast<int>(i);
        if (f == "target_mm") column[0] = idx;
        if (f == "run") column[1] = idx;
        if (f == "direction") column[2] = idx;
        if (f == "sub_step") column[4] = idx;
        if (f == "reading_mm" || f == "reading_urad") {
          if (column[3] >= 0) fail("both reading_mm and reading_urad columns");
          column[3] = idx;
          file.reading_unit = f == "reading_mm" ? "mm" : "urad";
        }
      }
      const char* names[] = {"target_mm", "run", "direction", "reading_mm or reading_urad"};
      for (std::size_t c = 0; c < 4; ++c)
        if (column[c] < 0) fail(fmt::format("missing column '{}'", names[c]));
      fields_expected = fields.size();
      header = true;
      continue;
    }
    if (fields.size() != fields_expected)
      fail(fmt::format("expected {} fields, found {}", fields_expected, fields.size()));
    const auto field = [&](int c) {
      return fields[static_cast<std::size_t>(column[static_cast<std::size_t>(c)])];
    };
    sim::LineReading r;
    double run = 0.0;
    if (!parseFiniteDouble(field(0), r.target))
      fail(fmt::format("target_mm '{}' is not a number", field(0)));
    // Range first: converting a double beyond int's range to int is undefined behaviour.
    if (!parseFiniteDouble(field(1), run) || run < 1 || run > kMaxRun || run != std::floor(run))
      fail(fmt::format("run '{}' is not an integer from 1 to {}", field(1), kMaxRun));
    const std::string_view d = field(2);
    if (d == "+" || d == "+1" || d == "1")
      r.direction = 1;
    else if (d == "-" || d == "-1")
      r.direction = -1;
    else
      fail(fmt::format("direction '{}' is not + or -", d));
    if (!parseFiniteDouble(field(3), r.reading))
      fail(fmt::format("reading '{}' is not a number", field(3)));
    if (column[4] >= 0) {
      double step = 0.0;
      if (!parseFiniteDouble(field(4), step) || step < 0 || step > 1000 || step != std::floor(step))
        fail(fmt::format("sub_step '{}' is not an integer >= 0", field(4)));
      r.sub_step = static_cast<int>(step);
    }
    file.runs.push_back(static_cast<int>(run));
    file.readings.push_back(r);
  }
  if (!header) throw IoError(locate(source, 0, "no header row"));
  return file;
}

LineRunFile readLineRunCsv(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(locate(path, 0, "cannot open the file"));
  std::ostringstream text;
  text << in.rdbuf();
  return parseLineRunCsv(text.str(), path);
}

}  // namespace pkm::io
