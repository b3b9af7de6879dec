// The report of `pkm calibrate hexapod --live` (pkm/live/live_calibration.hpp).
#include <fmt/format.h>

#include <cmath>

#include "pkm/core/units.hpp"
#include "pkm/live/live_calibration.hpp"
#include "pkm/workflow/calibration_text.hpp"

namespace pkm::live {
namespace {

void stationLines(std::string& out,
                  const char* title,
                  const std::vector<simulation::DialGaugeStation>& stations) {
  out += fmt::format("{}\n  {:>3} {:>9} {:>9} {:>8} {:>9} {:>9} {:>9} {:>5}\n",
                     title,
                     "#",
                     "x mm",
                     "y mm",
                     "c deg",
                     "g0 mm",
                     "g1 mm",
                     "g2 mm",
                     "reads");
  for (const simulation::DialGaugeStation& s : stations)
    out += fmt::format("  {:>3} {:>9.3f} {:>9.3f} {:>8.3f} {:>9.4f} {:>9.4f} {:>9.4f} {:>5}{}\n",
                       s.station,
                       s.command[0],
                       s.command[1],
                       radToDeg(s.command[5]),
                       s.readings[0],
                       s.readings[1],
                       s.readings[2],
                       s.iterations,
                       s.converged ? "" : "  not converged");
}

}  // namespace

std::string liveCalibrationText(const LiveCalibrationRequest& request,
                                const LiveCalibrationResult& r) {
  std::string out = fmt::format(
      "Calibration by constrained motion on the running LinuxCNC ({})\n"
      "Stations: {} to fit and {} held out, planned among {} reachable planar moves of {} tried "
      "(index {:.3g}; random choices {:.3g}); the gauges see {} of the 42 parameter directions.\n"
      "Every move approaches from {} mm below its command.\n\n",
      request.ini,
      r.plan.fit.size(),
      r.plan.holdout.size(),
      r.plan.candidates,
      r.plan.tried,
      r.plan.index_value,
      r.plan.random_baseline,
      r.plan.identifiable,
      request.approach);
  stationLines(out, "Stations (0: the reference, where the gauges were zeroed)", r.stations);
  stationLines(out, "Held-out stations", r.held_out);
  out += fmt::format("Files: {}, {}\n\n", r.data_file, r.holdout_file);
  out += workflow::hexapodCalibrationText(r.fit, r.calibration);
  out += fmt::format(
      "\nHeld-out check: gauge residuals RMS {:.4f} mm with the configuration's machine, "
      "{:.4f} mm calibrated ({} stations kept out of the fit)\n",
      r.holdout_rms_before,
      r.holdout_rms_after,
      r.held_out.empty() ? 0 : r.held_out.size() - 1);
  if (r.laser_error_before)
    out += fmt::format("Laser along x over {} mm: error {:+.4f} mm before calibration\n",
                       request.laser_length,
                       *r.laser_error_before);
  if (r.install) {
    out += fmt::format("Installed into {} ({}): {}\n",
                       request.ini,
                       r.install->kinematics,
                       r.install->written
                           ? "backups " + fmt::format("{}", fmt::join(r.install->backups, ", "))
                           : std::string("nothing to change"));
    out += r.applied ? "Applied to the running LinuxCNC (machine off, pkmhexkins pins set, "
                       "machine on; the struts did not move).\n"
                     : "Restart LinuxCNC to load the installed genhexkins values.\n";
  } else {
    out += fmt::format(
        "Not installed. To install: pkm linuxcnc install --calibration {} --ini {} "
        "--force\n",
        r.fit.out,
        request.ini);
  }
  if (r.laser_error_after)
    out += fmt::format("Laser along x over {} mm: error {:+.4f} mm after calibration\n",
                       request.laser_length,
                       *r.laser_error_after);
  out += fmt::format(
      "{} commands sent to LinuxCNC (commands.log); {:.1f} s\n", r.log.size(), r.seconds);
  return out;
}

}  // namespace pkm::live
