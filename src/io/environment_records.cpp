// Environment records of measurement files (io/environment_records.hpp).
#include "pkm/io/environment_records.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <string>
#include <tuple>

#include "pkm/core/error.hpp"
#include "pkm/io/export_columns.hpp"
#include "pkm/io/renishaw_rtl.hpp"

namespace pkm::io {
namespace {

enum Quantity { kAirTemperature, kAirPressure, kAirHumidity, kMaterialTemperature, kCount };

constexpr std::array<const char*, kCount> kWhat = {
    "air temperature", "air pressure", "air humidity", "material temperature"};
/// Plausible ranges (the Edlén equation's for the air).
constexpr std::array<std::array<double, 2>, kCount> kRange = {
    {{-40.0, 100.0}, {60000.0, 140000.0}, {0.0, 100.0}, {-50.0, 100.0}}};

/// `unit` without a degree sign, lower case.
std::string plainUnit(std::string unit) {
  for (const std::string& deg : {std::string("\xC2\xB0"), std::string("deg ")})
    for (std::size_t p = unit.find(deg); p != std::string::npos; p = unit.find(deg))
      unit.erase(p, deg.size());
  return unit;
}

/// value = scale·x + offset converting `unit` to degC, Pa or %RH; nullopt for an unknown unit.
std::optional<std::array<double, 2>> conversion(Quantity q, const std::string& raw) {
  const std::string u = plainUnit(raw);
  if (q == kAirTemperature || q == kMaterialTemperature) {
    if (u.empty() || u == "c" || u == "degc") return std::array{1.0, 0.0};
    if (u == "k") return std::array{1.0, -273.15};
  } else if (q == kAirPressure) {
    if (u.empty() || u == "pa") return std::array{1.0, 0.0};
    if (u == "hpa" || u == "mbar") return std::array{100.0, 0.0};
    if (u == "kpa") return std::array{1000.0, 0.0};
    if (u == "mmhg") return std::array{133.322387415, 0.0};
  } else if (u.empty() || u == "%" || u == "%rh" || u == "rh" || u == "percent") {
    return std::array{1.0, 0.0};
  }
  return std::nullopt;
}

/// The quantity a normalised column name gives, if any.
std::optional<Quantity> quantityOf(const std::string& name) {
  if (name == "air temperature" || name == "air temp") return kAirTemperature;
  if (name == "air pressure" || name == "pressure" || name == "barometric pressure")
    return kAirPressure;
  if (name == "air humidity" || name == "humidity" || name == "relative humidity" || name == "rh")
    return kAirHumidity;
  for (const char* stem : {"material temperature", "material temp", "mat temp"}) {
    const std::string s(stem);
    if (name.rfind(s, 0) != 0) continue;
    const std::string rest = name.substr(s.size());
    if (rest.empty() || (rest.size() >= 2 && rest[0] == ' ' &&
                         rest.find_first_not_of("0123456789", 1) == std::string::npos))
      return kMaterialTemperature;
  }
  return std::nullopt;
}

struct Column {
  Quantity quantity;
  std::size_t index;
  std::array<double, 2> convert;
};

/// The header's environment columns; a last word that is a unit of the quantity is its unit.
std::vector<Column> columnsOf(const TextTable& table) {
  std::vector<Column> out;
  for (std::size_t c = 0; c < table.header().size(); ++c) {
    HeaderField f = splitHeaderField(table.header()[c]);
    std::optional<Quantity> q = quantityOf(f.name);
    if (!q && f.unit.empty()) {
      const std::size_t space = f.name.rfind(' ');
      if (space != std::string::npos) {
        q = quantityOf(f.name.substr(0, space));
        if (q && conversion(*q, f.name.substr(space + 1)))
          f.unit = f.name.substr(space + 1);
        else
          q.reset();
      }
    }
    if (!q) continue;
    const auto convert = conversion(*q, f.unit);
    if (!convert)
      table.failHeader(fmt::format(
          "column '{}': unknown unit '{}' for the {}", table.header()[c], f.unit, kWhat[*q]));
    out.push_back({*q, c, *convert});
  }
  return out;
}

double checked(const TextTable& t, std::optional<std::size_t> row, Quantity q, double v) {
  if (v >= kRange[q][0] && v <= kRange[q][1]) return v;
  const std::string what = fmt::format(
      "{} {} is outside the plausible range {}..{}", kWhat[q], v, kRange[q][0], kRange[q][1]);
  if (row) t.fail(*row, what);
  t.failHeader(what);
}

/// A metadata number, if the key is present.
std::optional<double> metaNumber(const TextTable& t, const char* key) {
  const std::optional<std::string> text = t.meta(key);
  if (!text) return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(text->c_str(), &end);
  if (text->empty() || end != text->c_str() + text->size() || !std::isfinite(v))
    throw IoError(
        fmt::format("{}: metadata '{}': '{}' is not a finite number", t.source(), key, *text));
  return v;
}

}  // namespace

metrology::RecordedConditions environmentRecords(const TextTable& table) {
  std::array<std::optional<metrology::RecordedSeries>, kCount> series;
  const std::vector<Column> columns = columnsOf(table);
  for (std::size_t r = 0; r < table.rows(); ++r) {
    std::array<double, kCount> sum{};
    std::array<int, kCount> n{};
    for (const Column& c : columns) {
      sum[c.quantity] += c.convert[0] * table.number(r, c.index) + c.convert[1];
      ++n[c.quantity];
    }
    for (int q = 0; q < kCount; ++q) {
      if (n[q] == 0) continue;
      const double v = checked(table, r, static_cast<Quantity>(q), sum[q] / n[q]);
      if (!series[q]) series[q].emplace();
      series[q]->add(v);
    }
  }
  constexpr std::array<const char*, kCount> kMeta = {
      "air temperature C", "air pressure Pa", "air humidity %RH", "material temperature C"};
  for (int q = 0; q < kCount; ++q) {
    if (series[q]) continue;
    if (const std::optional<double> v = metaNumber(table, kMeta[q])) {
      series[q].emplace();
      series[q]->add(checked(table, std::nullopt, static_cast<Quantity>(q), *v));
    }
  }
  metrology::RecordedConditions out;
  out.air_temperature_c = series[kAirTemperature];
  out.air_pressure_pa = series[kAirPressure];
  out.air_humidity_rh = series[kAirHumidity];
  out.material_temperature_c = series[kMaterialTemperature];
  for (const auto& [key, field, scale] :
       {std::tuple{"dead path mm", &out.dead_path_mm, 1.0},
        std::tuple{"beam alignment urad", &out.misalignment_rad, 1e-6},
        std::tuple{"abbe offset mm", &out.abbe_offset_mm, 1.0},
        std::tuple{"angular range urad", &out.angular_range_rad, 1e-6}}) {
    const std::optional<double> v = metaNumber(table, key);
    if (!v) continue;
    if (*v < 0.0)
      throw IoError(fmt::format("{}: metadata '{}' must be >= 0, got {}", table.source(), key, *v));
    *field = *v * scale;
  }
  return out;
}

metrology::RecordedConditions readEnvironmentRecords(const std::vector<NamedText>& files) {
  metrology::RecordedConditions out;
  for (const NamedText& f : files) {
    if (isRenishawRtl(f.text)) continue;
    out.merge(environmentRecords(TextTable::parse(f.text, f.name)));
  }
  return out;
}

}  // namespace pkm::io
