/// @file
/// @brief Hexapod (6-UPS Stewart platform) kinematics for a LinuxCNC kinematics component, in
/// plain C (C99, no LinuxCNC dependency): the same model and formulas as pkm's C++ library
/// (include/pkm/kinematics/hexapod_model.hpp, src/kinematics/hexapod_ik.cpp, hexapod_fk.cpp,
/// detail/newton.hpp), checked against it by tests/linuxcnc/hexkins_core_test.cpp.
///
/// Model (docs/conventions.md): strut i joins the base joint centre b_i (world frame) to the
/// platform joint centre a_i (platform frame, relative to the platform origin). The controlled
/// point (TCP) is `tool` in the platform frame. With s = spindle_offset (genhexkins'
/// `spindle-offset` + `tool-offset`), the effective joints are
///   b'_i = b_i + s·ẑ,   a'_i = a_i − tool + s·ẑ,
/// and the reading (joint position) of strut i at the TCP pose (p, R) is
///   q_i = |p + R·a'_i − b'_i| − length_offset_i.
/// R = Rz(c)·Ry(b)·Rx(a) (LinuxCNC roll-pitch-yaw about fixed X, Y, Z). Lengths are in the
/// machine's unit; angles in radians in this API (LinuxCNC's degrees are converted by the
/// component).
#ifndef PKM_HEXKINS_CORE_H
#define PKM_HEXKINS_CORE_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/// Number of struts (joints).
#define PKM_HEX_STRUTS 6

/// The 42 calibration parameters and the tool: HexapodModel's kinematic fields as plain numbers.
typedef struct {
  double base[PKM_HEX_STRUTS][3];        ///< b_i, world frame, machine unit
  double platform[PKM_HEX_STRUTS][3];    ///< a_i, platform frame, machine unit
  double length_offset[PKM_HEX_STRUTS];  ///< reading + offset = joint-centre distance
  double tool[3];                        ///< TCP in the platform frame (HexapodModel::tool_offset)
  double spindle_offset;  ///< added to the z of every base and platform joint (see above)
} pkm_hex_geometry;

/// Options of the forward kinematics (defaults: pkm_hex_default_fk_options, = pkm's FkOptions).
typedef struct {
  double tolerance;    ///< converged when max_i |q_i(pose) − q_i| <= tolerance (machine unit)
  int max_iterations;  ///< Newton steps per continuation stage
  int max_backtracks;  ///< step halvings when a full step does not reduce |r|
  double singular_pivot_ratio;  ///< a smaller min/max LU pivot ratio means singular
  double max_step_translation;  ///< trust region: characteristic lengths per step
  double max_step_rotation;     ///< trust region: rad per step
  double continuation_step;     ///< stage size of a far seed, characteristic lengths of readings
  double max_error;  ///< a residual above this (machine unit) stops the solve (no convergence)
  /// Hard budget of one solve: at most this many Newton steps over all continuation stages
  /// (each with at most max_backtracks step halvings), and at most this many stages; 0: no
  /// budget (pkm's library: max_iterations per stage, up to 1000 stages). A solve that runs out
  /// returns PKM_HEX_BUDGET_EXHAUSTED. Worst-case cost: max_total_iterations × (one LU of the
  /// 6×6 Jacobian + max_backtracks + 2 evaluations of the six legs).
  int max_total_iterations;
  /// The assembly branch the solution must be on: +1 or −1, the sign of the determinant of the
  /// scaled strut Jacobian at the solution (pkm_hex_branch; it changes sign only through a
  /// singular configuration, e.g. the platform crossing the base plane into the mirror assembly);
  /// a solution on the other side gives PKM_HEX_OTHER_BRANCH. 0: no check (pkm's library).
  int branch;
} pkm_hex_fk_options;

/// Outcome of a forward-kinematics solve (pkm's FkStatus).
typedef enum {
  PKM_HEX_OK = 0,
  PKM_HEX_NO_CONVERGENCE,    ///< iteration cap, max_error, or no step reduced the residual
  PKM_HEX_SINGULAR,          ///< the strut Jacobian is numerically singular at an iterate
  PKM_HEX_INVALID_INPUT,     ///< a non-finite reading or seed
  PKM_HEX_OTHER_BRANCH,      ///< converged to another assembly mode than the seed's (or `branch`)
  PKM_HEX_BUDGET_EXHAUSTED,  ///< max_total_iterations Newton steps were not enough
} pkm_hex_status;

/// What a forward-kinematics solve did.
typedef struct {
  pkm_hex_status status;
  int iterations;       ///< Newton steps over all stages
  int backtracks;       ///< step halvings over all iterations
  double max_residual;  ///< max_i |residual_i| at the returned iterate (machine unit)
} pkm_hex_fk_summary;

/// "ok", "no_convergence", "singular", "invalid_input", "other_branch", "budget_exhausted".
const char* pkm_hex_status_name(pkm_hex_status status);

/// pkm's FkOptions defaults: tolerance 1e-9, 120 iterations, 12 backtracks, pivot ratio 1e-12,
/// trust region 0.5 L and 0.25 rad, continuation stages of 0.3 L; max_error +infinity; no total
/// budget and no branch check (max_total_iterations = branch = 0).
void pkm_hex_default_fk_options(pkm_hex_fk_options* options);

/// The LinuxCNC hexapod-sim sample geometry (inch; genhexkins' published defaults), no offsets.
void pkm_hex_sim_geometry(pkm_hex_geometry* geometry);

/// Mean distance of the platform joints a_i from the platform origin (1 when 0): the length
/// that makes the Jacobian's angular columns commensurate (HexapodModel::characteristicLength).
double pkm_hex_characteristic_length(const pkm_hex_geometry* geometry);

/// 0 when `geometry` is usable; otherwise −1 with the reason (NUL-terminated, at most `size`
/// bytes) in `why` (may be NULL): a non-finite value, two struts joining the same base and
/// platform joints (shared joints alone, as in a 6-3 hexapod, are allowed).
int pkm_hex_validate(const pkm_hex_geometry* geometry, char* why, size_t size);

/// 0 when the geometry assembles at the home pose (p, rpy in rad): pkm_hex_validate, then no strut
/// of zero length at home, and the scaled strut Jacobian at home not singular (its LU's min/max
/// pivot ratio above `singular_pivot_ratio`, the test forward kinematics uses). Otherwise −1 with
/// the reason in `why` (as pkm_hex_validate).
int pkm_hex_check_home(const pkm_hex_geometry* geometry,
                       const double p[3],
                       const double rpy[3],
                       double singular_pivot_ratio,
                       char* why,
                       size_t size);

/// Everything a pkmhexkins parameter file sets (pkm's io::linuxcncHexapodParameters writes it;
/// docs/linuxcnc.md, "The pkmhexkins parameter file"): the geometry, the home pose (the branch
/// reference of the component and LinuxCNC's [TRAJ] HOME) and the forward kinematics' settings.
typedef struct {
  pkm_hex_geometry geometry;
  double home[6];              ///< x, y, z (machine unit), a, b, c (degrees, as LinuxCNC's world)
  pkm_hex_fk_options options;  ///< max_error +infinity when the file gives 0 (no limit)
} pkm_hex_params;

/// Parses a parameter file's text: `name value...` lines, `#` comments, every name exactly once
/// (base.N, platform.N: 3 numbers; length-offset.N, spindle-offset, convergence-criterion,
/// limit-iterations, max-error, max-backtracks, singular-pivot-ratio, max-step-translation,
/// max-step-rotation, continuation-step: 1; tool: 3; home: 6), then checks the result
/// (pkm_hex_check_params). 0 and *params set, or −1 with "line N: ..." or "missing NAME" or the
/// check's reason in `why`; *params is then untouched.
int pkm_hex_parse_params(const char* text, pkm_hex_params* params, char* why, size_t size);

/// 0 when `params` are usable: the options valid (tolerance > 0, limit-iterations >= 1,
/// max-backtracks >= 0, 0 < singular-pivot-ratio < 1, positive trust region and continuation
/// step, max-error >= 0) and the geometry assembling at home (pkm_hex_check_home); −1 and why.
int pkm_hex_check_params(const pkm_hex_params* params, char* why, size_t size);

/// Reads and parses the parameter file at `path` (stdio; at most 64 KiB). As
/// pkm_hex_parse_params; a file that cannot be read gives "cannot read PATH".
int pkm_hex_load_params(const char* path, pkm_hex_params* params, char* why, size_t size);

/// R = Rz(rpy[2])·Ry(rpy[1])·Rx(rpy[0]), rpy in rad.
void pkm_hex_rotation_from_rpy(const double rpy[3], double R[3][3]);

/// Roll, pitch, yaw (rad) of R, of the two equivalent triples the one nearest to `near` (each
/// angle shifted by whole turns towards it); gimbal lock puts the whole yaw into c.
void pkm_hex_rpy_from_rotation(const double R[3][3], const double near[3], double rpy[3]);

/// Inverse kinematics: the readings q (machine unit) of the TCP pose (p, R). Returns 0, or −1
/// when an input or a reading is not finite (q is then unusable).
int pkm_hex_inverse(const pkm_hex_geometry* geometry,
                    const double p[3],
                    const double R[3][3],
                    double q[PKM_HEX_STRUTS]);

/// The assembly branch of the TCP pose (p, R): the sign (+1, −1) of the determinant of the scaled
/// strut Jacobian there, or 0 when it is numerically singular (its LU's min/max pivot ratio at or
/// below `singular_pivot_ratio`) or an input is not finite. The mirror assembly of a planar
/// platform and base (platform reflected through the base plane) has the opposite sign.
int pkm_hex_branch(const pkm_hex_geometry* geometry,
                   const double p[3],
                   const double R[3][3],
                   double singular_pivot_ratio);

/// Forward kinematics: the TCP pose (p, R) whose readings are q, by pkm's damped Newton on SO(3)
/// (left update R ← exp(−δθ)·R, LU with partial pivoting, step halving, trust region,
/// continuation from a far seed, one polishing step). (p, R) hold the seed on entry (the
/// previous pose) and the solution on PKM_HEX_OK; on any other status they are left unchanged.
/// Readings that give a strut of zero or negative length (q_i + length_offset_i <= 0, e.g. all
/// joints at 0 before homing) are PKM_HEX_INVALID_INPUT at once.
/// Precondition: `options` valid (tolerance > 0, max_iterations >= 1, ...).
pkm_hex_fk_summary pkm_hex_forward(const pkm_hex_geometry* geometry,
                                   const double q[PKM_HEX_STRUTS],
                                   const pkm_hex_fk_options* options,
                                   double p[3],
                                   double R[3][3]);

#ifdef __cplusplus
}
#endif

#endif  // PKM_HEXKINS_CORE_H
