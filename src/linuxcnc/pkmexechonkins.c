/* pkmexechonkins: LinuxCNC kinematics for an Exechon tripod with a C/A wrist, from pkm's model.
 *
 * Joints: 0, 1, 2 = readings of legs A, B, C (machine unit); 3 = wrist C, 4 = wrist A (degrees),
 * the order of pkm's CLI columns (q1,q2,q3,c,a). World: X Y Z = the tool point in the machine's
 * world frame (what `pkm exechon fk` reports), A and C = the wrist readings (degrees), B unused
 * (0). The controlled point is the machine file's tool point; the HAL pin tool-offset (net it to
 * motion.tooloffset.z) adds a G43 tool length along the tool direction. Docs: docs/linuxcnc.md,
 * "Exechon kinematics in LinuxCNC".
 *
 * Load: loadrt pkmexechonkins params=/path/to/exechon.params (the file `pkm` writes); a missing or
 * bad file fails the load with the reason in LinuxCNC's log. Built with halcompile --compile
 * (uspace: the parameter file is read with stdio at load time). */
#include <stdio.h>
#include <stdlib.h>

#include "hal.h"
#include "kinematics.h"
#include "rtapi.h"
#include "rtapi_app.h"
#include "rtapi_errno.h"

/* One translation unit, as halcompile builds one file. */
#include "pkmexechonkins_core.c"
#include "pkmexechonkins_fk.c"
#include "pkmexechonkins_math.c"
#include "pkmexechonkins_params.c"
#include "pkmexechonkins_prepare.c"

MODULE_LICENSE("GPL");
MODULE_DESCRIPTION("pkm Exechon kinematics (legs A, B, C + wrist C, A)");

static char* params = "";
RTAPI_MP_STRING(params, "path of the pkm Exechon parameter file");

/* HAL pins of the component (prefix pkmexechonkins.). */
typedef struct {
  hal_float_t* tool_offset;     /* in: G43 tool length, machine unit (motion.tooloffset.z) */
  hal_float_t* convergence;     /* io: FK tolerance, largest leg residual, machine unit */
  hal_u32_t* limit_iterations;  /* io: FK Newton step cap */
  hal_u32_t* last_iterations;   /* out: FK Newton steps of the last call */
  hal_s32_t* inv_status;        /* out: pkm_exechon_status of the last inverse call */
  hal_s32_t* fwd_status;        /* out: pkm_exechon_status of the last forward call */
  hal_bit_t* inv_kins_fail;     /* out: the last inverse call failed */
  hal_bit_t* fwd_kins_fail;     /* out: the last forward call failed (held until a success) */
  hal_bit_t* fault;             /* out: a forward failure after the first success: net to E-stop */
  hal_u32_t* fwd_kins_failures; /* out: failed forward calls after the first success */
  hal_u32_t* startup_failures;  /* out: failed forward calls before it (joints before homing) */
  hal_u32_t* last_call_ns;      /* out: time of the last forward call */
  hal_u32_t* max_call_ns;       /* out: longest forward call since load */
} pkx_pins;

#define PKX_DEG_PER_RAD (180.0 / 3.14159265358979323846264338327950288)

static int comp_id;
static pkx_pins* pins;
static pkm_exechon_params machine;
static pkm_exechon_state inverse_state, forward_state;
static double last_world[5]; /* the pose of the last successful forward call */
static int have_last_world;
static int armed;   /* a forward call has succeeded */
static int failing; /* failed forward calls in the current episode */

/* Logs a failure once per change of status (the kinematics run at the servo rate). */
static void pkx_report(const char* which, pkm_exechon_status status, hal_s32_t* last) {
  if ((int)status != *last && status != PKM_EXECHON_OK)
    rtapi_print_msg(RTAPI_MSG_ERR,
                    "pkmexechonkins: %s kinematics: %s\n",
                    which,
                    pkm_exechon_status_name(status));
  *last = (hal_s32_t)status;
}

/* The FK seed: the state of our last solution when LinuxCNC passes its pose back (to 1e-6 of
 * the machine's size), else the configuration of LinuxCNC's pose (its re-seed, e.g. [TRAJ] HOME
 * after homing). */
static pkm_exechon_state pkx_seed(const double w[5]) {
  pkm_exechon_state seed = forward_state;
  double d = 0.0;
  for (int i = 0; i < 3; ++i) d = fmax(d, fabs(w[i] - last_world[i]));
  if (have_last_world && d <= 1e-6 * machine.characteristic_length && w[3] == last_world[3] &&
      w[4] == last_world[4])
    return seed;
  if (pkm_exechon_seed(&machine, w, *pins->tool_offset, &seed) != PKM_EXECHON_OK)
    seed = forward_state; /* an unusable pose: our own last state */
  return seed;
}

/* Pins and one message per failure episode for a forward call. */
static void pkx_forward_outcome(pkm_exechon_status s, const double* joint) {
  *pins->fwd_kins_fail = s != PKM_EXECHON_OK;
  *pins->fwd_status = (hal_s32_t)s;
  if (s == PKM_EXECHON_OK) {
    if (failing > 0)
      rtapi_print_msg(RTAPI_MSG_ERR,
                      "pkmexechonkins: forward kinematics recovered after %d failed calls\n",
                      failing);
    armed = 1, failing = 0;
    *pins->fault = 0;
    return;
  }
  if (!armed) { /* before the first success: LinuxCNC's calls before homing */
    ++*pins->startup_failures;
    return;
  }
  ++*pins->fwd_kins_failures;
  *pins->fault = 1;
  if (failing++ == 0)
    rtapi_print_msg(RTAPI_MSG_ERR,
                    "pkmexechonkins: forward kinematics failed (%s) at joints %.6g %.6g %.6g %.6g "
                    "%.6g: position feedback invalid, pkmexechonkins.fault set\n",
                    pkm_exechon_status_name(s),
                    joint[0],
                    joint[1],
                    joint[2],
                    joint[3],
                    joint[4]);
}

int kinematicsForward(const double* joint,
                      struct EmcPose* world,
                      const KINEMATICS_FORWARD_FLAGS* fflags,
                      KINEMATICS_INVERSE_FLAGS* iflags) {
  (void)fflags, (void)iflags;
  const long long start = rtapi_get_time();
  double q[5] = {
      joint[0], joint[1], joint[2], joint[3] / PKX_DEG_PER_RAD, joint[4] / PKX_DEG_PER_RAD};
  const double seen[5] = {world->tran.x,
                          world->tran.y,
                          world->tran.z,
                          world->c / PKX_DEG_PER_RAD,
                          world->a / PKX_DEG_PER_RAD};
  double w[5];
  int iterations = 0;
  if (*pins->convergence > 0.0)
    machine.fk_tolerance = *pins->convergence; /* else keep the file's */
  if (*pins->limit_iterations > PKM_EXECHON_MAX_ITERATIONS)
    *pins->limit_iterations = PKM_EXECHON_MAX_ITERATIONS; /* the servo-time budget */
  if (*pins->limit_iterations >= 1) machine.fk_max_iterations = (int)*pins->limit_iterations;
  pkm_exechon_state state = pkx_seed(seen);
  const pkm_exechon_status s =
      pkm_exechon_forward(&machine, &state, q, *pins->tool_offset, w, &iterations);
  *pins->last_iterations = (hal_u32_t)iterations;
  pkx_forward_outcome(s, joint);
  if (s == PKM_EXECHON_OK) {
    forward_state = inverse_state = state; /* the branch the machine is in now */
    world->tran.x = w[0], world->tran.y = w[1], world->tran.z = w[2];
    world->c = w[3] * PKX_DEG_PER_RAD, world->a = w[4] * PKX_DEG_PER_RAD, world->b = 0.0;
    world->u = world->v = world->w = 0.0;
    for (int i = 0; i < 5; ++i) last_world[i] = w[i];
    have_last_world = 1;
  }
  const long long ns = rtapi_get_time() - start;
  *pins->last_call_ns = ns > 0 ? (hal_u32_t)ns : 0;
  if (*pins->last_call_ns > *pins->max_call_ns) *pins->max_call_ns = *pins->last_call_ns;
  return s == PKM_EXECHON_OK ? 0 : -1;
}

int kinematicsInverse(const struct EmcPose* world,
                      double* joint,
                      const KINEMATICS_INVERSE_FLAGS* iflags,
                      KINEMATICS_FORWARD_FLAGS* fflags) {
  (void)iflags, (void)fflags;
  const double w[5] = {world->tran.x,
                       world->tran.y,
                       world->tran.z,
                       world->c / PKX_DEG_PER_RAD,
                       world->a / PKX_DEG_PER_RAD};
  double q[5];
  const pkm_exechon_status s =
      world->b != 0.0 ? PKM_EXECHON_INVALID_INPUT
                      : pkm_exechon_inverse(&machine, &inverse_state, w, *pins->tool_offset, q);
  *pins->inv_kins_fail = s != PKM_EXECHON_OK;
  pkx_report("inverse", s, pins->inv_status);
  if (s != PKM_EXECHON_OK) return -1;
  joint[0] = q[0], joint[1] = q[1], joint[2] = q[2];
  joint[3] = q[3] * PKX_DEG_PER_RAD, joint[4] = q[4] * PKX_DEG_PER_RAD;
  return 0;
}

int kinematicsHome(struct EmcPose* world,
                   double* joint,
                   KINEMATICS_FORWARD_FLAGS* fflags,
                   KINEMATICS_INVERSE_FLAGS* iflags) {
  double q[5], w[5];
  *fflags = 0;
  *iflags = 0;
  pkm_exechon_home(&machine, *pins->tool_offset, q, w);
  for (int i = 0; i < 3; ++i) inverse_state.e[i] = forward_state.e[i] = machine.home_e[i];
  inverse_state.valid = forward_state.valid = 1;
  for (int i = 0; i < 5; ++i) last_world[i] = w[i];
  have_last_world = 1;
  joint[0] = q[0], joint[1] = q[1], joint[2] = q[2];
  joint[3] = q[3] * PKX_DEG_PER_RAD, joint[4] = q[4] * PKX_DEG_PER_RAD;
  world->tran.x = w[0], world->tran.y = w[1], world->tran.z = w[2];
  world->c = w[3] * PKX_DEG_PER_RAD, world->a = w[4] * PKX_DEG_PER_RAD, world->b = 0.0;
  world->u = world->v = world->w = 0.0;
  return 0;
}

KINEMATICS_TYPE kinematicsType(void) { return KINEMATICS_BOTH; }

KINS_NOT_SWITCHABLE
EXPORT_SYMBOL(kinematicsType);
EXPORT_SYMBOL(kinematicsForward);
EXPORT_SYMBOL(kinematicsInverse);
EXPORT_SYMBOL(kinematicsHome);

/* Reads the whole parameter file; NULL (with the reason logged) when it cannot be read. */
static char* pkx_read_file(const char* path) {
  FILE* f = fopen(path, "r");
  if (f == NULL) {
    rtapi_print_msg(RTAPI_MSG_ERR, "pkmexechonkins: cannot open params=%s\n", path);
    return NULL;
  }
  char* text = NULL;
  size_t size = 0, used = 0, n = 0;
  do {
    if (used + 4096 + 1 > size) {
      char* grown = realloc(text, size = used + 65536);
      if (grown == NULL) break;
      text = grown;
    }
    n = fread(text + used, 1, 4096, f);
    used += n;
  } while (n > 0);
  fclose(f);
  if (text != NULL) text[used] = '\0';
  return text;
}

static int pkx_load_params(void) {
  char why[256];
  if (params == NULL || params[0] == '\0') {
    rtapi_print_msg(RTAPI_MSG_ERR, "pkmexechonkins: give params=FILE (written by pkm)\n");
    return -1;
  }
  char* text = pkx_read_file(params);
  if (text == NULL) return -1;
  const int rc = pkm_exechon_parse_params(text, &machine, why, (int)sizeof why);
  free(text);
  if (rc != 0) rtapi_print_msg(RTAPI_MSG_ERR, "pkmexechonkins: %s: %s\n", params, why);
  return rc;
}

static int pkx_export_pins(void) {
  pins = hal_malloc(sizeof(pkx_pins));
  if (pins == NULL) return -1;
  int r = 0;
  r |= hal_pin_float_new("pkmexechonkins.tool-offset", HAL_IN, &pins->tool_offset, comp_id);
  r |= hal_pin_float_new(
      "pkmexechonkins.convergence-criterion", HAL_IO, &pins->convergence, comp_id);
  r |= hal_pin_u32_new("pkmexechonkins.limit-iterations", HAL_IO, &pins->limit_iterations, comp_id);
  r |= hal_pin_u32_new("pkmexechonkins.last-iterations", HAL_OUT, &pins->last_iterations, comp_id);
  r |= hal_pin_s32_new("pkmexechonkins.inv-status", HAL_OUT, &pins->inv_status, comp_id);
  r |= hal_pin_s32_new("pkmexechonkins.fwd-status", HAL_OUT, &pins->fwd_status, comp_id);
  r |= hal_pin_bit_new("pkmexechonkins.inv-kins-fail", HAL_OUT, &pins->inv_kins_fail, comp_id);
  r |= hal_pin_bit_new("pkmexechonkins.fwd-kins-fail", HAL_OUT, &pins->fwd_kins_fail, comp_id);
  r |= hal_pin_bit_new("pkmexechonkins.fault", HAL_OUT, &pins->fault, comp_id);
  r |= hal_pin_u32_new(
      "pkmexechonkins.fwd-kins-failures", HAL_OUT, &pins->fwd_kins_failures, comp_id);
  r |=
      hal_pin_u32_new("pkmexechonkins.startup-failures", HAL_OUT, &pins->startup_failures, comp_id);
  r |= hal_pin_u32_new("pkmexechonkins.last-call-ns", HAL_OUT, &pins->last_call_ns, comp_id);
  r |= hal_pin_u32_new("pkmexechonkins.max-call-ns", HAL_OUT, &pins->max_call_ns, comp_id);
  if (r != 0) return -1;
  *pins->tool_offset = 0.0;
  *pins->convergence = machine.fk_tolerance;
  *pins->limit_iterations = (hal_u32_t)machine.fk_max_iterations;
  *pins->last_iterations = 0;
  *pins->inv_status = *pins->fwd_status = 0;
  *pins->inv_kins_fail = *pins->fwd_kins_fail = *pins->fault = 0;
  *pins->fwd_kins_failures = *pins->startup_failures = 0;
  *pins->last_call_ns = *pins->max_call_ns = 0;
  return 0;
}

int rtapi_app_main(void) {
  comp_id = hal_init("pkmexechonkins");
  if (comp_id < 0) return comp_id;
  if (pkx_load_params() != 0 || pkx_export_pins() != 0) {
    hal_exit(comp_id);
    return -EINVAL; /* rtapi_app then says "Invalid argument", not EPERM's "not permitted" */
  }
  inverse_state.valid = forward_state.valid = 0;
  hal_ready(comp_id);
  return 0;
}

void rtapi_app_exit(void) { hal_exit(comp_id); }
