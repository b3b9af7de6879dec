// The machining preview's part of POST /api/gcode/run (api_machining.hpp).
#include "api_machining.hpp"

#include <fmt/format.h>

#include <bit>
#include <cstring>

namespace pkm::server::detail {
namespace {

/// The most cell changes a preview sends (about 11 MB of base64).
constexpr std::size_t kMaxMachiningChanges = 1'000'000;
/// The most animation moments of a preview.
constexpr std::size_t kMaxMachiningFrames = 2'000;

/// `bytes` as base64 (RFC 4648, with padding).
std::string base64(const unsigned char* bytes, std::size_t n) {
  static constexpr char kDigits[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((n + 2) / 3 * 4);
  for (std::size_t i = 0; i < n; i += 3) {
    const std::uint32_t b0 = bytes[i];
    const std::uint32_t b1 = i + 1 < n ? bytes[i + 1] : 0u;
    const std::uint32_t b2 = i + 2 < n ? bytes[i + 2] : 0u;
    const std::uint32_t v = (b0 << 16) | (b1 << 8) | b2;
    out += kDigits[(v >> 18) & 63];
    out += kDigits[(v >> 12) & 63];
    out += i + 1 < n ? kDigits[(v >> 6) & 63] : '=';
    out += i + 2 < n ? kDigits[v & 63] : '=';
  }
  return out;
}

/// A float or uint32 array as base64 of its little-endian bytes.
template <class T>
std::string base64Of(const std::vector<T>& v) {
  static_assert(sizeof(T) == 4 && std::endian::native == std::endian::little);
  return base64(reinterpret_cast<const unsigned char*>(v.data()), v.size() * sizeof(T));
}

/// Field `key` of `m`: an array of exactly `n` finite numbers, or HttpError 400.
template <std::size_t N>
void numbers(const Json& m, const char* key, std::array<double, N>& out) {
  if (!m.contains(key)) return;
  const Json& a = m[key];
  if (!a.is_array() || a.size() != N)
    throw HttpError(400, fmt::format("\"machining.{}\" must be an array of {} numbers", key, N));
  for (std::size_t i = 0; i < N; ++i) {
    if (!a[i].is_number() || !std::isfinite(a[i].get<double>()))
      throw HttpError(400, fmt::format("\"machining.{}\" must hold finite numbers", key));
    out[i] = a[i].get<double>();
  }
}

Json eventJson(const cnc::MachiningEvent& e) {
  return {{"kind", e.kind},
          {"line", e.line},
          {"t", e.t},
          {"tip", e.tip},
          {"depth", e.depth},
          {"count", e.count}};
}

}  // namespace

std::optional<workflow::MachiningRequest> machiningRequest(const Json& body) {
  if (!body.contains("machining") || body["machining"].is_null()) return std::nullopt;
  const Json& m = body["machining"];
  if (!m.is_object()) throw HttpError(400, "\"machining\" must be an object");
  workflow::MachiningRequest q;
  q.stock = stringField(m, "stock", "auto");
  numbers(m, "box", q.box);
  numbers(m, "cylinder", q.cylinder);
  q.margin = numberField(m, "margin").value_or(q.margin);
  q.cell = numberField(m, "cell").value_or(0.0);
  q.auto_cells = numberField(m, "auto_cells").value_or(q.auto_cells);
  q.frames = countField(m, "frames", kMaxMachiningFrames).value_or(200);
  q.max_changes = kMaxMachiningChanges;
  q.default_tool.diameter = numberField(m, "tool_diameter").value_or(q.default_tool.diameter);
  q.default_tool.holder_diameter =
      numberField(m, "holder_diameter").value_or(q.default_tool.holder_diameter);
  q.default_tool.holder_length =
      numberField(m, "holder_length").value_or(q.default_tool.holder_length);
  return q;
}

Json machiningJson(const workflow::MachiningReport& r) {
  const cnc::StockShape& s = r.stock;
  Json frames = Json::array();
  for (const cnc::StockFrame& f : r.result.frames)
    frames.push_back({{"t", f.t}, {"cells", base64Of(f.cells)}, {"heights", base64Of(f.heights)}});
  Json events = Json::array();
  for (const cnc::MachiningEvent& e : r.result.events) events.push_back(eventJson(e));
  Json tools = Json::array();
  for (const workflow::MachiningTool& t : r.tools)
    tools.push_back({{"number", t.tool.number},
                     {"end", cnc::toString(t.tool.end)},
                     {"diameter", t.tool.diameter},
                     {"length", t.tool.length},
                     {"tip_offset", t.tip_offset},
                     {"holder_diameter", t.tool.holder_diameter},
                     {"holder_length", t.tool.holder_length},
                     {"first_line", t.first_line}});
  Json tips = Json::array(), axes = Json::array();
  for (const cnc::ToolPose& p : r.path_tools) {
    tips.push_back(p.tip);
    axes.push_back(p.axis);
  }
  return {{"stock",
           {{"kind", s.kind == cnc::StockShape::Kind::kCylinder ? "cylinder" : "box"},
            {"text", s.describe()},
            {"bottom", s.bottom},
            {"top", s.top}}},
          {"cell", r.cell},
          {"nx", r.nx},
          {"ny", r.ny},
          {"x0", r.x0},
          {"y0", r.y0},
          {"initial", base64Of(r.initial)},
          {"heights", base64Of(r.heights)},
          {"frames", frames},
          {"frames_complete", r.result.frames_complete},
          {"events", events},
          {"event_counts", r.result.event_counts},
          {"tools", tools},
          {"path_tools", {{"tip", tips}, {"axis", axes}, {"tool", r.path_tool_numbers}}},
          {"initial_volume_mm3", r.result.initial_volume},
          {"final_volume_mm3", r.result.final_volume},
          {"positions", r.result.positions},
          {"seconds", r.seconds}};
}

}  // namespace pkm::server::detail
