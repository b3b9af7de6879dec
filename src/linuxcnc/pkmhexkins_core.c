/* Hexapod kinematics in plain C: pkm's model and forward-kinematics algorithm (see the header). */
#include "pkmhexkins_core.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define N PKM_HEX_STRUTS
#include "pkmhexkins_internal.h"

static const double kPi = 3.14159265358979323846;

const char* pkm_hex_status_name(pkm_hex_status status) {
  switch (status) {
    case PKM_HEX_OK:
      return "ok";
    case PKM_HEX_NO_CONVERGENCE:
      return "no_convergence";
    case PKM_HEX_SINGULAR:
      return "singular";
    case PKM_HEX_INVALID_INPUT:
      return "invalid_input";
    case PKM_HEX_OTHER_BRANCH:
      return "other_branch";
    case PKM_HEX_BUDGET_EXHAUSTED:
      return "budget_exhausted";
  }
  return "unknown";
}

void pkm_hex_default_fk_options(pkm_hex_fk_options* o) {
  o->tolerance = 1e-9;
  o->max_iterations = 120;
  o->max_backtracks = 12;
  o->singular_pivot_ratio = 1e-12;
  o->max_step_translation = 0.5;
  o->max_step_rotation = 0.25;
  o->continuation_step = 0.3;
  o->max_error = INFINITY;
  o->max_total_iterations = 0;
  o->branch = 0;
}

void pkm_hex_sim_geometry(pkm_hex_geometry* g) {
  static const double base[N][3] = {{-22.950, 13.250, 0.0},
                                    {22.950, 13.250, 0.0},
                                    {22.950, 13.250, 0.0},
                                    {0.0, -26.500, 0.0},
                                    {0.0, -26.500, 0.0},
                                    {-22.950, 13.250, 0.0}};
  static const double platform[N][3] = {{-1.000, 11.500, 0.0},
                                        {1.000, 11.500, 0.0},
                                        {10.459, -4.884, 0.0},
                                        {9.459, -6.616, 0.0},
                                        {-9.459, -6.616, 0.0},
                                        {-10.459, -4.884, 0.0}};
  memset(g, 0, sizeof *g);
  memcpy(g->base, base, sizeof base);
  memcpy(g->platform, platform, sizeof platform);
}

double pkm_hex_characteristic_length(const pkm_hex_geometry* g) {
  double sum = 0.0;
  for (int i = 0; i < N; ++i) sum += norm3(g->platform[i]);
  const double mean = sum / N;
  return mean > 0.0 ? mean : 1.0;
}

static int same_point(const double* a, const double* b) {
  return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
}

int pkm_hex_validate(const pkm_hex_geometry* g, char* why, size_t size) {
  if (!all_finite(&g->base[0][0], 3 * N) || !all_finite(&g->platform[0][0], 3 * N) ||
      !all_finite(g->length_offset, N) || !all_finite(g->tool, 3) || !isfinite(g->spindle_offset)) {
    if (why != NULL) snprintf(why, size, "a geometry value is not finite");
    return -1;
  }
  /* Joints may be shared (a 6-3 hexapod), but two struts with both ends in common are one. */
  for (int i = 0; i < N; ++i)
    for (int j = i + 1; j < N; ++j)
      if (same_point(g->base[i], g->base[j]) && same_point(g->platform[i], g->platform[j])) {
        if (why != NULL) snprintf(why, size, "struts %d and %d join the same joints", i, j);
        return -1;
      }
  return 0;
}

void pkm_hex_rotation_from_rpy(const double rpy[3], double R[3][3]) {
  const double sa = sin(rpy[0]), ca = cos(rpy[0]);
  const double sb = sin(rpy[1]), cb = cos(rpy[1]);
  const double sc = sin(rpy[2]), cc = cos(rpy[2]);
  R[0][0] = cc * cb;
  R[0][1] = cc * sb * sa - sc * ca;
  R[0][2] = cc * sb * ca + sc * sa;
  R[1][0] = sc * cb;
  R[1][1] = sc * sb * sa + cc * ca;
  R[1][2] = sc * sb * ca - cc * sa;
  R[2][0] = -sb;
  R[2][1] = cb * sa;
  R[2][2] = cb * ca;
}

/* `angle` shifted by whole turns to lie within pi of `target`. */
static double nearest_equivalent(double angle, double target) {
  return angle + 2.0 * kPi * round((target - angle) / (2.0 * kPi));
}

void pkm_hex_rpy_from_rotation(const double R[3][3], const double near[3], double rpy[3]) {
  const double cb = hypot(R[0][0], R[1][0]);
  double first[3];
  first[1] = atan2(-R[2][0], cb);
  if (cb < 1e-12) { /* gimbal lock: only c − a or c + a is defined; all of it goes into c */
    first[0] = 0.0;
    first[2] = atan2(-R[0][1], R[1][1]);
  } else {
    first[0] = atan2(R[2][1], R[2][2]);
    first[2] = atan2(R[1][0], R[0][0]);
  }
  const double second[3] = {first[0] + kPi, kPi - first[1], first[2] + kPi};
  const double* candidates[2] = {first, second};
  double best_distance = INFINITY;
  for (int k = 0; k < 2; ++k) {
    double shifted[3], d = 0.0;
    for (int i = 0; i < 3; ++i) {
      shifted[i] = nearest_equivalent(candidates[k][i], near[i]);
      d += (shifted[i] - near[i]) * (shifted[i] - near[i]);
    }
    if (d < best_distance) {
      best_distance = d;
      memcpy(rpy, shifted, sizeof shifted);
    }
  }
}

int pkm_hex_inverse(const pkm_hex_geometry* g,
                    const double p[3],
                    const double R[3][3],
                    double q[N]) {
  double base[N][3], platform[N][3];
  legs at;
  effective_joints(g, base, platform);
  compute_legs(&base[0][0], &platform[0][0], g->length_offset, p, &R[0][0], &at);
  memcpy(q, at.q, sizeof at.q);
  return all_finite(p, 3) && all_finite(&R[0][0], 9) && all_finite(q, N) ? 0 : -1;
}

int pkm_hex_check_home(const pkm_hex_geometry* g,
                       const double p[3],
                       const double rpy[3],
                       double singular_pivot_ratio,
                       char* why,
                       size_t size) {
  if (pkm_hex_validate(g, why, size) != 0) return -1;
  if (!all_finite(p, 3) || !all_finite(rpy, 3)) {
    if (why != NULL) snprintf(why, size, "the home pose is not finite");
    return -1;
  }
  double R[3][3];
  pkm_hex_rotation_from_rpy(rpy, R);
  double scale = 0.0;
  for (int i = 0; i < N; ++i) scale = fmax(scale, fmax(norm3(g->base[i]), norm3(g->platform[i])));
  if (!(scale > 0.0)) {
    if (why != NULL) snprintf(why, size, "all joint centres are at the origin");
    return -1;
  }
  double base[N][3], platform[N][3];
  legs at;
  effective_joints(g, base, platform);
  compute_legs(&base[0][0], &platform[0][0], g->length_offset, p, &R[0][0], &at);
  for (int i = 0; i < N; ++i)
    if (!(at.q[i] + g->length_offset[i] > 1e-9 * scale)) {
      if (why != NULL) snprintf(why, size, "strut %d has zero length at the home pose", i);
      return -1;
    }
  double J[N][N];
  lu6 lu;
  int sign = 0;
  scaled_jacobian(&at, 1.0 / pkm_hex_characteristic_length(g), J);
  const double ratio = factor6((const double(*)[N])J, &lu, &sign);
  if (!(ratio > singular_pivot_ratio)) {
    if (why != NULL)
      snprintf(why,
               size,
               "the geometry is singular at the home pose (Jacobian pivot ratio %.3g): check for "
               "coincident or collinear joints",
               ratio);
    return -1;
  }
  return 0;
}

int pkm_hex_branch(const pkm_hex_geometry* g,
                   const double p[3],
                   const double R[3][3],
                   double singular_pivot_ratio) {
  if (!all_finite(p, 3) || !all_finite(&R[0][0], 9)) return 0;
  double base[N][3], platform[N][3], J[N][N];
  legs at;
  lu6 lu;
  int sign = 0;
  effective_joints(g, base, platform);
  compute_legs(&base[0][0], &platform[0][0], g->length_offset, p, &R[0][0], &at);
  scaled_jacobian(&at, 1.0 / pkm_hex_characteristic_length(g), J);
  const double ratio = factor6((const double(*)[N])J, &lu, &sign);
  return ratio > singular_pivot_ratio ? sign : 0;
}
