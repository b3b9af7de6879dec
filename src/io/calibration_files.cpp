#include "pkm/io/calibration_files.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <optional>

#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/io/csv.hpp"
#include "pkm/io/tracker_files.hpp"

namespace pkm::io {

std::vector<Eigen::Vector3d> parseVectorList(const std::string& text,
                                             const std::string& source,
                                             const std::string& key) {
  std::vector<Eigen::Vector3d> out;
  std::size_t pos = 0;
  const auto fail = [&](const std::string& what) {
    throw IoError(locate(source, 0, fmt::format("metadata '{}': {}", key, what)));
  };
  while (true) {
    const std::size_t open = text.find('(', pos);
    if (open == std::string::npos) break;
    const std::size_t close = text.find(')', open);
    if (close == std::string::npos) fail("unbalanced parentheses");
    const std::string group = text.substr(open + 1, close - open - 1);
    Eigen::Vector3d v;
    std::size_t start = 0;
    for (int k = 0; k < 3; ++k) {
      const std::size_t comma = group.find(',', start);
      if ((k < 2) != (comma != std::string::npos))
        fail(fmt::format("'({})' is not (x, y, z)", group));
      if (!parseFiniteDouble(group.substr(start, comma - start), v(k)))
        fail(fmt::format("'({})' is not three finite numbers", group));
      start = comma + 1;
    }
    out.push_back(v);
    pos = close + 1;
  }
  return out;
}

calibration::ConstrainedMotionData readConstrainedMotionCsv(const NamedText& input, int* skipped) {
  const std::string& path = input.name;
  const TextTable t = TextTable::parseData(input.text, path);
  calibration::ConstrainedMotionData set;
  const auto points = t.meta("gauge points mm");
  if (!points)
    t.failHeader("missing metadata '# gauge points mm: (x, y, z), (x, y, z), (x, y, z)'");
  const auto tips = parseVectorList(*points, path, "gauge points mm");
  if (tips.size() != 3)
    t.failHeader(fmt::format("metadata 'gauge points mm' has {} vectors, not 3", tips.size()));
  for (std::size_t j = 0; j < 3; ++j) set.gauge_points[j] = tips[j];
  if (const auto normal = t.meta("table normal")) {
    const auto n = parseVectorList(*normal, path, "table normal");
    if (n.size() != 1 || !(n[0].norm() > 0.0))
      t.failHeader("metadata 'table normal' is not one non-zero vector");
    set.table_normal = n[0].normalized();
  }
  const std::size_t station = t.column({"station"});
  const std::size_t pose_col[6] = {t.column({"x_mm", "x"}),
                                   t.column({"y_mm", "y"}),
                                   t.column({"z_mm", "z"}),
                                   t.column({"a_deg", "a"}),
                                   t.column({"b_deg", "b"}),
                                   t.column({"c_deg", "c"})};
  std::size_t strut_col[6];
  for (int i = 0; i < 6; ++i) {
    const std::string mm = fmt::format("l{}_mm", i), plain = fmt::format("l{}", i);
    strut_col[i] = t.column({mm, plain});
  }
  const std::size_t gauge_col[3] = {
      t.column({"g0_mm", "g0"}), t.column({"g1_mm", "g1"}), t.column({"g2_mm", "g2"})};
  const auto converged_col = t.findColumn({"converged"});
  bool have_reference = false;
  int left_out = 0;
  for (std::size_t r = 0; r < t.rows(); ++r) {
    calibration::GaugeStation s;
    for (int i = 0; i < 3; ++i) s.command.position(i) = t.number(r, pose_col[i]);
    for (int i = 0; i < 3; ++i) s.command.rpy(i) = degToRad(t.number(r, pose_col[3 + i]));
    for (int i = 0; i < 6; ++i) s.readings(i) = t.number(r, strut_col[i]);
    for (int j = 0; j < 3; ++j) s.gauges[static_cast<std::size_t>(j)] = t.number(r, gauge_col[j]);
    const long long id = t.integer(r, station);
    if (id < 0) t.fail(r, "station must be >= 0");
    if (id == 0) {
      if (have_reference) t.fail(r, "a second station 0 (the reference)");
      set.reference = s;
      have_reference = true;
      continue;
    }
    if (converged_col && t.integer(r, *converged_col) == 0) {
      ++left_out;
      continue;
    }
    set.stations.push_back(s);
  }
  if (!have_reference)
    throw IoError(locate(path, 0, "no station 0 (the reference where the gauges were zeroed)"));
  if (skipped != nullptr) *skipped = left_out;
  return set;
}

calibration::ConstrainedMotionData readConstrainedMotionCsv(const std::string& path, int* skipped) {
  return readConstrainedMotionCsv(readNamedText(path), skipped);
}

namespace {

/// A distance file: ball-bar lengths to the `# pivot mm` metadata's pivot, else distances from the
/// first row's TCP (whose distance must be 0).
void addDistanceFile(const std::string& path, const TextTable& probe, CalibrationInput& input) {
  const std::size_t d = probe.column({"distance", "distance_mm"});
  std::array<std::size_t, 6> l{};
  for (std::size_t i = 0; i < 6; ++i) {
    const std::string name = fmt::format("l{}", i);
    l[i] = probe.column({name});
  }
  std::optional<Eigen::Vector3d> pivot;
  if (const auto text = probe.meta("pivot mm")) {
    const auto v = parseVectorList(*text, path, "pivot mm");
    if (v.size() != 1) probe.failHeader("metadata 'pivot mm' is not one vector");
    pivot = v[0];
  }
  if (!pivot && probe.rows() < 2)
    probe.failHeader("a line of distances needs a first row (the zero) and at least one more");
  kinematics::StrutVector first = kinematics::StrutVector::Zero();
  for (std::size_t r = 0; r < probe.rows(); ++r) {
    calibration::DistanceObservation o;
    for (std::size_t i = 0; i < 6; ++i)
      o.readings(static_cast<Eigen::Index>(i)) = probe.number(r, l[i]);
    o.distance = probe.number(r, d);
    if (pivot) {
      o.from_point = *pivot;
      if (!(o.distance > 0.0))
        throw IoError(locate(path, probe.line(r), "a ball-bar length must be > 0"));
    } else if (r == 0) {
      first = o.readings;
      if (o.distance != 0.0)
        throw IoError(
            locate(path, probe.line(r), "the first row of a line is its zero: distance 0"));
      continue;  // the reference end of every other row
    } else {
      o.readings_from = first;
      if (o.distance < 0.0) throw IoError(locate(path, probe.line(r), "a distance must be >= 0"));
    }
    input.data.distances.push_back(o);
    input.distance_origin.push_back(fmt::format("{}:{}", path, probe.line(r)));
  }
  input.notes.push_back(fmt::format("{}: {} distances ({})",
                                    path,
                                    pivot ? probe.rows() : probe.rows() - 1,
                                    pivot ? "ball bar on a pivot" : "from the first row"));
}

/// A constrained-motion (dial-gauge) file.
void addConstrainedFile(const NamedText& file, CalibrationInput& input) {
  const std::string& path = file.name;
  int skipped = 0;
  input.data.constrained.push_back(readConstrainedMotionCsv(file, &skipped));
  input.notes.push_back(
      fmt::format("{}: constrained motion, {} stations{}",
                  path,
                  input.data.constrained.back().stations.size(),
                  skipped > 0 ? fmt::format(" ({} not converged, left out)", skipped) : ""));
}

/// A tracker pose or point file, with its `smr offset mm` and `frame` metadata.
void addTrackerFile(const NamedText& file, CalibrationInput& input) {
  const std::string& path = file.name;
  const TrackerFile f = parseTrackerCsv(file.text, path);
  bool frame_stated = false;
  for (const auto& [key, value] : f.metadata) {
    if (key == "smr offset mm" && !input.target_offset) {
      const auto v = parseVectorList(value, path, key);
      if (v.size() != 1)
        throw IoError(locate(path, 0, "metadata 'smr offset mm' is not one vector"));
      input.target_offset = v[0];
    }
    if (key == "frame") frame_stated = true;
    if (key == "frame" && value.rfind("tracker", 0) == 0) input.tracker_frame = true;
  }
  if (!frame_stated) input.frameless.push_back(path);
  // Each file is one sequence of moves: the approach directions follow from its row order (the
  // first row's is unknown).
  const std::vector<kinematics::StrutVector> approach =
      calibration::approachFromSequence(f.lengths);
  for (std::size_t k = 0; k < f.lengths.size(); ++k) {
    if (f.mode == simulation::TrackerMode::kPose) {
      calibration::PoseObservation o;
      o.readings = f.lengths[k];
      o.pose.position = f.positions[k];
      o.pose.rpy = f.rpy[k];
      o.approach = approach[k];
      input.data.poses.push_back(o);
      input.pose_origin.push_back(fmt::format("{}:{}", path, f.lines[k]));
    } else {
      input.data.points.push_back({f.lengths[k], f.positions[k], approach[k]});
      input.point_origin.push_back(fmt::format("{}:{}", path, f.lines[k]));
    }
  }
  input.notes.push_back(fmt::format("{}: {} {}",
                                    path,
                                    f.lengths.size(),
                                    f.mode == simulation::TrackerMode::kPose ? "poses" : "points"));
}

}  // namespace

void addCalibrationFile(const NamedText& file, CalibrationInput& input) {
  const TextTable probe = TextTable::parseData(file.text, file.name);
  if (probe.findColumn({"distance", "distance_mm"}))
    addDistanceFile(file.name, probe, input);
  else if (probe.findColumn({"g0_mm", "g0"}))
    addConstrainedFile(file, input);
  else
    addTrackerFile(file, input);
}

void addCalibrationFile(const std::string& path, CalibrationInput& input) {
  addCalibrationFile(readNamedText(path), input);
}

}  // namespace pkm::io
