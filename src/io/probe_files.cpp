#include "pkm/io/probe_files.hpp"

#include <fmt/format.h>

#include "pkm/core/units.hpp"
#include "pkm/io/number_format.hpp"

namespace pkm::io {

namespace sim = pkm::simulation;

namespace {

void row(std::string& out, std::initializer_list<double> values) {
  for (const double v : values) {
    out += ',';
    appendNumber(out, v);
  }
}

std::string header(const Metadata& metadata) {
  std::string out;
  for (const auto& [key, value] : metadata) out += fmt::format("# {}: {}\n", key, value);
  return out;
}

std::string vec(const Eigen::VectorXd& v) {
  std::string out = "(";
  for (Eigen::Index i = 0; i < v.size(); ++i) out += (i ? ", " : "") + formatNumber(v[i]);
  return out + ")";
}

Metadata metadata(const std::string& scenario,
                  std::uint64_t seed,
                  const sim::TouchProbeSetup& s,
                  const std::string& what,
                  const Eigen::Vector3d& centre) {
  Metadata md{
      {"format", "pkm.touch-probe/1"},
      {"scenario", scenario},
      {"seed", std::to_string(seed)},
      {"measurement", s.name},
      {"instrument", "touch-trigger probe with stylus offset on a master ring (simulated)"},
      {"sequence", what},
      {"ring diameter mm", formatNumber(s.ring_diameter)},
      {"stylus ball radius mm", formatNumber(s.ball_radius)},
      {"ring centre mm", vec(centre)},
      {"tool direction", vec(s.direction)},
      {"noise",
       fmt::format("sigma {} mm, resolution {} mm along the approach",
                   formatNumber(s.noise.sigma),
                   formatNumber(s.noise.resolution))},
  };
  // The ring's certificate: its form deviation, which bounds what the ring adds to a roundness.
  if (s.ring_form > 0.0) md.push_back({"ring form mm", formatNumber(s.ring_form)});
  return md;
}

}  // namespace

std::string probeOffsetCsv(const Metadata& md, const std::vector<sim::TouchRecord>& touches) {
  std::string out = header(md) + "touch,run,spindle_deg,drm_deg,x,y,z\n";
  for (const sim::TouchRecord& t : touches) {
    out += fmt::format("{},{}", t.touch, t.run);
    row(out,
        {radToDeg(t.spindle), radToDeg(t.drm), t.position.x(), t.position.y(), t.position.z()});
    out += '\n';
  }
  return out;
}

std::string probeCircleCsv(const Metadata& md,
                           const sim::TouchProbeSetup& setup,
                           const std::vector<sim::TouchRecord>& touches) {
  std::string out = header(md) + "x,y,run,approach_deg,spindle_deg,drm_deg,spindle_x,spindle_y,z\n";
  for (const sim::TouchRecord& t : touches) {
    const Eigen::Vector2d p = sim::reportedSurfacePoint(setup, t);
    appendNumber(out, p.x());
    row(out, {p.y()});
    out += fmt::format(",{}", t.run);
    row(out,
        {radToDeg(t.approach),
         radToDeg(t.spindle),
         radToDeg(t.drm),
         t.position.x(),
         t.position.y(),
         t.position.z()});
    out += '\n';
  }
  return out;
}

std::vector<std::pair<std::string, std::string>> touchProbeFiles(
    const std::string& scenario,
    std::uint64_t seed,
    const sim::TouchProbeSetup& setup,
    const sim::TouchProbeResult& result) {
  Metadata off = metadata(scenario,
                          seed,
                          setup,
                          "probe offset: spindle 0 and 180 deg, DRM compensated",
                          setup.offset_ring_center);
  Metadata without =
      metadata(scenario, seed, setup, "circle without DRM compensation", setup.circle_ring_center);
  Metadata with =
      metadata(scenario, seed, setup, "circle with DRM compensation", setup.circle_ring_center);
  const std::string corrected = fmt::format(
      "x, y = spindle axis + stylus offset ({}, {}) mm + ball radius along the approach",
      formatNumber(setup.stylus_offset.x()),
      formatNumber(setup.stylus_offset.y()));
  without.emplace_back("surface points", corrected);
  with.emplace_back("surface points", corrected);
  return {
      {setup.name + "_offset.csv", probeOffsetCsv(off, result.offset)},
      {setup.name + "_circle_uncompensated.csv",
       probeCircleCsv(without, setup, result.circle_uncompensated)},
      {setup.name + "_circle_compensated.csv",
       probeCircleCsv(with, setup, result.circle_compensated)},
  };
}

}  // namespace pkm::io
