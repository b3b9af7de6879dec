/* pkmhexkins: a LinuxCNC kinematics module for hexapods with pkm's model (pkmhexkins_core.h),
 * the full 42-parameter calibrated geometry as HAL pins. Documentation: docs/linuxcnc.md,
 * "The pkmhexkins kinematics component". Joints 0-5 are the strut readings; world X Y Z A B C
 * is the TCP pose (A, B, C roll-pitch-yaw in degrees).
 *
 * Load: `loadrt pkmhexkins` (pins with the hexapod-sim defaults, set by `setp`), or
 * `loadrt pkmhexkins params=FILE` (the file pkm writes: the pins' initial values, read and checked
 * at load, so that a missing parameter or a geometry that does not assemble at home fails the
 * loadrt with the reason in LinuxCNC's log). The pins still take live changes. */
#include <math.h>
#include <string.h>

#include "hal.h"
#include "kinematics.h"
#include "pkmhexkins_core.h"
#include "rtapi.h"
#include "rtapi_app.h"

MODULE_LICENSE("Dual MIT/GPL");
MODULE_AUTHOR("pkm");
MODULE_DESCRIPTION("Hexapod kinematics with pkm's model and forward kinematics");

#define N PKM_HEX_STRUTS

static char* params = "";
RTAPI_MP_STRING(params, "pkm's pkmhexkins parameter file (geometry, tool, home, solver)");

static const double kDegPerRad = 180.0 / 3.14159265358979323846;

/* The HAL pins (in: geometry and solver settings; out: what the last FK did). */
typedef struct {
  hal_float_t* base[N][3];
  hal_float_t* platform[N][3];
  hal_float_t* length_offset[N];
  hal_float_t* tool[3];
  hal_float_t* spindle_offset;
  hal_float_t* tool_offset; /* G43 length, net to motion.tooloffset.z */
  hal_float_t* home[6];     /* the second FK seed: X Y Z A B C (degrees) */
  hal_float_t* convergence_criterion;
  hal_u32_t* limit_iterations;
  hal_float_t* max_error;
  hal_u32_t* last_iterations;
  hal_u32_t* max_iterations;
  hal_bit_t* fwd_kins_fail;
  hal_bit_t* geometry_ok;
  hal_u32_t* fwd_kins_failures;
} pins;

static pins* hal;
static int comp_id;
static pkm_hex_geometry validated; /* the geometry last found valid */
static int have_validated;
static int reported_invalid; /* the invalid geometry was reported once */

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

/* 0 when the pins' geometry is usable (validated when it changed; an error logged once). */
static int current_geometry(pkm_hex_geometry* g) {
  memset(g, 0, sizeof *g);
  read_geometry(g);
  if (have_validated && memcmp(g, &validated, sizeof *g) == 0) return 0;
  char why[128];
  if (pkm_hex_validate(g, why, sizeof why) != 0) {
    *hal->geometry_ok = 0;
    if (!reported_invalid)
      rtapi_print_msg(RTAPI_MSG_ERR, "pkmhexkins: unusable geometry: %s\n", why);
    reported_invalid = 1;
    return -1;
  }
  validated = *g;
  have_validated = 1;
  reported_invalid = 0;
  *hal->geometry_ok = 1;
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

/* FK from the seed (x y z a b c, degrees); 0 and the world pose on success. */
static int forward_from(const pkm_hex_geometry* g,
                        const double* joints,
                        const double seed[6],
                        EmcPose* world) {
  pkm_hex_fk_options o;
  pkm_hex_default_fk_options(&o);
  o.tolerance = *hal->convergence_criterion;
  o.max_iterations = (int)*hal->limit_iterations;
  o.max_error = *hal->max_error > 0.0 ? *hal->max_error : INFINITY;
  if (!(o.tolerance > 0.0) || o.max_iterations < 1) return -1;
  double p[3] = {seed[0], seed[1], seed[2]}, rpy[3], R[3][3];
  for (int k = 0; k < 3; ++k) rpy[k] = seed[3 + k] / kDegPerRad;
  pkm_hex_rotation_from_rpy(rpy, R);
  const pkm_hex_fk_summary s = pkm_hex_forward(g, joints, &o, p, R);
  *hal->last_iterations = (hal_u32_t)s.iterations;
  if ((hal_u32_t)s.iterations > *hal->max_iterations)
    *hal->max_iterations = (hal_u32_t)s.iterations;
  if (s.status != PKM_HEX_OK) return -1;
  pose_to_world(p, R, seed + 3, world);
  return 0;
}

int kinematicsForward(const double* joints,
                      EmcPose* world,
                      const KINEMATICS_FORWARD_FLAGS* fflags,
                      KINEMATICS_INVERSE_FLAGS* iflags) {
  (void)fflags;
  (void)iflags;
  pkm_hex_geometry g;
  if (current_geometry(&g) != 0) {
    *hal->fwd_kins_fail = 1;
    return -1;
  }
  const double previous[6] = {
      world->tran.x, world->tran.y, world->tran.z, world->a, world->b, world->c};
  double home[6];
  for (int k = 0; k < 6; ++k) home[k] = *hal->home[k];
  /* Seeded from the previous pose; after a failure from home, as pkm's kinematics paths do. */
  if (forward_from(&g, joints, previous, world) == 0 ||
      (memcmp(previous, home, sizeof home) != 0 && forward_from(&g, joints, home, world) == 0)) {
    *hal->fwd_kins_fail = 0;
    return 0;
  }
  *hal->fwd_kins_fail = 1;
  ++*hal->fwd_kins_failures;
  return -1;
}

int kinematicsInverse(const EmcPose* world,
                      double* joints,
                      const KINEMATICS_INVERSE_FLAGS* iflags,
                      KINEMATICS_FORWARD_FLAGS* fflags) {
  (void)iflags;
  (void)fflags;
  pkm_hex_geometry g;
  if (current_geometry(&g) != 0) return -1;
  const double p[3] = {world->tran.x, world->tran.y, world->tran.z};
  const double rpy[3] = {world->a / kDegPerRad, world->b / kDegPerRad, world->c / kDegPerRad};
  double R[3][3], q[N];
  pkm_hex_rotation_from_rpy(rpy, R);
  if (pkm_hex_inverse(&g, p, R, q) != 0) return -1;
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

/* A float pin named pkmhexkins.<name> with its default; 0 or a HAL error. */
static int float_pin(hal_float_t** pin, hal_pin_dir_t dir, double value, const char* name) {
  const int r = hal_pin_float_newf(dir, pin, comp_id, "pkmhexkins.%s", name);
  if (r == 0) **pin = value;
  return r;
}

static int u32_pin(hal_u32_t** pin, hal_pin_dir_t dir, hal_u32_t value, const char* name) {
  const int r = hal_pin_u32_newf(dir, pin, comp_id, "pkmhexkins.%s", name);
  if (r == 0) **pin = value;
  return r;
}

static int bit_pin(hal_bit_t** pin, hal_pin_dir_t dir, const char* name) {
  const int r = hal_pin_bit_newf(dir, pin, comp_id, "pkmhexkins.%s", name);
  if (r == 0) **pin = 0;
  return r;
}

/* base.N.x|y|z, platform.N.x|y|z, length-offset.N and tool.x|y|z, with the values of g. */
static int geometry_pins(const pkm_hex_geometry* g) {
  static const char axis[3] = {'x', 'y', 'z'};
  char name[48];
  int r = 0;
  for (int i = 0; i < N && r == 0; ++i) {
    for (int k = 0; k < 3 && r == 0; ++k) {
      rtapi_snprintf(name, sizeof name, "base.%d.%c", i, axis[k]);
      r = float_pin(&hal->base[i][k], HAL_IN, g->base[i][k], name);
      rtapi_snprintf(name, sizeof name, "platform.%d.%c", i, axis[k]);
      if (r == 0) r = float_pin(&hal->platform[i][k], HAL_IN, g->platform[i][k], name);
    }
    rtapi_snprintf(name, sizeof name, "length-offset.%d", i);
    if (r == 0) r = float_pin(&hal->length_offset[i], HAL_IN, g->length_offset[i], name);
  }
  for (int k = 0; k < 3 && r == 0; ++k) {
    rtapi_snprintf(name, sizeof name, "tool.%c", axis[k]);
    r = float_pin(&hal->tool[k], HAL_IN, g->tool[k], name);
  }
  return r;
}

/* Offsets, the home seed, the solver's settings (initial values from p) and its outputs. */
static int other_pins(const pkm_hex_params* p) {
  static const char* const home[6] = {"home.x", "home.y", "home.z", "home.a", "home.b", "home.c"};
  const pkm_hex_fk_options* o = &p->options;
  int r = float_pin(&hal->spindle_offset, HAL_IN, p->geometry.spindle_offset, "spindle-offset");
  if (r == 0) r = float_pin(&hal->tool_offset, HAL_IN, 0.0, "tool-offset");
  for (int k = 0; k < 6 && r == 0; ++k) r = float_pin(&hal->home[k], HAL_IN, p->home[k], home[k]);
  if (r == 0)
    r = float_pin(&hal->convergence_criterion, HAL_IN, o->tolerance, "convergence-criterion");
  if (r == 0)
    r = u32_pin(&hal->limit_iterations, HAL_IN, (hal_u32_t)o->max_iterations, "limit-iterations");
  if (r == 0)
    r = float_pin(&hal->max_error, HAL_IN, isinf(o->max_error) ? 0.0 : o->max_error, "max-error");
  if (r == 0) r = u32_pin(&hal->last_iterations, HAL_OUT, 0, "last-iterations");
  if (r == 0) r = u32_pin(&hal->max_iterations, HAL_OUT, 0, "max-iterations");
  if (r == 0) r = u32_pin(&hal->fwd_kins_failures, HAL_OUT, 0, "fwd-kins-failures");
  if (r == 0) r = bit_pin(&hal->fwd_kins_fail, HAL_OUT, "fwd-kins-fail");
  if (r == 0) r = bit_pin(&hal->geometry_ok, HAL_OUT, "geometry-ok");
  return r;
}

/* The pins' initial values: the parameter file's (read and checked here), or the hexapod-sim
 * defaults without one. 0, or −1 with the reason logged. */
static int initial_values(pkm_hex_params* p) {
  memset(p, 0, sizeof *p);
  if (params == NULL || params[0] == '\0') {
    pkm_hex_sim_geometry(&p->geometry);
    pkm_hex_default_fk_options(&p->options);
    return 0;
  }
  char why[256];
  if (pkm_hex_load_params(params, p, why, sizeof why) != 0) {
    rtapi_print_msg(RTAPI_MSG_ERR, "pkmhexkins: %s: %s\n", params, why);
    return -1;
  }
  rtapi_print_msg(RTAPI_MSG_INFO, "pkmhexkins: parameters from %s\n", params);
  return 0;
}

int rtapi_app_main(void) {
  pkm_hex_params p;
  if (initial_values(&p) != 0) return -1;
  comp_id = hal_init("pkmhexkins");
  if (comp_id < 0) return comp_id;
  hal = hal_malloc(sizeof(pins));
  int r = hal == NULL ? -1 : 0;
  if (r == 0) r = geometry_pins(&p.geometry);
  if (r == 0) r = other_pins(&p);
  if (r != 0) {
    rtapi_print_msg(RTAPI_MSG_ERR, "pkmhexkins: cannot create the HAL pins (%d)\n", r);
    hal_exit(comp_id);
    return -1;
  }
  hal_ready(comp_id);
  return 0;
}

void rtapi_app_exit(void) { hal_exit(comp_id); }
