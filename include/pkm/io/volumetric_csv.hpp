/// @file
/// @brief The rows of `pkm volumetric` (docs/formats.md, "pkm volumetric"): the volumetric error
/// of a hybrid machine at one command, exact and first-order (MXT700S parallelism paper, eq. 3),
/// and its CSV form.
#pragma once

#include <Eigen/Core>
#include <string>

#include "pkm/kinematics/hybrid_model.hpp"

namespace pkm::io {

/// The volumetric error at one command of a hybrid machine.
struct VolumetricRow {
  Eigen::Vector3d tool = Eigen::Vector3d::Zero();  ///< nominal tool position, work frame
  kinematics::HybridCommand command;               ///< x2, y2 and the PKM command
  /// kOk or kAxisLimit: dp and dp_linear hold the error; kOutsideTable: an error table with
  /// "out_of_range": "error" does not cover the command, and there is no error.
  enum class Status { kOk, kAxisLimit, kOutsideTable } status = Status::kOk;
  Eigen::Vector3d dp = Eigen::Vector3d::Zero();         ///< exact Δp, machine unit
  Eigen::Vector3d dp_linear = Eigen::Vector3d::Zero();  ///< first-order Δp, machine unit
};

/// The CSV header, with its newline: x,y,z,x2,y2,xp,yp,zp,dx,dy,dz,dp,dx_lin,dy_lin,dz_lin,status.
[[nodiscard]] std::string volumetricCsvHeader();

/// Appends `row` as one CSV line (numbers in round-trip form; the error fields empty outside the
/// tables; status ok, axis_limit or outside_table).
void appendVolumetricCsvRow(std::string& out, const VolumetricRow& row);

}  // namespace pkm::io
