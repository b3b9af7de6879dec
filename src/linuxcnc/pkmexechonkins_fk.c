/* Forward kinematics and home of pkmexechonkins: pkm's damped Newton on e for the leg readings
 * (src/kinematics/detail/newton.hpp with exechon_fk.cpp's scaled LU), then the wrist. */
#include <math.h>
#include <stddef.h>

#include "pkmexechonkins_internal.h"

#define PKX_FK_POLISH_FRACTION 1e-3 /* no polishing step below this fraction of the tolerance */
#define PKX_FK_TWO_PI 6.283185307179586476925286766559

/* Residual r = lengths(e) − target, J = d(lengths)/de; returns |r|² (HUGE_VAL if not finite). */
static double pkx_fk_evaluate(const pkm_exechon_params* p,
                              const double e[3],
                              const double target[3],
                              double r[3],
                              double J[9]) {
  double lengths[3];
  if (pkm_exechon_leg_lengths(p, e, lengths, J) != 0) return HUGE_VAL;
  for (int i = 0; i < 3; ++i) r[i] = lengths[i] - target[i];
  const double n2 = pkx_dot(r, r);
  return isfinite(n2) ? n2 : HUGE_VAL;
}

/* delta ← J⁻¹·delta by LU with partial pivoting on J with its angular columns × 1/L (a unit-free
 * pivot test); returns the smallest/largest |pivot| (0: singular, delta untouched). */
static double pkx_fk_solve(const double J[9], double L, double delta[3]) {
  double a[9], b[3] = {delta[0], delta[1], delta[2]}, pmin = HUGE_VAL, pmax = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) a[3 * i + j] = j < 2 ? J[3 * i + j] / L : J[3 * i + j];
  for (int k = 0; k < 3; ++k) {
    int piv = k;
    for (int i = k + 1; i < 3; ++i)
      if (fabs(a[3 * i + k]) > fabs(a[3 * piv + k])) piv = i;
    for (int j = 0; j < 3 && piv != k; ++j) {
      const double x = a[3 * k + j];
      a[3 * k + j] = a[3 * piv + j], a[3 * piv + j] = x;
    }
    const double x = b[k];
    b[k] = b[piv], b[piv] = x;
    const double pk = fabs(a[3 * k + k]);
    pmin = fmin(pmin, pk), pmax = fmax(pmax, pk);
    if (a[3 * k + k] == 0.0) continue;
    for (int i = k + 1; i < 3; ++i) {
      const double f = a[3 * i + k] / a[3 * k + k];
      for (int j = k; j < 3; ++j) a[3 * i + j] -= f * a[3 * k + j];
      b[i] -= f * b[k];
    }
  }
  const double ratio = pmax > 0.0 ? pmin / pmax : 0.0;
  if (!(ratio > 0.0)) return 0.0;
  for (int i = 2; i >= 0; --i) {
    double s = b[i];
    for (int j = i + 1; j < 3; ++j) s -= a[3 * i + j] * b[j];
    b[i] = s / a[3 * i + i];
  }
  delta[0] = b[0] / L, delta[1] = b[1] / L, delta[2] = b[2];
  return ratio;
}

static double pkx_max_abs(const double r[3]) {
  return fmax(fabs(r[0]), fmax(fabs(r[1]), fabs(r[2])));
}

/* pkm's dampedNewton: convergence on the largest leg residual, one polishing step, step halving. */
static pkm_exechon_status pkx_fk_newton(const pkm_exechon_params* p,
                                        const double target[3],
                                        double x[3],
                                        int* iterations) {
  double r[3], J[9], x_try[3], r_try[3], J_try[9], delta[3];
  double norm2 = pkx_fk_evaluate(p, x, target, r, J);
  pkm_exechon_status status = PKM_EXECHON_NO_CONVERGENCE;
  int polishing = 0;
  *iterations = 0;
  for (int iter = 0;; ++iter) {
    const double max_r = pkx_max_abs(r);
    if (!isfinite(norm2)) return PKM_EXECHON_NO_CONVERGENCE;
    if (max_r <= p->fk_tolerance) {
      status = PKM_EXECHON_OK;
      if (polishing || max_r <= PKX_FK_POLISH_FRACTION * p->fk_tolerance ||
          iter == p->fk_max_iterations)
        return status;
      polishing = 1;
    }
    if (iter == p->fk_max_iterations) return polishing ? status : PKM_EXECHON_BUDGET_EXHAUSTED;
    for (int i = 0; i < 3; ++i) delta[i] = r[i];
    const double ratio = pkx_fk_solve(J, p->characteristic_length, delta);
    if (!(ratio > p->fk_singular_pivot_ratio) || !pkx_all_finite(delta, 3))
      return PKM_EXECHON_SINGULAR;
    double step = 1.0;
    int accepted = 0;
    for (int k = 0; k <= p->fk_max_backtracks && !accepted; ++k) {
      for (int i = 0; i < 3; ++i) x_try[i] = x[i] - step * delta[i];
      const double n2 = pkx_fk_evaluate(p, x_try, target, r_try, J_try);
      if (n2 < norm2 || (!polishing && pkx_max_abs(r_try) <= p->fk_tolerance)) {
        accepted = 1;
        norm2 = n2;
      }
      step *= 0.5;
    }
    ++*iterations;
    if (!accepted) return polishing ? status : PKM_EXECHON_NO_CONVERGENCE;
    for (int i = 0; i < 3; ++i) x[i] = x_try[i], r[i] = r_try[i];
    for (int i = 0; i < 9; ++i) J[i] = J_try[i];
    if (polishing) return status;
  }
}

/* world = (tool point, C, A) of the configuration (e, c, a). -1 when leg B's solve fails. */
static int pkx_tool_pose(
    const pkm_exechon_params* p, const double e[3], double c, double a, double L, double world[5]) {
  double v[3], z[3];
  const pkx_trig t = pkx_trig_of(e);
  pkx_tool_offset(p, c, a, L, v);
  if (pkx_platform_point(p, &t, v, z, NULL) != 0) return -1;
  pkx_world_from_zoppi(p, z, world);
  world[3] = c;
  world[4] = a;
  return 0;
}

pkm_exechon_status pkm_exechon_forward(const pkm_exechon_params* p,
                                       pkm_exechon_state* state,
                                       const double joints[5],
                                       double extra_tool_length,
                                       double world[5],
                                       int* iterations) {
  int its = 0;
  if (iterations != NULL) *iterations = 0;
  const double* seed = state->valid ? state->e : p->home_e;
  double e[3] = {seed[0], seed[1], seed[2]}, target[3], out[5];
  if (!pkx_all_finite(joints, 5) || !isfinite(extra_tool_length) || !pkx_all_finite(e, 3))
    return PKM_EXECHON_INVALID_INPUT;
  for (int i = 0; i < 3; ++i) target[i] = joints[i] + p->length_offset[i];
  const pkm_exechon_status status = pkx_fk_newton(p, target, e, &its);
  if (iterations != NULL) *iterations = its;
  if (status != PKM_EXECHON_OK) return status;
  e[0] = remainder(e[0], PKX_FK_TWO_PI);
  e[1] = remainder(e[1], PKX_FK_TWO_PI);
  if (pkm_exechon_branch(p, e) != p->branch) return PKM_EXECHON_OTHER_BRANCH;
  if (pkx_tool_pose(p, e, joints[3], joints[4], p->tool_length + extra_tool_length, out) != 0)
    return PKM_EXECHON_SINGULAR;
  for (int i = 0; i < 5; ++i) world[i] = out[i];
  for (int i = 0; i < 3; ++i) state->e[i] = e[i];
  state->valid = 1;
  return PKM_EXECHON_OK;
}

void pkm_exechon_home(const pkm_exechon_params* p,
                      double extra_tool_length,
                      double joints[5],
                      double world[5]) {
  double lengths[3];
  (void)pkm_exechon_leg_lengths(p, p->home_e, lengths, NULL); /* checked by pkm_exechon_prepare */
  for (int i = 0; i < 3; ++i) joints[i] = lengths[i] - p->length_offset[i];
  joints[3] = p->home_c;
  joints[4] = p->home_a;
  (void)pkx_tool_pose(
      p, p->home_e, p->home_c, p->home_a, p->tool_length + extra_tool_length, world);
}
