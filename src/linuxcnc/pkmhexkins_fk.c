/* Forward kinematics of pkmhexkins' core: pkm's damped Newton on SO(3) with continuation (see
 * pkmhexkins_core.h), the legs, the scaled strut Jacobian and its LU (shared with the core's
 * checks through pkmhexkins_internal.h). */
#include <math.h>
#include <string.h>

#include "pkmhexkins_internal.h"

#define N PKM_HEX_STRUTS

/* Below this rotation angle (rad) exp uses its series (pkm's so3Exp). */
static const double kSmallAngle = 1e-8;
/* No polishing step below this fraction of the tolerance (pkm's detail::kPolishFraction). */
static const double kPolishFraction = 1e-3;
/* Strut tolerance of a continuation's intermediate stages, × the characteristic length. */
static const double kStageTolerance = 1e-6;
/* Most continuation stages of one solve. */
static const int kMaxStages = 1000;

/* An iterate: the TCP position and the platform rotation, world frame. */
typedef struct {
  double p[3];
  double R[3][3];
} pose;

/* Everything one solve shares between its steps. */
typedef struct {
  const pkm_hex_geometry* geometry;
  const pkm_hex_fk_options* options;
  double base[N][3];     /* b'_i */
  double platform[N][3]; /* a'_i */
  double inv_length;
  double max_translation;
  double target[N]; /* the readings the current stage solves for */
  legs at;          /* the legs of the current iterate */
  lu6 lu;
  double lu_ratio;
  int seed_sign; /* sign of det J at a stage's first linearisation (0: none yet) */
  int last_sign; /* and at its latest */
  int budget; /* Newton steps plus step halvings left (options' max_total_iterations); −1: none */
  int exhausted; /* the budget ran out */
} solver;

/* b ← A⁻¹·b for the A factorised in lu (precondition: lu->valid). */
static void substitute6(const lu6* lu, double b[N]) {
  double y[N];
  for (int k = 0; k < N; ++k) {
    const double* r = lu->m[lu->row[k]];
    double s = b[lu->row[k]];
    for (int j = 0; j < k; ++j) s -= r[j] * y[j];
    y[k] = s;
  }
  for (int k = N - 1; k >= 0; --k) {
    const double* r = lu->m[lu->row[k]];
    double s = y[k];
    for (int j = k + 1; j < N; ++j) s -= r[j] * y[j];
    y[k] = s * lu->inverse_pivot[k];
  }
  memcpy(b, y, sizeof y);
}

/* exp([w]×), Rodrigues' formula with pkm's small-angle series. */
static void so3_exp(const double w[3], double E[3][3]) {
  const double theta2 = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
  const double theta = sqrt(theta2);
  const double W[3][3] = {{0.0, -w[2], w[1]}, {w[2], 0.0, -w[0]}, {-w[1], w[0], 0.0}};
  double a, b;
  if (theta < kSmallAngle) {
    a = 1.0 - theta2 / 6.0;
    b = 0.5 - theta2 / 24.0;
  } else {
    a = sin(theta) / theta;
    b = (1.0 - cos(theta)) / theta2;
  }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double ww = W[i][0] * W[0][j] + W[i][1] * W[1][j] + W[i][2] * W[2][j];
      E[i][j] = (i == j ? 1.0 : 0.0) + a * W[i][j] + b * ww;
    }
}

/* The iterate x − step·delta: p − step·δp, exp(−step·δθ)·R. */
static void retract(const pose* x, const double delta[N], double step, pose* out) {
  double w[3], E[3][3];
  for (int k = 0; k < 3; ++k) {
    out->p[k] = x->p[k] - step * delta[k];
    w[k] = -step * delta[3 + k];
  }
  so3_exp(w, E);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      out->R[i][j] = E[i][0] * x->R[0][j] + E[i][1] * x->R[1][j] + E[i][2] * x->R[2][j];
}

/* The residual at x into r (the legs into s->at); returns |r|² (+infinity when not finite). */
static double evaluate(solver* s, const pose* x, double r[N]) {
  compute_legs(
      &s->base[0][0], &s->platform[0][0], s->geometry->length_offset, x->p, &x->R[0][0], &s->at);
  double n2 = 0.0;
  for (int i = 0; i < N; ++i) {
    r[i] = s->at.q[i] - s->target[i];
    n2 += r[i] * r[i];
  }
  return isfinite(n2) ? n2 : INFINITY;
}

static double max_abs(const double r[N]) {
  double m = 0.0;
  for (int i = 0; i < N; ++i) m = fmax(m, fabs(r[i]));
  return m;
}

/* The strut residuals left after the full step delta from the legs in s->at, to second order
 * (pkm's secondOrderResidual): per leg with unit vector u, length l and joint offset r,
 * s = u·q + (|w|² − (u·w)²)/(2l), w = −δp − δθ×r, q = ½ δθ×(δθ×r). */
static void second_order_residual(const solver* s, const double delta[N], double out[N]) {
  const double* dp = delta;
  const double* dt = delta + 3;
  for (int i = 0; i < N; ++i) {
    const double* r = s->at.r_joint[i];
    const double* u = s->at.unit[i];
    const double c[3] = {
        dt[1] * r[2] - dt[2] * r[1], dt[2] * r[0] - dt[0] * r[2], dt[0] * r[1] - dt[1] * r[0]};
    const double tc[3] = {
        dt[1] * c[2] - dt[2] * c[1], dt[2] * c[0] - dt[0] * c[2], dt[0] * c[1] - dt[1] * c[0]};
    double w2 = 0.0, uw = 0.0, uq = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double w = -dp[k] - c[k];
      w2 += w * w;
      uw += u[k] * w;
      uq += u[k] * tc[k];
    }
    const double length = s->at.q[i] + s->geometry->length_offset[i];
    out[i] = 0.5 * uq + (w2 - uw * uw) / (2.0 * length);
  }
}

/* delta ← J⁻¹·delta at the current iterate, shortened to the trust region; returns the pivot
 * ratio. A polishing step reuses the previous factorisation (a chord step). A full step is
 * corrected for its second-order residual with the same factorisation where that residual needs
 * polishing (pkm's forwardKinematics). */
static double solve_step(solver* s, double delta[N], int polishing) {
  if (!polishing || !s->lu.valid) {
    double J[N][N];
    scaled_jacobian(&s->at, s->inv_length, J);
    s->lu_ratio = factor6((const double(*)[N])J, &s->lu, &s->last_sign);
    if (s->seed_sign == 0) s->seed_sign = s->last_sign;
  }
  if (!s->lu.valid) return s->lu_ratio;
  substitute6(&s->lu, delta);
  for (int k = 3; k < N; ++k) delta[k] *= s->inv_length;
  const double t = norm3(delta) / s->max_translation;
  const double w = norm3(delta + 3) / s->options->max_step_rotation;
  const double shrink = fmax(1.0, fmax(t, w));
  if (isfinite(shrink))
    for (int k = 0; k < N; ++k) delta[k] /= shrink;
  if (shrink != 1.0 || polishing) return s->lu_ratio;
  double e[N];
  second_order_residual(s, delta, e);
  if (max_abs(e) > kPolishFraction * s->options->tolerance && all_finite(e, N)) {
    substitute6(&s->lu, e);
    for (int k = 0; k < N; ++k) delta[k] += k < 3 ? e[k] : e[k] * s->inv_length;
  }
  return s->lu_ratio;
}

/* One Newton step with step halving from x (residual r, |r|² *norm2). Returns 1 when a step was
 * accepted (x, r, *norm2 updated), 0 when none reduced |r|, −1 when singular. */
static int newton_step(solver* s,
                       const pkm_hex_fk_options* o,
                       pose* x,
                       double r[N],
                       double* norm2,
                       int polishing,
                       pkm_hex_fk_summary* summary) {
  double delta[N];
  memcpy(delta, r, sizeof delta);
  const double ratio = solve_step(s, delta, polishing);
  if (!(ratio > o->singular_pivot_ratio) || !all_finite(delta, N)) return -1;
  double step = 1.0;
  for (int k = 0; k <= o->max_backtracks; ++k) {
    pose x_try;
    double r_try[N];
    retract(x, delta, step, &x_try);
    const double n2 = evaluate(s, &x_try, r_try);
    if (n2 < *norm2 || (!polishing && max_abs(r_try) <= o->tolerance)) {
      *x = x_try;
      memcpy(r, r_try, sizeof r_try);
      *norm2 = n2;
      return 1;
    }
    step *= 0.5;
    ++summary->backtracks;
    if (s->budget == 0) { /* no evaluation left: as if no step reduced |r| */
      s->exhausted = 1;
      break;
    }
    if (s->budget > 0) --s->budget;
  }
  *norm2 = evaluate(s, x, r); /* the legs back to the best iterate */
  return 0;
}

/* pkm's detail::dampedNewton: converges on max|r| <= tolerance, then one polishing step. */
static pkm_hex_fk_summary damped_newton(solver* s, const pkm_hex_fk_options* o, pose* x) {
  pkm_hex_fk_summary summary = {PKM_HEX_NO_CONVERGENCE, 0, 0, 0.0};
  double r[N];
  double norm2 = evaluate(s, x, r);
  int polishing = 0;
  for (int iter = 0;; ++iter) {
    summary.max_residual = max_abs(r);
    if (!isfinite(norm2) || summary.max_residual > o->max_error) {
      summary.status = PKM_HEX_NO_CONVERGENCE;
      break;
    }
    if (summary.max_residual <= o->tolerance) {
      summary.status = PKM_HEX_OK;
      if (polishing || summary.max_residual <= kPolishFraction * o->tolerance ||
          iter == o->max_iterations)
        break;
      polishing = 1;
    }
    if (iter == o->max_iterations) break;
    if (s->budget == 0) {
      s->exhausted = 1;
      break;
    }
    if (s->budget > 0) --s->budget;
    const int accepted = newton_step(s, o, x, r, &norm2, polishing, &summary);
    if (accepted < 0) {
      summary.status = PKM_HEX_SINGULAR;
      break;
    }
    ++summary.iterations;
    summary.max_residual = max_abs(r);
    if (accepted == 0) {
      if (!polishing) summary.status = PKM_HEX_NO_CONVERGENCE;
      break;
    }
    if (polishing) break;
  }
  return summary;
}

/* Number of continuation stages from the seed's readings `start` to `q` (at most `cap`). */
static int stage_count(const double start[N], const double q[N], double stage_length, int cap) {
  double gap = 0.0;
  for (int i = 0; i < N; ++i) gap = fmax(gap, fabs(q[i] - start[i]));
  if (!isfinite(gap) || gap <= stage_length) return 1;
  return (int)fmin(ceil(gap / stage_length), (double)cap);
}

/* Solves the stages from x; the summary of the last stage run, with the totals. With a total
 * budget (o->max_total_iterations > 0), every Newton step and every step halving spends one unit
 * of it, over all stages; none left ends the solve (budget_exhausted). */
static pkm_hex_fk_summary run_stages(solver* s, const double q[N], pose* x) {
  const pkm_hex_fk_options* o = s->options;
  const int budget = o->max_total_iterations > 0 ? o->max_total_iterations : 0;
  s->budget = budget > 0 ? budget : -1;
  const double length = 1.0 / s->inv_length;
  double start[N], r[N];
  memcpy(start, s->at.q, sizeof start);
  const int stages = stage_count(start,
                                 q,
                                 o->continuation_step * length,
                                 budget > 0 && budget < kMaxStages ? budget : kMaxStages);
  pkm_hex_fk_options intermediate = *o;
  intermediate.tolerance = fmax(o->tolerance, kStageTolerance * length);
  pkm_hex_fk_summary summary = {PKM_HEX_OK, 0, 0, 0.0};
  int iterations = 0, backtracks = 0, previous_sign = 0;
  for (int k = 1; k <= stages; ++k) {
    for (int i = 0; i < N; ++i)
      s->target[i] = k == stages ? q[i] : start[i] + (q[i] - start[i]) * ((double)k / stages);
    s->seed_sign = s->last_sign = 0;
    summary = damped_newton(s, k == stages ? o : &intermediate, x);
    iterations += summary.iterations;
    backtracks += summary.backtracks;
    if (summary.status == PKM_HEX_NO_CONVERGENCE && s->exhausted)
      summary.status = PKM_HEX_BUDGET_EXHAUSTED;
    if (summary.status != PKM_HEX_OK) break;
    if (s->seed_sign == 0) continue; /* converged without a linearisation */
    if ((previous_sign != 0 && s->seed_sign != previous_sign) || s->last_sign != s->seed_sign) {
      summary.status = PKM_HEX_OTHER_BRANCH;
      break;
    }
    previous_sign = s->last_sign;
  }
  summary.iterations = iterations;
  summary.backtracks = backtracks;
  if (summary.status != PKM_HEX_OK && stages > 1) { /* the residual against q, not a stage's */
    memcpy(s->target, q, sizeof s->target);
    evaluate(s, x, r);
    summary.max_residual = max_abs(r);
  }
  return summary;
}

/* PKM_HEX_OTHER_BRANCH (or PKM_HEX_SINGULAR) unless the solution x is on the branch o->branch. */
static pkm_hex_status check_branch(solver* s, const pose* x) {
  double J[N][N];
  int sign = 0;
  compute_legs(
      &s->base[0][0], &s->platform[0][0], s->geometry->length_offset, x->p, &x->R[0][0], &s->at);
  scaled_jacobian(&s->at, s->inv_length, J);
  const double ratio = factor6((const double(*)[N])J, &s->lu, &sign);
  if (!(ratio > s->options->singular_pivot_ratio)) return PKM_HEX_SINGULAR;
  return sign == s->options->branch ? PKM_HEX_OK : PKM_HEX_OTHER_BRANCH;
}

pkm_hex_fk_summary pkm_hex_forward(const pkm_hex_geometry* g,
                                   const double q[N],
                                   const pkm_hex_fk_options* o,
                                   double p[3],
                                   double R[3][3]) {
  pkm_hex_fk_summary summary = {PKM_HEX_INVALID_INPUT, 0, 0, INFINITY};
  if (!all_finite(q, N) || !all_finite(p, 3) || !all_finite(&R[0][0], 9)) return summary;
  for (int i = 0; i < N; ++i)
    if (!(q[i] + g->length_offset[i] > 0.0)) return summary; /* no strut of zero length */
  solver s;
  memset(&s, 0, sizeof s);
  s.geometry = g;
  s.options = o;
  effective_joints(g, s.base, s.platform);
  const double length = pkm_hex_characteristic_length(g);
  s.inv_length = 1.0 / length;
  s.max_translation = o->max_step_translation * length;
  pose x;
  memcpy(x.p, p, sizeof x.p);
  memcpy(x.R, R, sizeof x.R);
  compute_legs(&s.base[0][0], &s.platform[0][0], g->length_offset, x.p, &x.R[0][0], &s.at);
  summary = run_stages(&s, q, &x);
  if (summary.status == PKM_HEX_OK && o->branch != 0) summary.status = check_branch(&s, &x);
  if (summary.status == PKM_HEX_OK) {
    memcpy(p, x.p, sizeof x.p);
    memcpy(R, x.R, sizeof x.R);
  }
  return summary;
}
