/// @file
/// @brief Laser-interferometer measurements along a line of motion: linear positioning (ISO 230-2
/// cycle), straightness (horizontal or vertical optics with beam misalignment), diagonal
/// displacement (face and body diagonals, ISO 230-6) and angular (pitch/yaw) readings, on any
/// VirtualMachine (docs/formats.md, "Measurement files").
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "pkm/simulation/measurement_conditions.hpp"
#include "pkm/simulation/noise.hpp"
#include "pkm/simulation/virtual_machine.hpp"

namespace pkm::simulation {

/// What a line measurement reads.
enum class LineQuantity {
  kLinear,        ///< displacement along the beam (linear positioning, diagonals), mm
  kStraightness,  ///< lateral displacement from the beam line, mm
  kAngular,       ///< rotation of the tool about a fixed work-frame axis, rad (files: µrad)
};

/// The name used in files and scenarios: "linear", "straightness", "angular".
[[nodiscard]] const char* toString(LineQuantity quantity);

/// How the machine travels between targets.
enum class LineProcedure {
  kContinuous,  ///< all axes together along the line; one reading per target
  /// The step-diagonal ("laser vector") procedure (after C. Wang, Rev. Sci. Instrum. 71(10), 2000):
  /// from one target to the next each moving axis moves alone, in axis order, and the laser (with a
  /// flat mirror, which tolerates the lateral motion) is read after every single-axis sub-move.
  /// Only for kLinear on a line that moves at least two axes.
  kStepDiagonal,
};

/// The name used in files and scenarios: "continuous", "step_diagonal".
[[nodiscard]] const char* toString(LineProcedure procedure);

/// A line of motion in command space: command(s) = start + s·direction for the line coordinate s
/// (mm). The nominal tool displacement per unit s must have length 1 (checked), so s is the
/// nominal travel: one axis with a unit direction, or a diagonal with direction (a, b, c)/L.
struct MotionLine {
  Eigen::VectorXd start;      ///< command at s = 0
  Eigen::VectorXd direction;  ///< command change per mm of s
  /// The command at s.
  [[nodiscard]] Eigen::VectorXd at(double s) const { return start + s * direction; }
};

/// The ISO 230-2 measurement cycle: m targets from `first` to `last` (line coordinate, mm), each
/// interior target shifted by a uniform random offset in ±`target_jitter` (the same targets in
/// every run, ISO 230-2 §5.3.2); `runs` runs; each run approaches every target in the + direction
/// (ascending s, starting `overshoot` below `first`) and, when `bidirectional`, then in the −
/// direction (descending, starting `overshoot` above `last`).
struct PositioningCycle {
  double first = 0.0;          ///< first target, mm
  double last = 0.0;           ///< last target, mm (≠ first when targets ≥ 2)
  int targets = 2;             ///< number of targets, ≥ 2
  double target_jitter = 0.0;  ///< amplitude of the random target offsets, mm, ≥ 0
  int runs = 5;                ///< number of runs, ≥ 1 (ISO 230-2: 5)
  double overshoot = 0.0;      ///< travel beyond the end targets before a pass, mm, ≥ 0
  bool bidirectional = true;   ///< also approach every target in the − direction
  /// Throws pkm::InvalidArgument naming the field when a precondition above is violated, or when
  /// the jitter is not below half the target spacing (targets must stay in order).
  void validate() const;
};

/// The set-up of one line measurement.
struct LineSetup {
  std::string name;  ///< unique in a campaign; names the random stream
  LineQuantity quantity = LineQuantity::kLinear;
  LineProcedure procedure = LineProcedure::kContinuous;  ///< continuous or step-diagonal
  MotionLine line;                                       ///< the axis motion
  PositioningCycle cycle;                                ///< targets and runs
  /// Where the moving optic (reflector) sits relative to the tool point, in the tool frame, mm: the
  /// Abbe offset. Angular errors of the machine show in the reading as offset × angle.
  Eigen::Vector3d reflector_offset = Eigen::Vector3d::Zero();
  /// kStraightness: the nominal lateral direction in the work frame (e.g. x̂ horizontal, ẑ
  /// vertical); made perpendicular to the beam. kAngular: the rotation axis read (e.g. ŷ for the
  /// pitch of an X axis). Unused for kLinear.
  Eigen::Vector3d lateral = Eigen::Vector3d::UnitZ();
  /// kStraightness: the beam misalignment, rad: the beam line is tilted towards `lateral` so that
  /// the reading gains the slope `misalignment` (reading ≈ deviation + misalignment·(s − s₀)).
  double misalignment = 0.0;
  /// The instrument noise, in the reading's unit (mm, or rad for kAngular); its ppm term is a
  /// scale error of the line (NoiseModel::drawScale, once per line) times the travel from the
  /// datum s − s₀.
  NoiseModel noise;
  /// Throws pkm::InvalidArgument when a part is invalid or the name is empty.
  void validate() const;
};

/// What a laser's environmental compensation unit read at one reading (its sensors, with their
/// errors): the records a measurement file carries (docs/formats.md, "Environment records").
struct SensedConditions {
  bool recorded = false;                 ///< false: no records (no environment, or not a laser)
  double air_temperature_c = 20.0;       ///< °C
  double air_pressure_pa = 101325.0;     ///< Pa
  double air_humidity_rh = 50.0;         ///< %RH
  double material_temperature_c = 20.0;  ///< °C
  /// The tool's rotation since the datum (rad, work frame, rotation vector), as angular optics
  /// (or a tracker) read it along the line: the source of the set-up's Abbe record.
  Eigen::Vector3d rotation_rad = Eigen::Vector3d::Zero();
};

/// One reading: the target (line coordinate, mm), the approach direction (+1 or −1) and the reading
/// (mm, or rad for kAngular).
struct LineReading {
  double target = 0.0;   ///< commanded line coordinate, mm
  int direction = 1;     ///< +1: approached in +s, −1: in −s
  double reading = 0.0;  ///< instrument reading (see simulateLine)
  /// 0 for a reading at a target of a continuous line. Step-diagonal: k ≥ 1 for the reading after
  /// the k-th single-axis sub-move of a step (the last one is at the target); `target` is then the
  /// nominal position of the commanded point along the beam, s₀ + b·(p̄(command) − p̄(s₀)).
  int sub_step = 0;
  /// kLinear readings taken in an environment (simulateLine with conditions): what the
  /// compensation unit's sensors read at this reading.
  SensedConditions sensed = {};
};

/// The readings of one run, in the order taken.
struct LineRun {
  int run = 1;                        ///< run number, from 1
  std::vector<LineReading> readings;  ///< + pass, then − pass
};

/// The targets of the cycle after the random offsets, ascending (draws target_jitter offsets from
/// `rng` for the targets − 2 interior targets, none when target_jitter = 0).
[[nodiscard]] std::vector<double> cycleTargets(const PositioningCycle& cycle, RandomStream& rng);

/// Runs the measurement on `machine` (after machine.reset(s), s the first raw draw of `rng` after
/// the target offsets, so the machine's own noise is independent per measurement). The instrument
/// is zeroed at the datum, the first target s₀ approached in + at the start of run 1, as an
/// operator zeroes a laser:
/// - kLinear: reading = s₀ + b·(p(s) − p(s₀)), b the nominal unit tool displacement per +s, p the
///   actual reflector position in the work frame; so reading − target is the positioning deviation.
/// - kStraightness: reading = l'·(p(s) − p(s₀)), l' = normalize(l + misalignment·b), l the
///   lateral direction made perpendicular to b.
/// - kAngular: reading = lateral·so3Log(R(s)·R(s₀)ᵀ), R the actual tool rotation.
/// Step-diagonal lines read after every sub-move (LineProcedure::kStepDiagonal, LineReading::
/// sub_step): the − pass moves the axes in the same order as the + pass.
/// Noise is added per reading (none at the zeroing), the ppm term as one scale error of the line.
/// The random target offsets come first from `rng`, then the machine's seed, then the line's
/// scale error (when sigma_ppm > 0), then the noise in reading order. Throws pkm::InvalidArgument
/// for an invalid set-up or a line whose nominal tool displacement per unit s does not have
/// length 1.
[[nodiscard]] std::vector<LineRun> simulateLine(VirtualMachine& machine,
                                                const LineSetup& setup,
                                                RandomStream& rng);

/// simulateLine in an environment (environment.hpp): `conditions` (null: the ideal environment,
/// as above) is zeroed with the instrument and advanced before every reading (readingCount of
/// them); every pose the machine reaches (the datum's too) becomes conditions->actualPose(pose)
/// (thermal expansion, warm-up), the reflector sits at reflector_offset +
/// conditions->reflectorOffset(), and a linear reading's displacement from the datum becomes
/// conditions->laserDisplacement(b'·(p(s) − p(s₀))), b' = conditions->laserBeam(b) (set-up).
/// Straightness and angular optics are differential (both beams in the same air), so the air does
/// not act on them.
[[nodiscard]] std::vector<LineRun> simulateLine(VirtualMachine& machine,
                                                const LineSetup& setup,
                                                RandomStream& rng,
                                                MeasurementConditions* conditions);

/// As above, with the instrument's ppm scale error given for the session instead of drawn for the
/// line: `scale_z` standard deviations of the noise's sigma_ppm (NoiseModel::scaleFor), the same
/// for every line a campaign measures with one laser (its environmental compensation holds over
/// the session). Nothing is drawn from `rng` for it.
[[nodiscard]] std::vector<LineRun> simulateLine(VirtualMachine& machine,
                                                const LineSetup& setup,
                                                RandomStream& rng,
                                                MeasurementConditions* conditions,
                                                double scale_z);

/// The largest difference between the tool rotations recorded along a line (rad; readings with
/// SensedConditions::recorded, all runs): the range of the axis's angular error, which an offset
/// reflector reads as an Abbe error. 0 without records.
[[nodiscard]] double rotationRange(const std::vector<LineRun>& runs);

/// The number of readings simulateLine takes (runs × targets × passes × sub-moves per target).
[[nodiscard]] int readingCount(const LineSetup& setup);

}  // namespace pkm::simulation
