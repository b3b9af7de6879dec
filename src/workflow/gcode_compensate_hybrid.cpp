// `pkm gcode compensate --hybrid-frame F --x2 POS`: the hybrid machine's X2–Y2 squareness
// corrected in a PKM program (workflow/gcode_compensate.hpp; MXT700S parallelism paper,
// docs/campaign.md).
#include <fmt/format.h>

#include <Eigen/Core>
#include <map>
#include <sstream>

#include "gcode_compensate_detail.hpp"
#include "pkm/compensation/hybrid_squareness.hpp"
#include "pkm/core/error.hpp"
#include "pkm/geometry/so3.hpp"
#include "pkm/io/atomic_file.hpp"
#include "pkm/io/hexapod_machine.hpp"

namespace pkm::workflow::detail {

namespace {

/// The `key = a b c` values of a pkm-base-frame.txt (docs/campaign.md); `#` lines are comments.
std::map<std::string, Eigen::Vector3d> readFrameValues(const std::string& path) {
  const std::string text = io::readTextFile(path);
  std::map<std::string, Eigen::Vector3d> values;
  std::size_t line_no = 0, start = 0;
  while (start < text.size()) {
    std::size_t nl = text.find('\n', start);
    if (nl == std::string::npos) nl = text.size();
    const std::string line = text.substr(start, nl - start);
    start = nl + 1;
    ++line_no;
    if (line.empty() || line[0] == '#') continue;
    const std::size_t eq = line.find('=');
    std::istringstream in(eq == std::string::npos ? std::string() : line.substr(eq + 1));
    Eigen::Vector3d v;
    std::string rest;
    if (eq == std::string::npos || !(in >> v.x() >> v.y() >> v.z()) || (in >> rest) ||
        !v.allFinite())
      throw IoError(fmt::format("{}:{}: expected 'key = a b c'", path, line_no));
    std::string key = line.substr(0, eq);
    key.erase(key.find_last_not_of(' ') + 1);
    values[key] = v;
  }
  return values;
}

/// The base frame and X2 term of a pkm-base-frame.txt. Throws pkm::IoError naming the file (and
/// line) for an unreadable file, a malformed line or a missing key.
compensation::HybridSquarenessCompensation readBaseFrame(const std::string& path) {
  std::map<std::string, Eigen::Vector3d> values = readFrameValues(path);
  compensation::HybridSquarenessCompensation c;
  for (const char* key : {"base_rpy_rad", "base_offset_mm", "per_x2"})
    if (!values.count(key)) throw IoError(fmt::format("{}: '{}' is missing", path, key));
  c.base_rpy = values["base_rpy_rad"];
  c.base_rotation = geometry::rotationFromRpy(c.base_rpy);
  c.base_offset = values["base_offset_mm"];
  c.per_x2 = values["per_x2"];
  return c;
}

}  // namespace

std::string flattenedNote(const cnc::ProgramCompensation& r) {
  if (r.flattened_blocks == 0) return "";
  return fmt::format(
      "; the program has O-words: its {} executed blocks were flattened first (pkm gcode "
      "flatten)",
      r.flattened_blocks);
}

void writeCompensated(const GcodeCompensateRequest& request, const GcodeCompensateResult& result) {
  if (!request.out.empty())
    io::writeFileAtomic(request.out, result.compensation.text, io::Overwrite::kAllow);
}

GcodeCompensateResult compensateHybridGcode(const GcodeCompensateRequest& request) {
  const compensation::HybridSquarenessCompensation c = readBaseFrame(request.hybrid_frame);
  cnc::InterpolationOptions options;
  options.tolerance = request.tolerance.value_or(kDefaultToleranceMm);
  const double x2 = *request.x2;
  const bool in_controller = !request.frame_not_in_controller;
  GcodeCompensateResult result;
  result.compensation = cnc::compensateHybridProgram(request.program.text,
                                                     request.program.name,
                                                     c,
                                                     x2,
                                                     in_controller,
                                                     options,
                                                     request.interpreter.options());
  writeCompensated(request, result);
  const cnc::ProgramCompensation& r = result.compensation;
  result.note = fmt::format(
      "hybrid squareness correction at X2 = {} mm ({}): {} motion lines rewritten, {} lines "
      "added (segments, dwells), {} G92/G10 L20 lines shifted, largest correction {:.4g} mm{}",
      x2,
      in_controller ? "X2 term; base frame in the controller" : "base frame and X2 term",
      r.motion_lines,
      r.added_lines,
      r.offset_lines,
      r.max_correction,
      flattenedNote(r));
  return result;
}

}  // namespace pkm::workflow::detail
