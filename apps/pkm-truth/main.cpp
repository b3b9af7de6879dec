// pkm-truth: the physical hexapod behind LinuxCNC's joint commands, as a userspace HAL component
// (docs/linuxcnc.md, "A simulated machine in the loop"). A HAL file starts it:
//
//   loadusr -Wn pkmtruth pkm-truth --truth truth.json [--name pkmtruth] [--period-ms 1]
//   net j0 joint.0.pos-cmd => pkmtruth.joint-0     (… joint-5)
//
// Pins (lengths in mm, angles in degrees):
//   NAME.joint-0..5  in  float  the commanded strut readings
//   NAME.zero        in  bit    a rising edge zeroes the gauges and the laser here
//   NAME.gauge-0..2  out float  dial-gauge readings (simulation::HexapodMachineInLoop)
//   NAME.laser-x     out float  the laser's reading along x
//   NAME.x .y .z .a .b .c  out float  the true tool pose
//   NAME.ok          out bit    the last command was followed (forward kinematics converged)
// Parsing and pins only: the machine is pkm::simulation's. Exit codes as pkm's.
#include <fmt/format.h>
#include <hal.h>
#include <signal.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <atomic>
#include <chrono>
#include <cmath>
#include <thread>

#include "pkm/core/error.hpp"
#include "pkm/geometry/so3.hpp"
#include "pkm/io/truth_file.hpp"
#include "pkm/simulation/machine_in_loop.hpp"

namespace {

std::atomic<bool> g_stop{false};
void onSignal(int) { g_stop = true; }

struct Pins {
  hal_float_t* joint[6];
  hal_bit_t* zero;
  hal_float_t* gauge[3];
  hal_float_t* laser_x;
  hal_float_t* pose[6];
  hal_bit_t* ok;
};

/// Makes every pin of `p` for component `comp` named `name`. Throws pkm::IoError on failure.
void makePins(Pins& p, int comp, const std::string& name) {
  const auto check = [&](int rc, const std::string& pin) {
    if (rc != 0) throw pkm::IoError(fmt::format("cannot make HAL pin {}.{} ({})", name, pin, rc));
  };
  for (int i = 0; i < 6; ++i)
    check(hal_pin_float_newf(HAL_IN, &p.joint[i], comp, "%s.joint-%d", name.c_str(), i),
          fmt::format("joint-{}", i));
  check(hal_pin_bit_newf(HAL_IN, &p.zero, comp, "%s.zero", name.c_str()), "zero");
  for (int j = 0; j < 3; ++j)
    check(hal_pin_float_newf(HAL_OUT, &p.gauge[j], comp, "%s.gauge-%d", name.c_str(), j),
          fmt::format("gauge-{}", j));
  check(hal_pin_float_newf(HAL_OUT, &p.laser_x, comp, "%s.laser-x", name.c_str()), "laser-x");
  const char* axes[] = {"x", "y", "z", "a", "b", "c"};
  for (int k = 0; k < 6; ++k)
    check(hal_pin_float_newf(HAL_OUT, &p.pose[k], comp, "%s.%s", name.c_str(), axes[k]), axes[k]);
  check(hal_pin_bit_newf(HAL_OUT, &p.ok, comp, "%s.ok", name.c_str()), "ok");
}

/// Follows the joints until SIGTERM or SIGINT.
void run(pkm::simulation::HexapodMachineInLoop& m,
         Pins& p,
         double period_ms,
         const std::vector<double>& offsets) {
  bool last_zero = false;
  const auto period = std::chrono::microseconds(static_cast<long>(period_ms * 1000));
  while (!g_stop.load()) {
    pkm::kinematics::StrutVector q;
    for (int i = 0; i < 6; ++i) q[i] = *p.joint[i] + offsets[static_cast<std::size_t>(i)];
    *p.ok = m.command(q);
    const bool zero = *p.zero;
    if (zero && !last_zero) m.zero();
    last_zero = zero;
    const std::array<double, 3> g = m.gauges();
    for (int j = 0; j < 3; ++j) *p.gauge[j] = g[static_cast<std::size_t>(j)];
    *p.laser_x = m.laser();
    const pkm::kinematics::PoseRpy pose = pkm::kinematics::PoseRpy{
        m.truePose().translation(), pkm::geometry::rpyFromRotation(m.truePose().linear())};
    for (int k = 0; k < 3; ++k) *p.pose[k] = pose.position[k];
    for (int k = 0; k < 3; ++k) *p.pose[3 + k] = pose.rpy[k] * 180.0 / M_PI;
    std::this_thread::sleep_for(period);
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"the simulated physical hexapod in LinuxCNC's loop (a userspace HAL component)",
               "pkm-truth"};
  std::string truth_path, name = "pkmtruth";
  double period_ms = 1.0;
  std::vector<double> offsets(6, 0.0);
  app.add_option("--truth", truth_path, "truth.json of `pkm simulate` (a hexapod truth)")
      ->required();
  app.add_option("--name", name, "the component's name (its pins' prefix)");
  app.add_option("--period-ms", period_ms, "how often the pins are read, ms")
      ->check(CLI::Range(0.1, 1000.0));
  app.add_option("--joint-offset", offsets, "each joint's HOME_OFFSET: reading = motor + offset")
      ->delimiter(',')
      ->expected(6);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  try {
    const pkm::io::HexapodTruth truth = pkm::io::readHexapodTruth(truth_path);
    pkm::simulation::HexapodMachineInLoop machine(pkm::io::trueMachine(truth));
    const int comp = hal_init(name.c_str());
    if (comp < 0) throw pkm::IoError(fmt::format("hal_init({}) failed ({})", name, comp));
    Pins* pins = static_cast<Pins*>(hal_malloc(sizeof(Pins)));
    if (pins == nullptr) throw pkm::IoError("hal_malloc failed");
    try {
      makePins(*pins, comp, name);
    } catch (...) {
      hal_exit(comp);
      throw;
    }
    signal(SIGTERM, onSignal);
    signal(SIGINT, onSignal);
    hal_ready(comp);
    fmt::print(stderr,
               "pkm-truth: {} follows the joints of the true {} ({})\n",
               name,
               truth.machine,
               truth_path);
    run(machine, *pins, period_ms, offsets);
    hal_exit(comp);
  } catch (const pkm::IoError& e) {
    fmt::print(stderr, "pkm-truth: error: {}\n", e.what());
    return 2;
  } catch (const pkm::InvalidArgument& e) {
    fmt::print(stderr, "pkm-truth: error: {}\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, "pkm-truth: internal error: {}\n", e.what());
    return 3;
  }
  return 0;
}
