/// @file
/// @brief Exechon kinematics for a LinuxCNC kinematics component, in plain C (C99, no LinuxCNC
/// dependency): Zoppi's tripod (legs A, B, C; leg B's base-joint offsets solved by Newton) with the
/// C/A wrist, the same formulas as pkm's C++ library (src/kinematics/exechon_*.cpp), checked
/// against it by tests/linuxcnc/exechon_core_test.cpp.
///
/// Joints (pkm's CLI column order): q1, q2, q3 = readings of legs A, B, C (machine length unit),
/// then the wrist readings C and A (rad here; degrees in LinuxCNC).
/// World: the tool point (x, y, z) in the machine's world frame (the frame `pkm exechon fk`
/// reports), and the wrist readings C and A themselves ("axes" orientation, as
/// `pkm gcode run --orientation axes`): the tool point is
///   world_T_zoppi · (S(e) + R(e) · (L · W·Rz(θC)·Rx(θA)·ẑ)),  θC = c_sign·C + c0, θA = a_sign·A +
///   a0
/// with L = tool_length + the extra tool length (a G43 offset). Frames and symbols:
/// docs/conventions.md, "Exechon tripod" and "C/A wrist".
#ifndef PKM_EXECHON_KINS_CORE_H
#define PKM_EXECHON_KINS_CORE_H

#ifdef __cplusplus
extern "C" {
#endif

/// Number of joints: legs A, B, C, wrist C, wrist A.
#define PKM_EXECHON_JOINTS 5

/// Most forward-kinematics Newton steps and step halvings per step a parameter file may ask for
/// (the component clamps its limit-iterations pin to the first): the servo-time budget of one
/// call is at most 120 × 31 evaluations of the legs (docs/linuxcnc.md).
#define PKM_EXECHON_MAX_ITERATIONS 120
#define PKM_EXECHON_MAX_BACKTRACKS 30

/// Outcome of a solve. Expected failures are statuses; nothing is clamped.
typedef enum {
  PKM_EXECHON_OK = 0,
  PKM_EXECHON_INVALID_INPUT,  ///< a non-finite input
  PKM_EXECHON_SINGULAR,       ///< a singular Jacobian, or condition number of dq/dS > max_condition
  PKM_EXECHON_NO_CONVERGENCE,  ///< Newton did not converge (IK: typically a point out of reach)
  PKM_EXECHON_OUT_OF_RANGE,  ///< solved, but a leg stroke or an alpha, beta, C, A range is violated
  PKM_EXECHON_OTHER_BRANCH,  ///< solved, but on another assembly branch than home's (see branch)
  PKM_EXECHON_BUDGET_EXHAUSTED,  ///< FK: fk_max_iterations Newton steps were not enough
} pkm_exechon_status;

/// "ok", "invalid_input", "singular", "no_convergence", "out_of_range", "other_branch",
/// "budget_exhausted".
const char* pkm_exechon_status_name(pkm_exechon_status status);

/// The machine: ExechonModel's fields as plain numbers. Lengths in the machine's unit, angles in
/// rad. Filled by pkm_exechon_parse_params from the file `pkm` writes
/// (io::linuxcncExechonParameters), then completed by pkm_exechon_prepare.
typedef struct {
  /* Zoppi's tripod (ExechonTripodGeometry); delta1B, delta2B only name the assembly branch. */
  double dA, dB, dC, l12A, l12C, l12B, l23B, pA, pB, pC, hA, hC, hx, hz;
  int delta1B, delta2B, deltaA, deltaC;
  /* Legs A, B, C: reading + length_offset = geometric length; stroke [min, max] of the reading. */
  double length_offset[3], stroke_min[3], stroke_max[3];
  /* Ranges [min, max] (rad; ±HUGE_VAL disables a side). */
  double alpha_range[2], beta_range[2], c_range[2], a_range[2];
  /* Wrist: axes in the platform frame, zero offsets (rad), senses (±1), tool length. */
  double c_axis[3], a_axis[3], c0, a0;
  int c_sign, a_sign;
  double tool_length;
  /* world_T_zoppi: rotation (row-major) and Zoppi origin O in the world frame. */
  double world_R_zoppi[9], world_p_zoppi[3];
  /* Home configuration: e = (alpha, beta, h), wrist C, A. */
  double home_e[3], home_c, home_a;
  double max_condition;            ///< largest allowed condition number of dq/dS (unit-free)
  double fk_tolerance;             ///< FK: largest leg residual at convergence, length unit
  int fk_max_iterations;           ///< FK: Newton step cap
  int fk_max_backtracks;           ///< FK: step halvings per iteration
  double fk_singular_pivot_ratio;  ///< FK: smallest/largest LU pivot below this is singular
  /* Derived by pkm_exechon_prepare: W = [a, c × a, c] (row-major) and max(|dA|, |dB|, |dC|). */
  double wrist_frame[9];
  double characteristic_length;
  /* Derived: the assembly branch of home, the sign (±1) of det d(lengths)/de there; it changes
   * only through a singular configuration. */
  int branch;
} pkm_exechon_params;

/// The previous solution, for continuity: e = (alpha, beta, h) of the last IK or FK.
typedef struct {
  double e[3];
  int valid;  ///< 0: start from the home configuration
} pkm_exechon_state;

/// Checks the parameters and fills the derived fields. Returns 0, or -1 with a message in
/// why[0..why_size) (which field is wrong; a home that does not assemble or is singular).
int pkm_exechon_prepare(pkm_exechon_params* params, char* why, int why_size);

/// Reads the parameter file text (`name value...` lines, `#` comments; names as
/// io::linuxcncExechonParameters writes them, angles in degrees) into *params and prepares it.
/// Returns 0, or -1 with "line N: ..." or "missing NAME" in why.
int pkm_exechon_parse_params(const char* text, pkm_exechon_params* params, char* why, int why_size);

/// Geometric leg lengths of legs A, B, C at e = (alpha, beta, h) in the model's leg working modes;
/// J_q_e (row-major 3×3, may be NULL) receives d(lengths)/de. Returns 0, or -1 when leg B's offset
/// solve fails.
int pkm_exechon_leg_lengths(const pkm_exechon_params* p,
                            const double e[3],
                            double lengths[3],
                            double* J_q_e);

/// Condition number σmax/σmin of dq/dS at e (HUGE_VAL when singular), as pkm's checks compute it.
double pkm_exechon_condition(const pkm_exechon_params* p, const double e[3]);

/// Inverse kinematics. world = (x, y, z, C, A): the tool point (world frame, length unit) and the
/// wrist readings (rad); extra_tool_length adds to the model's tool length along the tool
/// direction (the G43 offset). Newton's method on e from state->e (home when !state->valid), so
/// the tripod stays on the previous solution's branch; converged when |F| <= 1e-14·L (or <= 1e-12·L
/// and no longer falling). On OK, joints = (q1, q2, q3, C, A) and state->e is updated (the branch
/// state is committed on success only); on OUT_OF_RANGE and SINGULAR (condition limit) the joints
/// are set (the true readings, not clamped) but state->e is not; a solution on another branch
/// than home's (det d(lengths)/de of the other sign) is OTHER_BRANCH; otherwise nothing is
/// touched.
pkm_exechon_status pkm_exechon_inverse(const pkm_exechon_params* p,
                                       pkm_exechon_state* state,
                                       const double world[5],
                                       double extra_tool_length,
                                       double joints[5]);

/// Forward kinematics: joints (q1, q2, q3, C, A) -> world (x, y, z, C, A). Damped Newton on e for
/// the leg readings (pkm's stopping rule: largest leg residual <= fk_tolerance, one polishing
/// step), seeded by state->e (home when !state->valid). Applies no limits (as pkm's FK), but a
/// solution on another branch than home's is OTHER_BRANCH, and a solve stopped by
/// fk_max_iterations is BUDGET_EXHAUSTED (at most fk_max_iterations × (fk_max_backtracks + 1)
/// evaluations of the legs). On OK, world and state->e are set; otherwise neither is touched.
/// *iterations (may be NULL) receives the Newton steps.
pkm_exechon_status pkm_exechon_forward(const pkm_exechon_params* p,
                                       pkm_exechon_state* state,
                                       const double joints[5],
                                       double extra_tool_length,
                                       double world[5],
                                       int* iterations);

/// The tripod configuration e of the world pose (x, y, z, C, A) by the inverse's Newton from home,
/// no limits applied: a forward-kinematics seed from a pose (LinuxCNC's). On OK, state->e is set
/// and state->valid = 1; otherwise state is untouched.
pkm_exechon_status pkm_exechon_seed(const pkm_exechon_params* p,
                                    const double world[5],
                                    double extra_tool_length,
                                    pkm_exechon_state* state);

/// +1 or −1: the branch of e (sign of det d(lengths)/de), 0 when singular or not computable.
int pkm_exechon_branch(const pkm_exechon_params* p, const double e[3]);

/// The joints at the home configuration (q1, q2, q3, home C, home A) and its world pose.
void pkm_exechon_home(const pkm_exechon_params* p,
                      double extra_tool_length,
                      double joints[5],
                      double world[5]);

#ifdef __cplusplus
}
#endif

#endif /* PKM_EXECHON_KINS_CORE_H */
