// The tracker-frame registration of the calibration workflows (frame_registration.hpp).
#include "frame_registration.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "pkm/calibration/acceptance.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/registration_files.hpp"

namespace pkm::workflow::detail {

std::string worldFrameKind(bool tracker_frame, bool registered) {
  if (registered) return "registered";
  return tracker_frame ? "unregistered" : "machine";
}

calibration::FrameRegistration registerTrackerFrame(const io::NamedText& file,
                                                    LengthUnit unit,
                                                    double characteristic_length,
                                                    const metrology::UncertaintySources& sources) {
  const io::RegistrationFile f = io::parseRegistrationCsv(file);
  const double mm = millimetresPer(unit);
  double stated = 0.0;  // the tracker's ±(a + b·L) as a standard uncertainty, at the longest range
  for (const Eigen::Vector3d& m : f.measured) {
    const double range_mm = m.norm() * mm;
    const metrology::LaserTrackerSpec& t = sources.tracker;
    stated = std::max(stated, (t.accuracy_mm + t.accuracy_mm_per_m * range_mm * 1e-3) / mm);
  }
  stated /= std::sqrt(3.0);
  calibration::FrameRegistration reg;
  try {
    reg = calibration::registerMeasurementFrame(f.world, f.measured, stated);
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(fmt::format("{}: {}", file.name, e.what()));
  }
  if (!calibration::explainsData(reg.max, characteristic_length)) {
    const auto worst = static_cast<std::size_t>(
        std::max_element(reg.residuals.begin(), reg.residuals.end()) - reg.residuals.begin());
    throw InvalidArgument(fmt::format(
        "{}:{}: nest '{}' is {:.4g} {} from where the rigid fit of the {} nests puts it (RMS "
        "{:.4g}): the nests' table coordinates and the tracker's readings do not describe one "
        "rigid placement; check that nest's coordinates and reading, the nests' order and the "
        "unit ({}); nothing was written",
        file.name,
        f.lines[worst],
        f.nests[worst],
        reg.residuals[worst],
        toString(unit),
        reg.references,
        reg.rms,
        toString(unit)));
  }
  return reg;
}

void refuseRegistrationOfWorldData(const std::optional<io::NamedText>& registration,
                                   bool tracker_frame) {
  if (registration && !tracker_frame)
    throw InvalidArgument(fmt::format(
        "--registration {}: the readings are in the machine's world frame (--frame world or the "
        "files' '# frame: world'); a registration places readings taken in the tracker's own "
        "frame (--frame tracker)",
        registration->name));
}

}  // namespace pkm::workflow::detail
