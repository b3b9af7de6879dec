/// @file
/// @brief What the `pkm calibrate` kinds share (calibrate_command.cpp, calibrate_exechon.cpp).
#pragma once

#include <CLI/CLI.hpp>
#include <Eigen/Core>
#include <string>
#include <vector>

#include "analyze_common.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/named_text.hpp"

namespace pkm::cli {

/// Adds `pkm calibrate exechon` to the `calibrate` command (calibrate_exechon.cpp).
void addCalibrateExechon(CLI::App& calibrate);

/// The arguments of a `pkm calibrate` kind: its workflow request (HexapodCalibrationRequest or
/// ExechonCalibrationRequest) and what the command line gives as paths or lists first.
template <typename Request>
struct CalibrateArgs {
  Request request;
  std::vector<std::string> data, holdout;  ///< --data, --holdout paths (read into the request)
  std::vector<double> target_offset;       ///< --target-offset x,y,z
  bool json = false;                       ///< --json: print the summary document
  UncertaintyArgs uncertainty;             ///< --uncertainty FILE
};

/// Puts into `args.request` what both kinds read the same way: the target offset, the
/// uncertainty sources and the data and hold-out files. Throws pkm::InvalidArgument for a target
/// offset that is not x,y,z, pkm::IoError for an unreadable file.
template <typename Request>
void fillCalibrateRequest(CalibrateArgs<Request>& args) {
  if (!args.target_offset.empty()) {
    if (args.target_offset.size() != 3) throw InvalidArgument("--target-offset needs x,y,z");
    args.request.target_offset =
        Eigen::Vector3d(args.target_offset[0], args.target_offset[1], args.target_offset[2]);
  }
  args.request.uncertainty = args.uncertainty.parsed();
  args.request.uncertainty_name = args.uncertainty.file;
  args.request.data = io::readNamedTexts(args.data);
  args.request.holdout = io::readNamedTexts(args.holdout);
}

}  // namespace pkm::cli
