/* Hexapod kinematics in plain C: pkm's model and forward-kinematics algorithm (see the header). */
#include "pkmhexkins_core.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define N PKM_HEX_STRUTS

/* Below this rotation angle (rad) exp uses its series (pkm's so3Exp). */
static const double kSmallAngle = 1e-8;
/* No polishing step below this fraction of the tolerance (pkm's detail::kPolishFraction). */
static const double kPolishFraction = 1e-3;
/* Strut tolerance of a continuation's intermediate stages, × the characteristic length. */
static const double kStageTolerance = 1e-6;
/* Most continuation stages of one solve. */
static const int kMaxStages = 1000;
static const double kPi = 3.14159265358979323846;

/* An iterate: the TCP position and the platform rotation, world frame. */
typedef struct {
  double p[3];
  double R[3][3];
} pose;

/* The legs at a pose: what the residual and the Jacobian need. */
typedef struct {
  double r_joint[N][3]; /* R·a'_i, world */
  double unit[N][3];    /* unit leg vector u_i, base to platform */
  double q[N];          /* readings */
} legs;

/* LU factorisation of the scaled 6×6 Jacobian with partial pivoting (rows swapped by index). */
typedef struct {
  double m[N][N];
  int row[N];
  double inverse_pivot[N];
  int valid;
} lu6;

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
} solver;

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

static double norm3(const double v[3]) { return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

double pkm_hex_characteristic_length(const pkm_hex_geometry* g) {
  double sum = 0.0;
  for (int i = 0; i < N; ++i) sum += norm3(g->platform[i]);
  const double mean = sum / N;
  return mean > 0.0 ? mean : 1.0;
}

static int all_finite(const double* v, int n) {
  for (int i = 0; i < n; ++i)
    if (!isfinite(v[i])) return 0;
  return 1;
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

/* The effective joints b'_i, a'_i of the header's model. */
static void effective_joints(const pkm_hex_geometry* g, double base[N][3], double platform[N][3]) {
  for (int i = 0; i < N; ++i) {
    for (int k = 0; k < 3; ++k) {
      base[i][k] = g->base[i][k];
      platform[i][k] = g->platform[i][k] - g->tool[k];
    }
    base[i][2] += g->spindle_offset;
    platform[i][2] += g->spindle_offset;
  }
}

/* The legs of the pose (p, R), in pkm's order of operations (detail::computeLegs). The arrays
 * are passed flat (base[3·i + k], R[3·row + column]): ISO C before C23 does not convert a
 * double (*)[3] to a const double (*)[3]. */
static void compute_legs(const double* base,
                         const double* platform,
                         const double* length_offset,
                         const double* p,
                         const double* R,
                         legs* out) {
  for (int i = 0; i < N; ++i) {
    const double* a = platform + 3 * i;
    double leg[3];
    for (int k = 0; k < 3; ++k) {
      out->r_joint[i][k] = R[3 * k] * a[0] + R[3 * k + 1] * a[1] + R[3 * k + 2] * a[2];
      leg[k] = (p[k] + out->r_joint[i][k]) - base[3 * i + k];
    }
    const double len = norm3(leg);
    for (int k = 0; k < 3; ++k) out->unit[i][k] = len > 0.0 ? leg[k] / len : 0.0;
    out->q[i] = len - length_offset[i];
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

/* Factorises A into lu; returns min|pivot|/max|pivot| (0 when singular) and the sign of det A. */
static double factor6(const double A[N][N], lu6* lu, int* det_sign) {
  memcpy(lu->m, A, sizeof lu->m);
  for (int i = 0; i < N; ++i) lu->row[i] = i;
  lu->valid = 0;
  *det_sign = 0;
  double min_pivot = INFINITY, max_pivot = 0.0;
  int sign = 1;
  for (int k = 0; k < N; ++k) {
    int p = k;
    double best = fabs(lu->m[lu->row[k]][k]);
    for (int i = k + 1; i < N; ++i) {
      const double v = fabs(lu->m[lu->row[i]][k]);
      if (v > best) {
        best = v;
        p = i;
      }
    }
    if (best == 0.0) return 0.0;
    if (p != k) {
      const int t = lu->row[p];
      lu->row[p] = lu->row[k];
      lu->row[k] = t;
      sign = -sign;
    }
    const double* pivot_row = lu->m[lu->row[k]];
    if (pivot_row[k] < 0.0) sign = -sign;
    min_pivot = fmin(min_pivot, best);
    max_pivot = fmax(max_pivot, best);
    const double inv = 1.0 / pivot_row[k];
    lu->inverse_pivot[k] = inv;
    for (int i = k + 1; i < N; ++i) {
      double* r = lu->m[lu->row[i]];
      const double f = r[k] * inv;
      for (int j = k + 1; j < N; ++j) r[j] -= f * pivot_row[j];
      r[k] = f;
    }
  }
  lu->valid = 1;
  *det_sign = sign;
  return min_pivot / max_pivot;
}

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

/* The strut Jacobian at the legs `at`, angular columns scaled by inv_length (1/L): row i is
 * [u_i, (R·a'_i × u_i)/L]. */
static void scaled_jacobian(const legs* at, double inv_length, double J[N][N]) {
  for (int i = 0; i < N; ++i) {
    const double* u = at->unit[i];
    const double* a = at->r_joint[i];
    J[i][0] = u[0];
    J[i][1] = u[1];
    J[i][2] = u[2];
    J[i][3] = (a[1] * u[2] - a[2] * u[1]) * inv_length;
    J[i][4] = (a[2] * u[0] - a[0] * u[2]) * inv_length;
    J[i][5] = (a[0] * u[1] - a[1] * u[0]) * inv_length;
  }
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

/* Number of continuation stages from the seed's readings `start` to `q`. */
static int stage_count(const double start[N], const double q[N], double stage_length) {
  double gap = 0.0;
  for (int i = 0; i < N; ++i) gap = fmax(gap, fabs(q[i] - start[i]));
  if (!isfinite(gap) || gap <= stage_length) return 1;
  return (int)fmin(ceil(gap / stage_length), (double)kMaxStages);
}

/* Solves the stages from x; the summary of the last stage run, with the totals. */
static pkm_hex_fk_summary run_stages(solver* s, const double q[N], pose* x) {
  const pkm_hex_fk_options* o = s->options;
  const double length = 1.0 / s->inv_length;
  double start[N], r[N];
  memcpy(start, s->at.q, sizeof start);
  const int stages = stage_count(start, q, o->continuation_step * length);
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

pkm_hex_fk_summary pkm_hex_forward(const pkm_hex_geometry* g,
                                   const double q[N],
                                   const pkm_hex_fk_options* o,
                                   double p[3],
                                   double R[3][3]) {
  pkm_hex_fk_summary summary = {PKM_HEX_INVALID_INPUT, 0, 0, INFINITY};
  if (!all_finite(q, N) || !all_finite(p, 3) || !all_finite(&R[0][0], 9)) return summary;
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
  if (summary.status == PKM_HEX_OK) {
    memcpy(p, x.p, sizeof x.p);
    memcpy(R, x.R, sizeof x.R);
  }
  return summary;
}
