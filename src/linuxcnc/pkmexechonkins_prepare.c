/* pkm_exechon_prepare: the checks of ExechonModel::validate() on the plain parameters, and the
 * derived wrist frame and characteristic length. */
#include <math.h>
#include <stdio.h>

#include "pkmexechonkins_internal.h"

static int pkx_fail(char* why, int why_size, const char* message) {
  snprintf(why, (size_t)why_size, "%s", message);
  return -1;
}

static int pkx_is_sign(int s) { return s == 1 || s == -1; }

static int pkx_range_ok(const double r[2]) { return !isnan(r[0]) && !isnan(r[1]) && r[0] <= r[1]; }

/* W = [x̂, ĉ × x̂, ĉ] (row-major) from c_axis and a_axis; -1 unless non-zero and perpendicular. */
static int pkx_wrist_frame(pkm_exechon_params* p) {
  const double nc = sqrt(pkx_dot(p->c_axis, p->c_axis)), na = sqrt(pkx_dot(p->a_axis, p->a_axis));
  if (!(nc > 1e-12) || !(na > 1e-12)) return -1;
  double c[3], x[3], y[3];
  for (int i = 0; i < 3; ++i) c[i] = p->c_axis[i] / nc;
  const double ca = pkx_dot(c, p->a_axis) / na;
  if (!(fabs(ca) < 1e-9)) return -1;
  for (int i = 0; i < 3; ++i) x[i] = p->a_axis[i] - pkx_dot(p->a_axis, c) * c[i];
  const double nx = sqrt(pkx_dot(x, x));
  for (int i = 0; i < 3; ++i) x[i] /= nx;
  pkx_cross(c, x, y);
  for (int i = 0; i < 3; ++i) {
    p->wrist_frame[3 * i + 0] = x[i];
    p->wrist_frame[3 * i + 1] = y[i];
    p->wrist_frame[3 * i + 2] = c[i];
  }
  return 0;
}

/* 0 when world_R_zoppi is a rotation (RᵀR = I to 1e-9, det > 0). */
static int pkx_rotation_ok(const double R[9]) {
  double err = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double d = R[i] * R[j] + R[3 + i] * R[3 + j] + R[6 + i] * R[6 + j] - (i == j);
      err += d * d;
    }
  const double det = R[0] * (R[4] * R[8] - R[5] * R[7]) - R[1] * (R[3] * R[8] - R[5] * R[6]) +
                     R[2] * (R[3] * R[7] - R[4] * R[6]);
  return sqrt(err) < 1e-9 && det > 0.0 ? 0 : -1;
}

static int pkx_check_numbers(const pkm_exechon_params* p, char* why, int why_size) {
  const double tripod[] = {p->dA,
                           p->dB,
                           p->dC,
                           p->l12A,
                           p->l12C,
                           p->l12B,
                           p->l23B,
                           p->pA,
                           p->pB,
                           p->pC,
                           p->hA,
                           p->hC,
                           p->hx,
                           p->hz};
  if (!pkx_all_finite(tripod, 14)) return pkx_fail(why, why_size, "tripod geometry is not finite");
  if (!pkx_is_sign(p->delta1B) || !pkx_is_sign(p->delta2B) || !pkx_is_sign(p->deltaA) ||
      !pkx_is_sign(p->deltaC))
    return pkx_fail(
        why, why_size, "branch signs delta1B, delta2B, deltaA, deltaC must be +1 or -1");
  if (!pkx_all_finite(p->length_offset, 3))
    return pkx_fail(why, why_size, "length_offset not finite");
  for (int i = 0; i < 3; ++i)
    if (isnan(p->stroke_min[i]) || isnan(p->stroke_max[i]) || p->stroke_min[i] > p->stroke_max[i])
      return pkx_fail(why, why_size, "a leg stroke [stroke_min, stroke_max] is empty");
  if (!pkx_range_ok(p->alpha_range) || !pkx_range_ok(p->beta_range) || !pkx_range_ok(p->c_range) ||
      !pkx_range_ok(p->a_range))
    return pkx_fail(why, why_size, "an angle range (alpha, beta, c, a) is empty");
  const double wrist[] = {p->c0, p->a0, p->tool_length};
  if (!pkx_all_finite(wrist, 3) || !pkx_is_sign(p->c_sign) || !pkx_is_sign(p->a_sign))
    return pkx_fail(why, why_size, "wrist: c0, a0, tool_length finite, c_sign, a_sign +1 or -1");
  if (!pkx_all_finite(p->world_R_zoppi, 9) || !pkx_all_finite(p->world_p_zoppi, 3) ||
      pkx_rotation_ok(p->world_R_zoppi) != 0)
    return pkx_fail(why, why_size, "world_R_zoppi must be a rotation and world_p_zoppi finite");
  if (!(p->max_condition > 1.0)) return pkx_fail(why, why_size, "max_condition must be > 1");
  if (!(p->fk_tolerance > 0.0) || p->fk_max_iterations < 1 || p->fk_max_backtracks < 0 ||
      !(p->fk_singular_pivot_ratio >= 0.0))
    return pkx_fail(why, why_size, "fk_tolerance > 0, fk_max_iterations >= 1 and so on");
  if (p->fk_max_iterations > PKM_EXECHON_MAX_ITERATIONS ||
      p->fk_max_backtracks > PKM_EXECHON_MAX_BACKTRACKS)
    return pkx_fail(why,
                    why_size,
                    "fk_max_iterations <= 120 and fk_max_backtracks <= 30 (the servo-time budget)");
  return 0;
}

int pkm_exechon_prepare(pkm_exechon_params* p, char* why, int why_size) {
  if (pkx_check_numbers(p, why, why_size) != 0) return -1;
  const double L = fmax(fabs(p->dA), fmax(fabs(p->dB), fabs(p->dC)));
  p->characteristic_length = L > 0.0 ? L : 1.0;
  if (!(fabs(p->dB) > 1e-9 * p->characteristic_length))
    return pkx_fail(why, why_size, "tripod: dB must be != 0");
  if (!(fabs(p->dA - p->dC) > 1e-9 * p->characteristic_length))
    return pkx_fail(why, why_size, "tripod: dA and dC must differ");
  if (pkx_wrist_frame(p) != 0)
    return pkx_fail(why, why_size, "wrist: c_axis and a_axis must be non-zero and perpendicular");
  const double home[] = {p->home_e[0], p->home_e[1], p->home_e[2], p->home_c, p->home_a};
  if (!pkx_all_finite(home, 5)) return pkx_fail(why, why_size, "home is not finite");
  double lengths[3];
  if (pkm_exechon_leg_lengths(p, p->home_e, lengths, NULL) != 0 || !pkx_all_finite(lengths, 3))
    return pkx_fail(why, why_size, "the tripod does not assemble at the home configuration");
  for (int i = 0; i < 3; ++i)
    if (!(lengths[i] > 1e-9 * p->characteristic_length))
      return pkx_fail(why, why_size, "a leg has zero length at the home configuration");
  const double cond = pkm_exechon_condition(p, p->home_e);
  if (!(cond < 1e12)) return pkx_fail(why, why_size, "the tripod is singular at home");
  p->branch = pkm_exechon_branch(p, p->home_e);
  if (p->branch == 0) return pkx_fail(why, why_size, "the tripod is singular at home");
  return 0;
}
