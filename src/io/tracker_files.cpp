#include "pkm/io/tracker_files.hpp"

#include <fmt/format.h>

#include <array>
#include <fstream>
#include <sstream>
#include <string_view>

#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/geometry/so3.hpp"
#include "pkm/io/csv.hpp"
#include "pkm/io/number_format.hpp"
#include "pkm/kinematics/pose_rpy.hpp"

namespace pkm::io {

namespace sim = pkm::simulation;

namespace {

constexpr std::size_t kColumns = 12;  // l0..l5, x, y, z, a, b, c
const std::array<const char*, kColumns> kNames = {
    "l0", "l1", "l2", "l3", "l4", "l5", "x", "y", "z", "a", "b", "c"};

/// The column index 0..11 that header field `f` names (with an optional unit suffix), or -1.
int columnOf(std::string_view f) {
  for (std::size_t c = 0; c < kColumns; ++c) {
    const std::string_view name = kNames[c];
    const std::string_view suffix = c < 9 ? "_mm" : "_deg";
    if (f == name ||
        (f.size() == name.size() + suffix.size() && f.starts_with(name) && f.ends_with(suffix)))
      return static_cast<int>(c);
  }
  return -1;
}

std::string vectorText(const Eigen::Vector3d& v) {
  return fmt::format("({}, {}, {})", formatNumber(v[0]), formatNumber(v[1]), formatNumber(v[2]));
}

}  // namespace

std::string trackerCsv(const Metadata& metadata,
                       sim::TrackerMode mode,
                       const std::vector<sim::TrackerReading>& readings) {
  std::string out;
  for (const auto& [key, value] : metadata) out += fmt::format("# {}: {}\n", key, value);
  const bool pose = mode == sim::TrackerMode::kPose;
  out += pose ? "l0,l1,l2,l3,l4,l5,x,y,z,a,b,c\n" : "l0,l1,l2,l3,l4,l5,x,y,z\n";
  for (const sim::TrackerReading& r : readings) {
    for (Eigen::Index i = 0; i < r.lengths.size(); ++i) {
      appendNumber(out, r.lengths[i]);
      out += ',';
    }
    const kinematics::PoseRpy p = kinematics::poseRpyFromTransform(r.measured);
    for (Eigen::Index k = 0; k < 3; ++k) {
      if (k > 0) out += ',';
      appendNumber(out, p.position[k]);
    }
    if (pose) {
      for (Eigen::Index k = 0; k < 3; ++k) {
        out += ',';
        appendNumber(out, radToDeg(p.rpy[k]));
      }
    }
    out += '\n';
  }
  return out;
}

Metadata trackerMetadata(const std::string& scenario,
                         std::uint64_t seed,
                         const sim::TrackerSetup& setup,
                         std::size_t poses) {
  const bool pose = setup.mode == sim::TrackerMode::kPose;
  const sim::TrackerNoise& n = setup.noise;
  return {
      {"format", pose ? "pkm.tracker-pose/1" : "pkm.tracker-point/1"},
      {"scenario", scenario},
      {"seed", std::to_string(seed)},
      {"measurement", setup.name},
      {"instrument",
       pose ? "laser tracker with a 6-DOF probe (simulated)"
            : "laser tracker with a spherically mounted retroreflector (simulated)"},
      {"mode", sim::toString(setup.mode)},
      {"frame",
       setup.placed()
           ? "tracker (x, y, z, a, b, c in the tracker's own frame; its placement is not known)"
           : "world (x, y, z, a, b, c in the machine's world frame: the tracker was aligned to "
             "it)"},
      {"target",
       pose ? "6-DOF probe at the smr offset, axes parallel to the tool frame"
            : "SMR centre at the smr offset"},
      {"smr offset mm", vectorText(setup.smr_offset)},
      {"noise",
       fmt::format("range sigma {} mm + {} ppm, angle sigma {} urad, orientation sigma {} urad",
                   formatNumber(n.range_sigma),
                   formatNumber(n.range_ppm),
                   formatNumber(n.angle_sigma * kUradPerRad),
                   formatNumber(n.orientation_sigma * kUradPerRad))},
      {"poses", std::to_string(poses)},
      {"columns",
       pose ? "l0..l5 commanded strut readings mm (nominal IK, encoder counts); x,y,z mm; a,b,c deg"
            : "l0..l5 commanded strut readings mm (nominal IK, encoder counts); x,y,z mm"},
  };
}

TrackerFile parseTrackerCsv(const std::string& text, const std::string& source) {
  TrackerFile file;
  std::array<int, kColumns> column{};
  column.fill(-1);
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
        const int c = columnOf(fields[i]);
        if (c < 0) continue;
        if (column[static_cast<std::size_t>(c)] >= 0)
          fail(fmt::format("column '{}' appears twice", kNames[static_cast<std::size_t>(c)]));
        column[static_cast<std::size_t>(c)] = static_cast<int>(i);
      }
      for (std::size_t c = 0; c < 9; ++c)
        if (column[c] < 0)
          fail(fmt::format("missing column '{}' (a tracker file needs l0..l5 and x, y, z)",
                           kNames[c]));
      const int angles = (column[9] >= 0) + (column[10] >= 0) + (column[11] >= 0);
      if (angles != 0 && angles != 3) fail("a pose file needs all of the columns a, b, c");
      file.mode = angles == 3 ? sim::TrackerMode::kPose : sim::TrackerMode::kPoint;
      fields_expected = fields.size();
      header = true;
      continue;
    }
    if (fields.size() != fields_expected)
      fail(fmt::format("expected {} fields, found {}", fields_expected, fields.size()));
    std::array<double, kColumns> v{};
    const std::size_t used = file.mode == sim::TrackerMode::kPose ? kColumns : 9;
    for (std::size_t c = 0; c < used; ++c) {
      const std::string_view f = fields[static_cast<std::size_t>(column[c])];
      if (!parseFiniteDouble(f, v[c]))
        fail(fmt::format("{} '{}' is not a finite number", kNames[c], f));
    }
    kinematics::StrutVector l;
    for (Eigen::Index i = 0; i < 6; ++i) l[i] = v[static_cast<std::size_t>(i)];
    file.lengths.push_back(l);
    file.positions.emplace_back(v[6], v[7], v[8]);
    if (file.mode == sim::TrackerMode::kPose)
      file.rpy.emplace_back(degToRad(v[9]), degToRad(v[10]), degToRad(v[11]));
    file.lines.push_back(line_no);
  }
  if (!header) throw IoError(locate(source, line_no, "no header row"));
  if (file.lengths.empty()) throw IoError(locate(source, line_no, "no data rows"));
  return file;
}

TrackerFile readTrackerCsv(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(locate(path, 0, "cannot open the file"));
  std::ostringstream text;
  text << in.rdbuf();
  return parseTrackerCsv(text.str(), path);
}

}  // namespace pkm::io
