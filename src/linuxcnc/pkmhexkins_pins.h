/* The HAL pins of the pkmhexkins module (included by pkmhexkins.c alone, after hal.h and its
 * `comp_id`): the struct and their creation with initial values. Names: docs/linuxcnc.md,
 * "Pins". */
#ifndef PKM_HEXKINS_PINS_H
#define PKM_HEXKINS_PINS_H

/* The HAL pins (in: geometry and solver settings; out: what the last FK did). */
typedef struct {
  hal_float_t* base[N][3];
  hal_float_t* platform[N][3];
  hal_float_t* length_offset[N];
  hal_float_t* tool[3];
  hal_float_t* spindle_offset;
  hal_float_t* tool_offset; /* G43 length, net to motion.tooloffset.z */
  hal_float_t* home[6];     /* the branch reference (and [TRAJ] HOME): X Y Z A B C (degrees) */
  hal_float_t* convergence_criterion;
  hal_u32_t* limit_iterations;
  hal_float_t* max_error;
  hal_bit_t* in_position;       /* in: geometry changes are taken only while true and still */
  hal_bit_t* hold;              /* in: while true, pin changes wait (set many pins as one) */
  hal_float_t* still_tolerance; /* in: joints moving less than this per call are still */
  hal_u32_t* last_iterations;
  hal_u32_t* max_iterations;
  hal_u32_t* last_call_ns; /* out: time of the last forward-kinematics call */
  hal_u32_t* max_call_ns;  /* out: longest forward-kinematics call since load */
  hal_s32_t* fwd_status;   /* out: pkm_hex_status of the last forward call */
  hal_bit_t* fwd_kins_fail;
  hal_bit_t* inv_kins_fail;
  hal_u32_t* branch_errors; /* out: FK or IK calls that met the other assembly branch */
  hal_bit_t* geometry_ok;
  hal_bit_t* fault; /* out: net to E-stop (docs/linuxcnc.md) */
  hal_u32_t* fwd_kins_failures;
  hal_u32_t* startup_failures; /* failed calls before the first success (joints before homing) */
} pins;

static pins* hal;
static int comp_id;
static pins* hal;

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

static int s32_pin(hal_s32_t** pin, hal_pin_dir_t dir, const char* name) {
  const int r = hal_pin_s32_newf(dir, pin, comp_id, "pkmhexkins.%s", name);
  if (r == 0) **pin = 0;
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
  if (r == 0) r = float_pin(&hal->still_tolerance, HAL_IN, 0.0, "still-tolerance");
  if (r == 0) r = bit_pin(&hal->in_position, HAL_IN, "in-position");
  if (r == 0) *hal->in_position = 1;
  if (r == 0) r = bit_pin(&hal->hold, HAL_IN, "hold");
  if (r == 0) r = u32_pin(&hal->last_iterations, HAL_OUT, 0, "last-iterations");
  if (r == 0) r = u32_pin(&hal->max_iterations, HAL_OUT, 0, "max-iterations");
  if (r == 0) r = u32_pin(&hal->last_call_ns, HAL_OUT, 0, "last-call-ns");
  if (r == 0) r = u32_pin(&hal->max_call_ns, HAL_OUT, 0, "max-call-ns");
  if (r == 0) r = u32_pin(&hal->fwd_kins_failures, HAL_OUT, 0, "fwd-kins-failures");
  if (r == 0) r = u32_pin(&hal->startup_failures, HAL_OUT, 0, "startup-failures");
  if (r == 0) r = s32_pin(&hal->fwd_status, HAL_OUT, "fwd-status");
  if (r == 0) r = bit_pin(&hal->fwd_kins_fail, HAL_OUT, "fwd-kins-fail");
  if (r == 0) r = bit_pin(&hal->inv_kins_fail, HAL_OUT, "inv-kins-fail");
  if (r == 0) r = u32_pin(&hal->branch_errors, HAL_OUT, 0, "branch-errors");
  if (r == 0) r = bit_pin(&hal->geometry_ok, HAL_OUT, "geometry-ok");
  if (r == 0) r = bit_pin(&hal->fault, HAL_OUT, "fault");
  return r;
}

#endif /* PKM_HEXKINS_PINS_H */
