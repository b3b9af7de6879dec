// Campaign step "probe-offset" on measured touch-probe files (the format of `pkm simulate`,
// docs/formats.md): offset touches on the master ring, and the ring measured without and with the
// DRM compensation. No virtual machine: the step evaluates what was measured (docs/campaign.md,
// "Measured data").
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <numbers>

#include "campaign_steps.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/calibration_files.hpp"
#include "pkm/io/text_table.hpp"

namespace pkm::workflow::campaign {

namespace sim = pkm::simulation;

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

std::string dataFile(const StepContext& ctx, const Json& data, const char* key) {
  if (!data.contains(key) || !data[key].is_string())
    throw IoError(fmt::format("{}: \"data\".\"{}\" must name a touch-probe file", ctx.source, key));
  std::filesystem::path p(data[key].get<std::string>());
  if (p.is_relative()) p = ctx.base_dir / p;
  if (!std::filesystem::is_regular_file(p))
    throw IoError(fmt::format("{}: {}: no such file", ctx.source, p.string()));
  return p.string();
}

double metaNumber(const io::TextTable& t, const char* key) {
  const auto v = t.meta(key);
  if (!v) t.failHeader(fmt::format("metadata '{}' is missing", key));
  try {
    std::size_t used = 0;
    const double x = std::stod(*v, &used);
    if (used == v->size() && std::isfinite(x)) return x;
  } catch (const std::exception&) {
  }
  t.failHeader(fmt::format("metadata '{}' is not a number: '{}'", key, *v));
}

Eigen::Vector3d metaVector(const io::TextTable& t, const char* key) {
  const auto v = t.meta(key);
  if (!v) t.failHeader(fmt::format("metadata '{}' is missing", key));
  const std::vector<Eigen::Vector3d> list = io::parseVectorList(*v, t.source(), key);
  if (list.size() != 1) t.failHeader(fmt::format("metadata '{}' is not one vector", key));
  return list.front();
}

/// Touches of a file: the spindle-axis position (x, y, z or spindle_x, spindle_y, z), the spindle
/// angle and φ_DRM (degrees in the file).
std::vector<sim::TouchRecord> touches(const io::TextTable& t, bool circle) {
  const std::size_t cx = t.column({circle ? "spindle_x" : "x"});
  const std::size_t cy = t.column({circle ? "spindle_y" : "y"});
  const std::size_t cz = t.column({"z"});
  const std::size_t cs = t.column({"spindle_deg"});
  const std::size_t cd = t.column({"drm_deg"});
  std::vector<sim::TouchRecord> out;
  for (std::size_t r = 0; r < t.rows(); ++r) {
    sim::TouchRecord rec;
    rec.position = Eigen::Vector3d(t.number(r, cx), t.number(r, cy), t.number(r, cz));
    rec.spindle = t.number(r, cs) * kDeg;
    rec.drm = t.number(r, cd) * kDeg;
    if (!rec.position.allFinite() || !std::isfinite(rec.spindle) || !std::isfinite(rec.drm))
      t.fail(r, "a value is not finite");
    out.push_back(rec);
  }
  if (out.empty()) t.failHeader("the file has no touches");
  return out;
}

}  // namespace

ProbeFiles readProbeFiles(const StepContext& ctx) {
  const Json& data = ctx.spec["data"];
  if (!data.is_object())
    throw IoError(fmt::format(
        "{}: \"data\" must be an object naming \"offset\", \"circle_before\" and \"circle_after\"",
        ctx.source));
  ProbeFiles f;
  f.paths = {dataFile(ctx, data, "offset"),
             dataFile(ctx, data, "circle_before"),
             dataFile(ctx, data, "circle_after")};
  const io::TextTable offset = io::TextTable::read(f.paths[0]);
  const io::TextTable before = io::TextTable::read(f.paths[1]);
  const io::TextTable after = io::TextTable::read(f.paths[2]);
  f.setup.ring_diameter = metaNumber(offset, "ring diameter mm");
  f.setup.ball_radius = metaNumber(offset, "stylus ball radius mm");
  f.setup.offset_ring_center = metaVector(offset, "ring centre mm");
  f.setup.circle_ring_center = metaVector(before, "ring centre mm");
  if (before.meta("ring form mm")) f.setup.ring_form = metaNumber(before, "ring form mm");
  f.setup.direction = metaVector(offset, "tool direction");
  if (!(f.setup.ring_diameter > 2.0 * f.setup.ball_radius) || !(f.setup.ball_radius > 0.0))
    offset.failHeader("the stylus ball does not fit the ring");
  if (std::abs(std::abs(f.setup.direction.z()) - 1.0) > 1e-9)
    offset.failHeader("'tool direction' must be (0, 0, 1) or (0, 0, -1)");
  f.offset = touches(offset, false);
  f.before = touches(before, true);
  f.after = touches(after, true);
  return f;
}

}  // namespace pkm::workflow::campaign
