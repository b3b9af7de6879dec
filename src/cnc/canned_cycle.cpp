// Canned cycles in the XY plane with the motions of Debian's LinuxCNC 2.9 snapshot, established
// against rs274 block by block (docs/gcode.md, "Canned cycles"):
// - the initial level IL is the Z before the first cycle block of a sequence (a non-cycle motion
//   mode ends the sequence; rs274ngc cycle_il);
// - R plane = R (G90) or IL + R (G91); bottom = Z (G90) or R plane + Z (G91);
// - if IL is below the R plane, first a rapid straight up to R at the current XY;
// - clear level = R plane (G99) or the higher of IL and R (G98);
// - per repeat: a rapid to X, Y at the higher of the current Z and the clear level (it may rise
//   diagonally), a rapid down to R when not there, the cycle body, which ends at the clear level.
// Bodies: G81 feed, rapid out; G82 feed, dwell, rapid out; G85 feed in, feed out to R, rapid to
// clear; G89 feed in, dwell, feed out to the clear level; G83 pecks with rapids to R and back to
// 0.254 mm above the last depth; G73 pecks with a 0.254 mm rapid retract.
#include "pkm/cnc/canned_cycle.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "pkm/cnc/gcode_error.hpp"

namespace pkm::cnc {

namespace {
void push(std::vector<CycleStep>& out, CycleStep::Kind k, double x, double y, double z) {
  CycleStep s;
  s.kind = k;
  s.to = {x, y, z};
  out.push_back(s);
}
}  // namespace

std::array<double, 3> expandCycle(const CycleRequest& q, std::vector<CycleStep>& out) {
  using K = CycleStep::Kind;
  double old_z = q.initial_level;
  double r = q.r;
  double bottom = q.z;
  double x = q.current[0];
  double y = q.current[1];
  double dx = 0.0;
  double dy = 0.0;
  if (q.incremental) {
    r = q.r + old_z;
    bottom = r + q.z;
    dx = q.has_x ? q.x : 0.0;
    dy = q.has_y ? q.y : 0.0;
  } else {
    if (q.has_x) x = q.x;
    if (q.has_y) y = q.y;
  }
  if (r < bottom) throw GcodeError("R plane below the bottom Z of the canned cycle");
  if (q.repeats < 1) throw GcodeError("canned cycle L must be a positive integer");
  if ((q.code == 73 || q.code == 83) && q.q <= 0.0)
    throw GcodeError("negative or zero Q value in a pecking cycle");
  {
    const double pecks = (q.code == 73 || q.code == 83) ? std::ceil((r - bottom) / q.q) : 1.0;
    const double steps = static_cast<double>(q.repeats) * (3.0 * pecks + 4.0);
    if (steps > static_cast<double>(q.max_steps))
      throw GcodeError(
          fmt::format("canned cycle would make {:.3g} motions (more than {})", steps, q.max_steps));
  }
  double z = q.current[2];
  if (old_z < r) {
    push(out, K::kRapid, q.current[0], q.current[1], r);
    old_z = r;
    z = r;
  }
  const double clear = q.retract_to_r ? r : old_z;
  for (int rep = 0; rep < q.repeats; ++rep) {
    x += dx;
    y += dy;
    const double level = std::max(z, clear);
    push(out, K::kRapid, x, y, level);
    if (level != r) push(out, K::kRapid, x, y, r);
    switch (q.code) {
      case 81:
        push(out, K::kFeed, x, y, bottom);
        push(out, K::kRapid, x, y, clear);
        break;
      case 82:
      case 89: {
        push(out, K::kFeed, x, y, bottom);
        CycleStep d;
        d.kind = K::kDwell;
        d.to = {x, y, bottom};
        d.seconds = q.p;
        out.push_back(d);
        if (q.code == 89)
          push(out, K::kFeed, x, y, clear);  // G89 feeds all the way out (rs274)
        else
          push(out, K::kRapid, x, y, clear);
        break;
      }
      case 85:
        push(out, K::kFeed, x, y, bottom);
        push(out, K::kFeed, x, y, r);
        push(out, K::kRapid, x, y, clear);
        break;
      case 83:
      case 73: {
        for (double depth = r - q.q; depth > bottom; depth -= q.q) {
          push(out, K::kFeed, x, y, depth);
          if (q.code == 83) {
            push(out, K::kRapid, x, y, r);
            push(out, K::kRapid, x, y, depth + kPeckClearanceMm);
          } else {
            push(out, K::kRapid, x, y, depth + kPeckClearanceMm);
          }
        }
        push(out, K::kFeed, x, y, bottom);
        push(out, K::kRapid, x, y, clear);
        break;
      }
      default:
        throw GcodeError("unsupported canned cycle");
    }
    z = clear;
  }
  return {x, y, clear};
}

}  // namespace pkm::cnc
