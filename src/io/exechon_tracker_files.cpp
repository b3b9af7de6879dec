#include "pkm/io/exechon_tracker_files.hpp"

#include <fmt/format.h>

#include <cmath>

#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/io/calibration_files.hpp"
#include "pkm/io/number_format.hpp"
#include "pkm/io/text_table.hpp"

namespace pkm::io {
namespace {

constexpr double kUnitTolerance = 1e-6;  // |1 − |u|| of a direction in a file

std::string vectorText(const Eigen::Vector3d& v) {
  return fmt::format("({}, {}, {})", formatNumber(v[0]), formatNumber(v[1]), formatNumber(v[2]));
}

}  // namespace

std::string exechonTrackerCsv(const Metadata& metadata,
                              const std::vector<simulation::ExechonTrackerReading>& readings) {
  std::string out;
  for (const auto& [key, value] : metadata) out += fmt::format("# {}: {}\n", key, value);
  out += "q1,q2,q3,c,a,x,y,z\n";
  for (const simulation::ExechonTrackerReading& r : readings)
    out += fmt::format("{},{},{},{},{},{},{},{}\n",
                       formatNumber(r.joints.readings[0]),
                       formatNumber(r.joints.readings[1]),
                       formatNumber(r.joints.readings[2]),
                       formatNumber(radToDeg(r.joints.c)),
                       formatNumber(radToDeg(r.joints.a)),
                       formatNumber(r.measured[0]),
                       formatNumber(r.measured[1]),
                       formatNumber(r.measured[2]));
  return out;
}

Metadata exechonTrackerMetadata(const std::string& scenario,
                                std::uint64_t seed,
                                const simulation::ExechonTrackerSetup& setup,
                                std::size_t poses) {
  const simulation::TrackerNoise& n = setup.noise;
  return {
      {"format", "pkm.exechon-tracker/1"},
      {"scenario", scenario},
      {"seed", std::to_string(seed)},
      {"measurement", setup.name},
      {"instrument",
       "laser tracker with a spherically mounted retroreflector on an Exechon (simulated)"},
      {"frame", "tracker (x, y, z in the tracker's own frame; its placement is not known)"},
      {"target", "SMR centre at the smr offset (tool frame)"},
      {"smr offset mm", vectorText(setup.smr_offset)},
      {"noise",
       fmt::format("range sigma {} mm + {} ppm, angle sigma {} urad",
                   formatNumber(n.range_sigma),
                   formatNumber(n.range_ppm),
                   formatNumber(n.angle_sigma * kUradPerRad))},
      {"poses", std::to_string(poses)},
      {"columns",
       "q1,q2,q3 commanded leg readings A, B, C mm (nominal IK); c,a wrist readings deg; x,y,z mm"},
  };
}

std::string hybridTrackerCsv(const Metadata& metadata,
                             const std::vector<simulation::HybridTrackerReading>& readings) {
  std::string out;
  for (const auto& [key, value] : metadata) out += fmt::format("# {}: {}\n", key, value);
  out += "x2,y2,xp,yp,zp,x,y,z\n";
  for (const simulation::HybridTrackerReading& r : readings)
    out += fmt::format("{},{},{},{},{},{},{},{}\n",
                       formatNumber(r.command.x2),
                       formatNumber(r.command.y2),
                       formatNumber(r.command.pkm[0]),
                       formatNumber(r.command.pkm[1]),
                       formatNumber(r.command.pkm[2]),
                       formatNumber(r.measured[0]),
                       formatNumber(r.measured[1]),
                       formatNumber(r.measured[2]));
  return out;
}

Metadata hybridTrackerMetadata(const std::string& scenario,
                               std::uint64_t seed,
                               const simulation::HybridTrackerSetup& setup,
                               std::size_t poses) {
  const simulation::TrackerNoise& n = setup.noise;
  return {
      {"format", "pkm.hybrid-tracker/1"},
      {"scenario", scenario},
      {"seed", std::to_string(seed)},
      {"measurement", setup.name},
      {"instrument", "laser tracker on the work table, SMR on the tool (simulated)"},
      {"frame", "tracker (x, y, z in the tracker's own frame on the table; placement not known)"},
      {"target", "SMR centre at the smr offset (tool frame)"},
      {"smr offset mm", vectorText(setup.smr_offset)},
      {"noise",
       fmt::format("range sigma {} mm + {} ppm, angle sigma {} urad",
                   formatNumber(n.range_sigma),
                   formatNumber(n.range_ppm),
                   formatNumber(n.angle_sigma * kUradPerRad))},
      {"poses", std::to_string(poses)},
      {"columns", "x2,y2 serial axes mm; xp,yp,zp PKM command mm (P frame); x,y,z mm"},
  };
}

namespace {

void addHybridFile(const TextTable& t, const std::string& path, ExechonCalibrationInput& input) {
  const std::size_t x2 = t.column({"x2"}), y2 = t.column({"y2"});
  const std::size_t xp = t.column({"xp"}), yp = t.column({"yp"}), zp = t.column({"zp"});
  const std::size_t x = t.column({"x"}), y = t.column({"y"}), z = t.column({"z"});
  if (const auto offset = t.meta("smr offset mm")) {
    const std::vector<Eigen::Vector3d> v = parseVectorList(*offset, path, "smr offset mm");
    if (v.size() != 1) t.failHeader("metadata 'smr offset mm' is not one vector");
    input.hybrid.target_offset = v[0];
    input.hybrid_target_offset = v[0];
  }
  const bool tracker = t.meta("frame").value_or("").rfind("tracker", 0) == 0;
  if (!t.meta("frame")) input.frameless.push_back(path);
  if (!input.hybrid.observations.empty() && tracker != input.hybrid.measurement_frame.has_value())
    t.failHeader("its 'frame' differs from an earlier hybrid file's");
  if (tracker && !input.hybrid.measurement_frame)  // a start is fitted later
    input.hybrid.measurement_frame = geometry::RigidTransform::Identity();
  for (std::size_t r = 0; r < t.rows(); ++r) {
    calibration::HybridObservation o;
    o.command.x2 = t.number(r, x2);
    o.command.y2 = t.number(r, y2);
    o.command.pkm = Eigen::Vector3d(t.number(r, xp), t.number(r, yp), t.number(r, zp));
    o.point = Eigen::Vector3d(t.number(r, x), t.number(r, y), t.number(r, z));
    o.source = fmt::format("{}:{}", path, t.line(r));
    input.hybrid.observations.push_back(std::move(o));
  }
  input.notes.push_back(fmt::format("{}: {} hybrid tracker observations", path, t.rows()));
}

}  // namespace

void addExechonCalibrationFile(const std::string& path, ExechonCalibrationInput& input) {
  addExechonCalibrationFile(readNamedText(path), input);
}

void addExechonCalibrationFile(const NamedText& file, ExechonCalibrationInput& input) {
  const std::string& path = file.name;
  const TextTable t = TextTable::parseData(file.text, path);
  if (t.findColumn({"x2"})) {
    addHybridFile(t, path, input);
    return;
  }
  // Legs A, B, C are q1,q2,q3 as in `pkm exechon ik/fk`; files written before that used q0,q1,q2.
  const bool from_zero = t.findColumn({"q0"}).has_value();
  const std::size_t q0 = t.column({from_zero ? "q0" : "q1"}),
                    q1 = t.column({from_zero ? "q1" : "q2"}),
                    q2 = t.column({from_zero ? "q2" : "q3"});
  const std::size_t cc = t.column({"c", "c_deg"}), ca = t.column({"a", "a_deg"});
  const std::size_t x = t.column({"x"}), y = t.column({"y"}), z = t.column({"z"});
  const auto i = t.findColumn({"i"}), j = t.findColumn({"j"}), k = t.findColumn({"k"});
  const bool has_direction = i && j && k;
  if ((i || j || k) && !has_direction) t.failHeader("a tool direction needs all of i, j, k");
  if (const auto offset = t.meta("smr offset mm")) {
    const std::vector<Eigen::Vector3d> v = parseVectorList(*offset, path, "smr offset mm");
    if (v.size() != 1) t.failHeader("metadata 'smr offset mm' is not one vector");
    if (input.target_offset && (*input.target_offset - v[0]).norm() > 0.0)
      t.failHeader("its 'smr offset mm' differs from an earlier file's");
    input.target_offset = v[0];
  }
  if (const auto frame = t.meta("frame")) {
    const bool tracker = frame->rfind("tracker", 0) == 0;
    if (!input.data.observations.empty() && tracker != input.tracker_frame)
      t.failHeader("its 'frame' differs from an earlier file's");
    input.tracker_frame = tracker;
  } else {
    input.frameless.push_back(path);
  }
  for (std::size_t r = 0; r < t.rows(); ++r) {
    calibration::ExechonObservation o;
    o.joints.readings = Eigen::Vector3d(t.number(r, q0), t.number(r, q1), t.number(r, q2));
    o.joints.c = degToRad(t.number(r, cc));
    o.joints.a = degToRad(t.number(r, ca));
    o.point = Eigen::Vector3d(t.number(r, x), t.number(r, y), t.number(r, z));
    o.source = fmt::format("{}:{}", path, t.line(r));
    if (has_direction) {
      const Eigen::Vector3d u(t.number(r, *i), t.number(r, *j), t.number(r, *k));
      if (std::fabs(u.norm() - 1.0) > kUnitTolerance)
        throw IoError(
            fmt::format("{}: the tool direction (i, j, k) is not a unit vector (|u| = {})",
                        o.source,
                        u.norm()));
      o.direction = u;
    }
    input.data.observations.push_back(std::move(o));
  }
  input.notes.push_back(fmt::format("{}: {} Exechon tracker observations{}",
                                    path,
                                    t.rows(),
                                    has_direction ? " with tool directions" : ""));
}

}  // namespace pkm::io
