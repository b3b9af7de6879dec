/* pkmhexkins: a LinuxCNC kinematics module for hexapods with pkm's model (pkmhexkins_core.h),
 * the full 42-parameter calibrated geometry as HAL pins. Documentation: docs/linuxcnc.md,
 * "The pkmhexkins kinematics component". Joints 0-5 are the strut readings; world X Y Z A B C
 * is the TCP pose (A, B, C roll-pitch-yaw in degrees).
 *
 * Load: `loadrt pkmhexkins` (pins with the hexapod-sim defaults, set by `setp`), or
 * `loadrt pkmhexkins params=FILE` (the file pkm writes: the pins' initial values, read and checked
 * at load, so that a missing parameter or a geometry that does not assemble at home fails the
 * loadrt with the reason in LinuxCNC's log). The pins take live changes while the machine stands
 * still (checked as at load); a change while it moves is refused (docs/linuxcnc.md, "Pins"). */
#include <math.h>
#include <string.h>

#include "hal.h"
#include "kinematics.h"
#include "pkmhexkins_core.h"
#include "rtapi.h"
#include "rtapi_app.h"
#include "rtapi_errno.h"

MODULE_LICENSE("Dual MIT/GPL");
MODULE_AUTHOR("pkm");
MODULE_DESCRIPTION("Hexapod kinematics with pkm's model and forward kinematics");

#define N PKM_HEX_STRUTS

static char* params = "";
RTAPI_MP_STRING(params, "pkm's pkmhexkins parameter file (geometry, tool, home, solver)");

static const double kDegPerRad = 180.0 / 3.14159265358979323846;

/* Most Newton steps one forward-kinematics call may take (limit-iterations is clamped to it):
 * the servo-time budget of docs/linuxcnc.md. */
#define PKM_HEX_MAX_LIMIT_ITERATIONS 120

static int comp_id;
#include "pkmhexkins_pins.h"

static pkm_hex_fk_options file_options; /* the parameter file's solver settings */
static pkm_hex_geometry validated;      /* the geometry in use (last found valid) */
static double validated_home[6];
static double validated_spindle_pin; /* spindle-offset (without tool-offset) of the one in use */
static int have_validated;
static int home_branch;      /* sign of det J at home for the geometry in use */
static int reported_invalid; /* the invalid or refused geometry was reported once */
static int armed;            /* a forward call has succeeded (LinuxCNC is past homing) */
static int failing;          /* failed forward calls in the current episode */
static int inverse_failing;  /* the inverse is in a reported failure episode */
static double last_joints[N];
static int have_last_joints;

/* The geometry from the pins. */
static void read_geometry(pkm_hex_geometry* g) {
  for (int i = 0; i < N; ++i) {
    for (int k = 0; k < 3; ++k) {
      g->base[i][k] = *hal->base[i][k];
      g->platform[i][k] = *hal->platform[i][k];
    }
    g->length_offset[i] = *hal->length_offset[i];
  }
  for (int k = 0; k < 3; ++k) g->tool[k] = *hal->tool[k];
  g->spindle_offset = *hal->spindle_offset + *hal->tool_offset;
}

/* 1 when the last forward call's joints are still and motion is in position. */
static int standing_still(const double* joints) {
  if (!*hal->in_position) return 0;
  if (!have_last_joints) return 1;
  for (int i = 0; i < N; ++i)
    if (!(fabs(joints[i] - last_joints[i]) <= *hal->still_tolerance)) return 0;
  return 1;
}

/* Checks a changed geometry as at load (pkm_hex_check_home: no singular or collinear home) and
 * takes it while the machine stands still; otherwise keeps the one in use (a message, once). */
static void take_geometry(const pkm_hex_geometry* g,
                          const double home[6],
                          const double* joints,
                          int tool_only) {
  char why[192];
  const double p[3] = {home[0], home[1], home[2]};
  const double rpy[3] = {home[3] / kDegPerRad, home[4] / kDegPerRad, home[5] / kDegPerRad};
  const char* what = "unusable geometry";
  int ok = pkm_hex_check_home(g, p, rpy, file_options.singular_pivot_ratio, why, sizeof why) == 0;
  if (ok && have_validated && !tool_only && !standing_still(joints)) {
    what = "geometry refused";
    rtapi_snprintf(why, sizeof why, "changed while the machine moves (kept the geometry in use)");
    ok = 0;
  }
  if (!ok) {
    *hal->geometry_ok = 0;
    *hal->fault = 1;
    if (!reported_invalid) rtapi_print_msg(RTAPI_MSG_ERR, "pkmhexkins: %s: %s\n", what, why);
    reported_invalid = 1;
    return;
  }
  double R[3][3];
  pkm_hex_rotation_from_rpy(rpy, R);
  validated = *g;
  memcpy(validated_home, home, sizeof validated_home);
  validated_spindle_pin = *hal->spindle_offset;
  home_branch = pkm_hex_branch(g, p, R, file_options.singular_pivot_ratio);
  if (armed && !tool_only)
    rtapi_print_msg(RTAPI_MSG_ERR, "pkmhexkins: new geometry taken (the machine stands still)\n");
  have_validated = 1;
  reported_invalid = 0;
  *hal->geometry_ok = 1;
}

/* 0 with the geometry in use in *g; −1 when there is none. Pin changes are checked first. */
static int current_geometry(pkm_hex_geometry* g, const double* joints) {
  if (*hal->hold && have_validated) { /* the pins are being changed together: not yet */
    *g = validated;
    return 0;
  }
  pkm_hex_geometry pinned;
  double home[6];
  memset(&pinned, 0, sizeof pinned);
  read_geometry(&pinned);
  for (int k = 0; k < 6; ++k) home[k] = *hal->home[k];
  const int changed = !have_validated || memcmp(&pinned, &validated, sizeof pinned) != 0 ||
                      memcmp(home, validated_home, sizeof home) != 0;
  /* A G43 tool length (tool-offset) alone is taken at once: LinuxCNC changes it itself. */
  pkm_hex_geometry untooled = pinned;
  untooled.spindle_offset = validated.spindle_offset;
  const int tool_only = changed && have_validated &&
                        *hal->spindle_offset == validated_spindle_pin &&
                        memcmp(&untooled, &validated, sizeof untooled) == 0 &&
                        memcmp(home, validated_home, sizeof home) == 0;
  if (changed && (joints != NULL || !have_validated || tool_only))
    take_geometry(&pinned, home, joints, tool_only); /* else the forward call (joints) decides */
  else if (!changed && reported_invalid) {           /* the pins are back to the geometry in use */
    reported_invalid = 0;
    *hal->geometry_ok = 1;
  }
  if (!have_validated) return -1;
  *g = validated;
  return 0;
}

static void pose_to_world(const double p[3],
                          const double R[3][3],
                          const double near_deg[3],
                          EmcPose* world) {
  double near[3], rpy[3];
  for (int k = 0; k < 3; ++k) near[k] = near_deg[k] / kDegPerRad;
  pkm_hex_rpy_from_rotation(R, near, rpy);
  world->tran.x = p[0];
  world->tran.y = p[1];
  world->tran.z = p[2];
  world->a = rpy[0] * kDegPerRad;
  world->b = rpy[1] * kDegPerRad;
  world->c = rpy[2] * kDegPerRad;
}

/* The solver's options from the parameter file and the pins: a hard budget of
 * limit-iterations Newton steps over the whole call (at most PKM_HEX_MAX_LIMIT_ITERATIONS), and
 * the home branch required. */
static pkm_hex_fk_options solver_options(void) {
  pkm_hex_fk_options o = file_options;
  hal_u32_t limit = *hal->limit_iterations;
  if (limit > PKM_HEX_MAX_LIMIT_ITERATIONS)
    *hal->limit_iterations = limit = PKM_HEX_MAX_LIMIT_ITERATIONS;
  o.tolerance = *hal->convergence_criterion;
  o.max_iterations = (int)limit;
  o.max_total_iterations = (int)limit;
  o.max_error = *hal->max_error > 0.0 ? *hal->max_error : INFINITY;
  o.branch = home_branch;
  return o;
}

/* FK from LinuxCNC's pose (the previous one, or its re-seed after homing): 0 and the world pose,
 * or the status. */
static pkm_hex_status forward_from(const pkm_hex_geometry* g,
                                   const double* joints,
                                   EmcPose* world) {
  const pkm_hex_fk_options o = solver_options();
  if (!(o.tolerance > 0.0) || o.max_iterations < 1) return PKM_HEX_INVALID_INPUT;
  const double seed[6] = {
      world->tran.x, world->tran.y, world->tran.z, world->a, world->b, world->c};
  double p[3] = {seed[0], seed[1], seed[2]}, rpy[3], R[3][3];
  for (int k = 0; k < 3; ++k) rpy[k] = seed[3 + k] / kDegPerRad;
  pkm_hex_rotation_from_rpy(rpy, R);
  const pkm_hex_fk_summary s = pkm_hex_forward(g, joints, &o, p, R);
  *hal->last_iterations = (hal_u32_t)s.iterations;
  if ((hal_u32_t)s.iterations > *hal->max_iterations)
    *hal->max_iterations = (hal_u32_t)s.iterations;
  if (s.status == PKM_HEX_OK) pose_to_world(p, R, seed + 3, world);
  return s.status;
}

/* Records a forward call's outcome: pins, and one message per failure episode. */
static void report_forward(pkm_hex_status status, const double* joints) {
  *hal->fwd_status = (hal_s32_t)status;
  *hal->fwd_kins_fail = status != PKM_HEX_OK;
  if (status == PKM_HEX_OTHER_BRANCH) ++*hal->branch_errors;
  if (status == PKM_HEX_OK) {
    if (failing > 0)
      rtapi_print_msg(RTAPI_MSG_ERR,
                      "pkmhexkins: forward kinematics recovered after %d failed calls\n",
                      failing);
    armed = 1;
    failing = 0;
    *hal->fault = !*hal->geometry_ok;
    return;
  }
  if (!armed) { /* before the first success: LinuxCNC's calls before homing */
    ++*hal->startup_failures;
    return;
  }
  ++*hal->fwd_kins_failures;
  *hal->fault = 1;
  if (failing++ == 0)
    rtapi_print_msg(RTAPI_MSG_ERR,
                    "pkmhexkins: forward kinematics failed (%s%s) at joints %.6g %.6g %.6g %.6g "
                    "%.6g %.6g: position feedback invalid, pkmhexkins.fault set\n",
                    pkm_hex_status_name(status),
                    status == PKM_HEX_OTHER_BRANCH ? ": the mirror or another assembly" : "",
                    joints[0],
                    joints[1],
                    joints[2],
                    joints[3],
                    joints[4],
                    joints[5]);
}

int kinematicsForward(const double* joints,
                      EmcPose* world,
                      const KINEMATICS_FORWARD_FLAGS* fflags,
                      KINEMATICS_INVERSE_FLAGS* iflags) {
  (void)fflags;
  (void)iflags;
  const long long start = rtapi_get_time();
  pkm_hex_geometry g;
  /* Seeded from LinuxCNC's pose only: no retry from home within the servo period (LinuxCNC
   * re-seeds from [TRAJ] HOME itself after homing). */
  const pkm_hex_status status =
      current_geometry(&g, joints) != 0 ? PKM_HEX_INVALID_INPUT : forward_from(&g, joints, world);
  report_forward(status, joints);
  memcpy(last_joints, joints, sizeof last_joints);
  have_last_joints = 1;
  const long long ns = rtapi_get_time() - start;
  *hal->last_call_ns = ns > 0 ? (hal_u32_t)ns : 0;
  if (*hal->last_call_ns > *hal->max_call_ns) *hal->max_call_ns = *hal->last_call_ns;
  return status == PKM_HEX_OK ? 0 : -1;
}

/* Records an inverse call's outcome: the pin, and one message per failure episode. */
static void report_inverse(int branch, const EmcPose* world) {
  const int failed = branch != home_branch;
  *hal->inv_kins_fail = failed;
  if (failed) ++*hal->branch_errors;
  if (failed && !inverse_failing)
    rtapi_print_msg(RTAPI_MSG_ERR,
                    "pkmhexkins: pose X%.4f Y%.4f Z%.4f A%.4f B%.4f C%.4f refused: %s\n",
                    world->tran.x,
                    world->tran.y,
                    world->tran.z,
                    world->a,
                    world->b,
                    world->c,
                    branch == 0 ? "singular (e.g. the platform in the base plane)"
                                : "beyond a singular configuration (the mirror assembly)");
  inverse_failing = failed;
}

int kinematicsInverse(const EmcPose* world,
                      double* joints,
                      const KINEMATICS_INVERSE_FLAGS* iflags,
                      KINEMATICS_FORWARD_FLAGS* fflags) {
  (void)iflags;
  (void)fflags;
  pkm_hex_geometry g;
  if (current_geometry(&g, NULL) != 0) return -1;
  const double p[3] = {world->tran.x, world->tran.y, world->tran.z};
  const double rpy[3] = {world->a / kDegPerRad, world->b / kDegPerRad, world->c / kDegPerRad};
  double R[3][3], q[N];
  pkm_hex_rotation_from_rpy(rpy, R);
  if (pkm_hex_inverse(&g, p, R, q) != 0) return -1;
  /* Only poses on home's assembly branch: the mirror pose has the same strut lengths. */
  const int branch = pkm_hex_branch(&g, p, R, file_options.singular_pivot_ratio);
  report_inverse(branch, world);
  if (branch != home_branch) return -1;
  for (int i = 0; i < N; ++i) joints[i] = q[i];
  return 0;
}

KINEMATICS_TYPE kinematicsType(void) { return KINEMATICS_BOTH; }

int kinematicsSwitchable(void) { return 0; }

int kinematicsSwitch(int switchkins_type) {
  (void)switchkins_type;
  return 0;
}

EXPORT_SYMBOL(kinematicsType);
EXPORT_SYMBOL(kinematicsForward);
EXPORT_SYMBOL(kinematicsInverse);
EXPORT_SYMBOL(kinematicsSwitchable);
EXPORT_SYMBOL(kinematicsSwitch);

/* The pins' initial values: the parameter file's (read and checked here), or the hexapod-sim
 * defaults without one. 0, or −1 with the reason logged. */
static int initial_values(pkm_hex_params* p) {
  memset(p, 0, sizeof *p);
  if (params == NULL || params[0] == '\0') {
    pkm_hex_sim_geometry(&p->geometry);
    pkm_hex_default_fk_options(&p->options);
    p->home[2] = 20.0; /* the sample's home: platform 20 in above the base */
    file_options = p->options;
    return 0;
  }
  char why[256];
  if (pkm_hex_load_params(params, p, why, sizeof why) != 0) {
    rtapi_print_msg(RTAPI_MSG_ERR, "pkmhexkins: %s: %s\n", params, why);
    return -1;
  }
  rtapi_print_msg(RTAPI_MSG_INFO, "pkmhexkins: parameters from %s\n", params);
  file_options = p->options;
  return 0;
}

int rtapi_app_main(void) {
  pkm_hex_params p;
  /* -EINVAL: rtapi_app then reports "Invalid argument" after the reason (not -1, EPERM's
   * "Operation not permitted"). */
  if (initial_values(&p) != 0) return -EINVAL;
  comp_id = hal_init("pkmhexkins");
  if (comp_id < 0) return comp_id;
  hal = hal_malloc(sizeof(pins));
  int r = hal == NULL ? -1 : 0;
  if (r == 0) r = geometry_pins(&p.geometry);
  if (r == 0) r = other_pins(&p);
  if (r != 0) {
    rtapi_print_msg(RTAPI_MSG_ERR, "pkmhexkins: cannot create the HAL pins (%d)\n", r);
    hal_exit(comp_id);
    return r < 0 ? r : -EINVAL;
  }
  hal_ready(comp_id);
  return 0;
}

void rtapi_app_exit(void) { hal_exit(comp_id); }
