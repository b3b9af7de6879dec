/// @file
/// @brief Tracker registration files (docs/formats.md, "Tracker registration files"): a laser
/// tracker's readings of fiducial nests whose coordinates in the machine's world frame are known
/// (nests on the table), one row per nest, header `nest,x_table,y_table,z_table,x,y,z` (mm): the
/// references from which the tracker's placement world_T_tracker is fitted
/// (calibration::registerMeasurementFrame).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "pkm/io/measurement_files.hpp"
#include "pkm/io/named_text.hpp"
#include "pkm/simulation/laser_tracker.hpp"

namespace pkm::io {

/// The CSV text of a registration: `metadata` as "# key: value" lines, the header
/// `nest,x_table,y_table,z_table,x,y,z` and one row per reading, nests numbered from 1 (world
/// coordinates, then the tracker's reading; shortest round-trip numbers).
[[nodiscard]] std::string registrationCsv(const Metadata& metadata,
                                          const std::vector<simulation::NestReading>& readings);

/// The metadata `pkm simulate` writes for the registration of tracker measurement `setup` of
/// scenario `scenario` with `seed`: format (pkm.tracker-registration/1), scenario, seed,
/// measurement, instrument, frame, noise, nests, columns.
[[nodiscard]] Metadata registrationMetadata(const std::string& scenario,
                                            std::uint64_t seed,
                                            const simulation::TrackerSetup& setup);

/// A registration file as read.
struct RegistrationFile {
  std::string source;                     ///< the file's name, for messages
  Metadata metadata;                      ///< the "# key: value" lines
  std::vector<std::string> nests;         ///< the nest column per row
  std::vector<Eigen::Vector3d> world;     ///< x_table, y_table, z_table: world frame, mm
  std::vector<Eigen::Vector3d> measured;  ///< x, y, z: the tracker's reading, tracker frame, mm
  std::vector<std::size_t> lines;         ///< the 1-based file line of each row
};

/// Parses a registration CSV: '#' metadata lines, the header with the columns `nest`,
/// `x_table`, `y_table`, `z_table`, `x`, `y`, `z` (the suffix `_mm` accepted on each coordinate;
/// other columns ignored), then one row per nest. Throws pkm::IoError "SOURCE:LINE: message" for
/// a missing column, a field that is not a finite number, a nest named twice, fewer than 3 rows,
/// or a metadata `frame` that is not the tracker's.
[[nodiscard]] RegistrationFile parseRegistrationCsv(const NamedText& file);

}  // namespace pkm::io
