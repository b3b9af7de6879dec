/* The Exechon kinematics of pkmexechonkins: inverse kinematics with the wrist readings held
 * (pkm's toolPointInverseKinematics), forward kinematics (pkm's tripodForwardKinematics and the
 * wrist), the condition number of dq/dS and the limits. Interface: pkmexechonkins_core.h. */
#include <math.h>
#include <stddef.h>

#include "pkmexechonkins_internal.h"

/* IK: Newton iterations and step halvings; convergence and rounding floor × the characteristic
 * length (the values of src/kinematics/exechon_wrist.cpp). */
#define PKX_IK_MAX_ITERATIONS 50
#define PKX_IK_MAX_HALVINGS 30
#define PKX_IK_TOLERANCE 1e-14
#define PKX_IK_FLOOR 1e-12
/* A leg shorter than this × the characteristic length is degenerate (pkm's checks). */
#define PKX_DEGENERATE_LEG 1e-9
#define PKX_TWO_PI 6.283185307179586476925286766559

const char* pkm_exechon_status_name(pkm_exechon_status status) {
  switch (status) {
    case PKM_EXECHON_OK:
      return "ok";
    case PKM_EXECHON_INVALID_INPUT:
      return "invalid_input";
    case PKM_EXECHON_SINGULAR:
      return "singular";
    case PKM_EXECHON_NO_CONVERGENCE:
      return "no_convergence";
    case PKM_EXECHON_OUT_OF_RANGE:
      return "out_of_range";
    case PKM_EXECHON_OTHER_BRANCH:
      return "other_branch";
    case PKM_EXECHON_BUDGET_EXHAUSTED:
      return "budget_exhausted";
  }
  return "unknown";
}

/* The tool offset v = L·W·Rz(θC)·Rx(θA)·ẑ in the platform frame for readings (c, a), rad. */
void pkx_tool_offset(const pkm_exechon_params* p, double c, double a, double L, double v[3]) {
  const double tc = p->c_sign * c + p->c0, ta = p->a_sign * a + p->a0;
  const double w[3] = {sin(tc) * sin(ta), -cos(tc) * sin(ta), cos(ta)};
  for (int i = 0; i < 3; ++i) v[i] = L * pkx_dot(p->wrist_frame + 3 * i, w);
}

static void pkx_zoppi_from_world(const pkm_exechon_params* p, const double w[3], double z[3]) {
  const double d[3] = {
      w[0] - p->world_p_zoppi[0], w[1] - p->world_p_zoppi[1], w[2] - p->world_p_zoppi[2]};
  for (int i = 0; i < 3; ++i) {
    const double col[3] = {p->world_R_zoppi[i], p->world_R_zoppi[3 + i], p->world_R_zoppi[6 + i]};
    z[i] = pkx_dot(col, d);
  }
}

void pkx_world_from_zoppi(const pkm_exechon_params* p, const double z[3], double w[3]) {
  for (int i = 0; i < 3; ++i) w[i] = pkx_dot(p->world_R_zoppi + 3 * i, z) + p->world_p_zoppi[i];
}

int pkx_all_finite(const double* x, int n) {
  for (int i = 0; i < n; ++i)
    if (!isfinite(x[i])) return 0;
  return 1;
}

static double pkx_norm(const double r[3]) { return sqrt(pkx_dot(r, r)); }

/* Eigenvalues of the symmetric 3×3 matrix a (row-major, overwritten) by cyclic Jacobi rotations. */
static void pkx_symmetric_eigenvalues(double a[9], double lambda[3]) {
  static const int pairs[3][2] = {{0, 1}, {0, 2}, {1, 2}};
  for (int sweep = 0; sweep < 60; ++sweep) {
    const double off = a[1] * a[1] + a[2] * a[2] + a[5] * a[5];
    const double diag = a[0] * a[0] + a[4] * a[4] + a[8] * a[8];
    if (!(off > 1e-36 * diag)) break;
    for (int k = 0; k < 3; ++k) {
      const int p = pairs[k][0], q = pairs[k][1];
      const double apq = a[3 * p + q];
      if (apq == 0.0) continue;
      const double theta = (a[3 * q + q] - a[3 * p + p]) / (2.0 * apq);
      const double t = isfinite(theta * theta)
                           ? (theta >= 0.0 ? 1.0 : -1.0) / (fabs(theta) + sqrt(theta * theta + 1.0))
                           : 0.5 / theta;
      const double c = 1.0 / sqrt(t * t + 1.0), s = t * c;
      for (int r = 0; r < 3; ++r) { /* columns p, q */
        const double arp = a[3 * r + p], arq = a[3 * r + q];
        a[3 * r + p] = c * arp - s * arq;
        a[3 * r + q] = s * arp + c * arq;
      }
      for (int r = 0; r < 3; ++r) { /* rows p, q */
        const double apr = a[3 * p + r], aqr = a[3 * q + r];
        a[3 * p + r] = c * apr - s * aqr;
        a[3 * q + r] = s * apr + c * aqr;
      }
    }
  }
  lambda[0] = a[0], lambda[1] = a[4], lambda[2] = a[8];
}

/* inv = m⁻¹ (row-major) by the adjugate; -1 when |det| <= 1e-12 · ‖m‖³ (pkm: singular dS/de). */
static int pkx_inverse3(const double m[9], double inv[9]) {
  const double c0 = m[4] * m[8] - m[5] * m[7], c1 = m[5] * m[6] - m[3] * m[8],
               c2 = m[3] * m[7] - m[4] * m[6];
  const double det = m[0] * c0 + m[1] * c1 + m[2] * c2;
  double n2 = 0.0;
  for (int i = 0; i < 9; ++i) n2 += m[i] * m[i];
  if (!isfinite(det) || !(fabs(det) > 1e-12 * n2 * sqrt(n2))) return -1;
  inv[0] = c0 / det, inv[3] = c1 / det, inv[6] = c2 / det;
  inv[1] = (m[2] * m[7] - m[1] * m[8]) / det, inv[4] = (m[0] * m[8] - m[2] * m[6]) / det;
  inv[7] = (m[1] * m[6] - m[0] * m[7]) / det, inv[2] = (m[1] * m[5] - m[2] * m[4]) / det;
  inv[5] = (m[2] * m[3] - m[0] * m[5]) / det, inv[8] = (m[0] * m[4] - m[1] * m[3]) / det;
  return 0;
}

double pkm_exechon_condition(const pkm_exechon_params* p, const double e[3]) {
  double lengths[3], J_q_e[9], J_S_e[9], inv[9], M[9], MtM[9], lambda[3], point[3];
  const double zero[3] = {0.0, 0.0, 0.0};
  const pkx_trig t = pkx_trig_of(e);
  if (pkm_exechon_leg_lengths(p, e, lengths, J_q_e) != 0) return HUGE_VAL;
  if (pkx_platform_point(p, &t, zero, point, J_S_e) != 0) return HUGE_VAL;
  if (pkx_inverse3(J_S_e, inv) != 0) return HUGE_VAL;
  for (int i = 0; i < 3; ++i) /* M = J_q_S = J_q_e · J_S_e⁻¹ */
    for (int j = 0; j < 3; ++j)
      M[3 * i + j] =
          J_q_e[3 * i] * inv[j] + J_q_e[3 * i + 1] * inv[3 + j] + J_q_e[3 * i + 2] * inv[6 + j];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      MtM[3 * i + j] = M[i] * M[j] + M[3 + i] * M[3 + j] + M[6 + i] * M[6 + j];
  pkx_symmetric_eigenvalues(MtM, lambda);
  const double lmax = fmax(lambda[0], fmax(lambda[1], lambda[2]));
  const double lmin = fmin(lambda[0], fmin(lambda[1], lambda[2]));
  if (!isfinite(lmax) || !(lmin > 0.0)) return HUGE_VAL;
  return sqrt(lmax / lmin);
}

/* Solves J·x = −r (J row-major) by Cramer's rule, as src/kinematics/exechon_wrist.cpp; -1 when
 * singular. */
static int pkx_newton_step(const double J[9], const double r[3], double step[3]) {
  const double c0[3] = {J[0], J[3], J[6]}, c1[3] = {J[1], J[4], J[7]}, c2[3] = {J[2], J[5], J[8]};
  double j12[3], x[3];
  pkx_cross(c1, c2, j12);
  const double det = pkx_dot(c0, j12);
  if (!(fabs(det) > 0.0) || !isfinite(det)) return -1;
  step[0] = -pkx_dot(r, j12) / det;
  pkx_cross(r, c2, x);
  step[1] = -pkx_dot(c0, x) / det;
  pkx_cross(c1, r, x);
  step[2] = -pkx_dot(c0, x) / det;
  return 0;
}

/* Newton on e for S(e) + R(e)·v = target (Zoppi frame) from e (updated in place). */
static pkm_exechon_status pkx_solve_point(const pkm_exechon_params* p,
                                          const double target[3],
                                          const double v[3],
                                          double e[3]) {
  const double tol = PKX_IK_TOLERANCE * p->characteristic_length;
  const double floor_ = PKX_IK_FLOOR * p->characteristic_length;
  double point[3], r[3], J[9], step[3], trial[3], trial_point[3];
  pkx_trig t = pkx_trig_of(e);
  if (pkx_platform_point(p, &t, v, point, NULL) != 0) return PKM_EXECHON_SINGULAR;
  double last = HUGE_VAL;
  for (int it = 0;; ++it) {
    for (int i = 0; i < 3; ++i) r[i] = point[i] - target[i];
    const double err = pkx_norm(r);
    if (err <= tol || (err <= floor_ && err >= last)) return PKM_EXECHON_OK;
    if (it == PKX_IK_MAX_ITERATIONS) return PKM_EXECHON_NO_CONVERGENCE;
    if (pkx_platform_point(p, &t, v, trial_point, J) != 0) return PKM_EXECHON_SINGULAR;
    if (pkx_newton_step(J, r, step) != 0) return PKM_EXECHON_SINGULAR;
    for (int halving = 0;; ++halving) {
      for (int i = 0; i < 3; ++i) trial[i] = e[i] + step[i];
      const pkx_trig trial_t = pkx_trig_of(trial);
      if (pkx_platform_point(p, &trial_t, v, trial_point, NULL) == 0) {
        double d[3];
        for (int i = 0; i < 3; ++i) d[i] = trial_point[i] - target[i];
        if (pkx_norm(d) < err || pkx_norm(d) <= floor_) {
          for (int i = 0; i < 3; ++i) e[i] = trial[i], point[i] = trial_point[i];
          t = trial_t;
          break;
        }
      }
      if (halving == PKX_IK_MAX_HALVINGS) return PKM_EXECHON_NO_CONVERGENCE;
      for (int i = 0; i < 3; ++i) step[i] *= 0.5;
    }
    last = err;
  }
}

static int pkx_outside(const double range[2], double x) { return x < range[0] || x > range[1]; }

/* The limits of a solved configuration: strokes, degenerate legs, alpha, beta, C, A, then the
 * condition number (pkm's check order). */
static pkm_exechon_status pkx_check(const pkm_exechon_params* p,
                                    const double e[3],
                                    const double lengths[3],
                                    const double joints[5]) {
  for (int i = 0; i < 3; ++i) {
    if (joints[i] < p->stroke_min[i] || joints[i] > p->stroke_max[i])
      return PKM_EXECHON_OUT_OF_RANGE;
    if (!(lengths[i] > PKX_DEGENERATE_LEG * p->characteristic_length))
      return PKM_EXECHON_OUT_OF_RANGE;
  }
  if (pkx_outside(p->alpha_range, e[0]) || pkx_outside(p->beta_range, e[1]) ||
      pkx_outside(p->c_range, joints[3]) || pkx_outside(p->a_range, joints[4]))
    return PKM_EXECHON_OUT_OF_RANGE;
  if (!(pkm_exechon_condition(p, e) <= p->max_condition)) return PKM_EXECHON_SINGULAR;
  return PKM_EXECHON_OK;
}

int pkm_exechon_branch(const pkm_exechon_params* p, const double e[3]) {
  double lengths[3], J[9];
  if (pkm_exechon_leg_lengths(p, e, lengths, J) != 0 || !pkx_all_finite(J, 9)) return 0;
  const double det = J[0] * (J[4] * J[8] - J[5] * J[7]) - J[1] * (J[3] * J[8] - J[5] * J[6]) +
                     J[2] * (J[3] * J[7] - J[4] * J[6]);
  return det > 0.0 ? 1 : det < 0.0 ? -1 : 0;
}

/* e of the tool point `world` (x, y, z, C, A) from `start` (Newton; no limits), wrapped. */
static pkm_exechon_status pkx_solve_world(const pkm_exechon_params* p,
                                          const double world[5],
                                          double extra_tool_length,
                                          const double start[3],
                                          double e[3]) {
  if (!pkx_all_finite(world, 5) || !isfinite(extra_tool_length)) return PKM_EXECHON_INVALID_INPUT;
  double v[3], target[3];
  for (int i = 0; i < 3; ++i) e[i] = start[i];
  if (!pkx_all_finite(e, 3)) return PKM_EXECHON_INVALID_INPUT;
  pkx_tool_offset(p, world[3], world[4], p->tool_length + extra_tool_length, v);
  pkx_zoppi_from_world(p, world, target);
  const pkm_exechon_status solved = pkx_solve_point(p, target, v, e);
  e[0] = remainder(e[0], PKX_TWO_PI);
  e[1] = remainder(e[1], PKX_TWO_PI);
  return solved;
}

pkm_exechon_status pkm_exechon_seed(const pkm_exechon_params* p,
                                    const double world[5],
                                    double extra_tool_length,
                                    pkm_exechon_state* state) {
  double e[3];
  const pkm_exechon_status s = pkx_solve_world(p, world, extra_tool_length, p->home_e, e);
  if (s != PKM_EXECHON_OK) return s;
  if (pkm_exechon_branch(p, e) != p->branch) return PKM_EXECHON_OTHER_BRANCH;
  for (int i = 0; i < 3; ++i) state->e[i] = e[i];
  state->valid = 1;
  return PKM_EXECHON_OK;
}

pkm_exechon_status pkm_exechon_inverse(const pkm_exechon_params* p,
                                       pkm_exechon_state* state,
                                       const double world[5],
                                       double extra_tool_length,
                                       double joints[5]) {
  double e[3], lengths[3], out[5];
  const double* start = state->valid ? state->e : p->home_e;
  const pkm_exechon_status solved = pkx_solve_world(p, world, extra_tool_length, start, e);
  if (solved != PKM_EXECHON_OK) return solved;
  if (pkm_exechon_leg_lengths(p, e, lengths, NULL) != 0 || !pkx_all_finite(lengths, 3))
    return PKM_EXECHON_SINGULAR;
  if (pkm_exechon_branch(p, e) != p->branch) return PKM_EXECHON_OTHER_BRANCH;
  for (int i = 0; i < 3; ++i) out[i] = lengths[i] - p->length_offset[i];
  out[3] = world[3];
  out[4] = world[4];
  for (int i = 0; i < 5; ++i) joints[i] = out[i];
  const pkm_exechon_status checked = pkx_check(p, e, lengths, out);
  if (checked != PKM_EXECHON_OK) return checked; /* a rejected pose does not move the seed */
  for (int i = 0; i < 3; ++i) state->e[i] = e[i];
  state->valid = 1;
  return PKM_EXECHON_OK;
}
