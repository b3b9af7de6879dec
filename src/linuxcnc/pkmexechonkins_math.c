/* The Exechon tripod's formulas in C: Zoppi et al. (DETC2010-28668, sec. 4) leg lengths and the
 * forward map e -> S with their derivatives, leg B's base-joint offsets (docs/conventions.md, "Leg
 * B's base-joint offsets"), the wrist offset and the condition number of dq/dS. The same formulas
 * as src/kinematics/exechon_tripod_math.hpp, exechon_leg_b.cpp and exechon_ik.cpp. */
#include <math.h>
#include <stddef.h>

#include "pkmexechonkins_internal.h"

/* Leg B at one e: s = P·kB5, length q and their derivatives with respect to e. */
typedef struct {
  int ok;
  double s, q;
  double ds_de[3], dq_de[3];
} pkx_leg_b;

double pkx_dot(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

void pkx_cross(const double a[3], const double b[3], double out[3]) {
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

pkx_trig pkx_trig_of(const double e[3]) {
  pkx_trig t;
  t.sa = sin(e[0]);
  t.ca = cos(e[0]);
  t.sb = sin(e[1]);
  t.cb = cos(e[1]);
  t.h = e[2];
  return t;
}

/* The platform axes kA2, kB5, eh in the Zoppi frame (exechon_model.hpp). */
void pkx_axes(const pkx_trig* t, double kA2[3], double kB5[3], double eh[3]) {
  kA2[0] = t->sa, kA2[1] = 0.0, kA2[2] = t->ca;
  kB5[0] = -t->sb * t->ca, kB5[1] = t->cb, kB5[2] = t->sb * t->sa;
  eh[0] = -t->cb * t->ca, eh[1] = -t->sb, eh[2] = t->cb * t->sa;
}

static int pkx_has_leg_b_offsets(const pkm_exechon_params* g) {
  return g->l12B != 0.0 || g->l23B != 0.0;
}

/* Leg B's closure at the angle phi of R2 about R1: a2, s(phi), its derivative sp, f(phi) and fp. */
typedef struct {
  double a2[3], c, n, s, sp, f, fp;
} pkx_leg_b_eval;

/* Evaluates the closure at phi (v = P5B − s·kB5, sg = σ); returns 0, or -1 when degenerate. */
static int pkx_leg_b_at(const pkm_exechon_params* g,
                        const double v[3],
                        const double kB5[3],
                        double sg,
                        double phi,
                        pkx_leg_b_eval* r) {
  const double ax = cos(phi), az = sin(phi);
  const double a2p[3] = {-az, 0.0, ax};
  double p5[3];
  r->a2[0] = ax, r->a2[1] = 0.0, r->a2[2] = az;
  r->c = pkx_dot(r->a2, kB5);
  r->n = sqrt(fmax(1.0 - r->c * r->c, 0.0));
  if (!(r->n > 1e-9)) return -1; /* leg axis along kB5 */
  const double cp = pkx_dot(a2p, kB5);
  r->s = g->dB * kB5[0] - g->l12B * (az * kB5[0] - ax * kB5[2]) + sg * g->l23B * r->n;
  r->sp = -g->l12B * r->c - sg * g->l23B * r->c * cp / r->n;
  for (int i = 0; i < 3; ++i) p5[i] = v[i] + r->s * kB5[i];
  r->fp = pkx_dot(p5, a2p) + r->sp * r->c + g->dB * az;
  r->f = pkx_dot(p5, r->a2) - g->dB * ax;
  return isfinite(r->f) ? 0 : -1;
}

/* Leg B with base-joint offsets: Newton on phi from Zoppi's ideal leg (closure d·a2 = 0 with
 * d = P5B − Q, s = Q·kB5 + σ·n·l23B), then the derivatives by implicit differentiation. */
static pkx_leg_b pkx_solve_leg_b(const pkm_exechon_params* g, const pkx_trig* t, int derivs) {
  pkx_leg_b out = {0, 0.0, 0.0, {0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}};
  double kA2[3], kB5[3], eh[3], v[3], d0[3], tmp[3];
  pkx_axes(t, kA2, kB5, eh);
  for (int i = 0; i < 3; ++i) v[i] = t->h * eh[i] + g->pB * kA2[i]; /* P5B = v + s·kB5 */
  for (int i = 0; i < 3; ++i) d0[i] = v[i] - (g->dB * t->ca * t->sb) * kB5[i];
  d0[0] -= g->dB;
  double phi = atan2(-d0[0], d0[2]);
  const double a20[3] = {cos(phi), 0.0, sin(phi)};
  pkx_cross(a20, kB5, tmp);
  const double sg = pkx_dot(d0, tmp) >= 0.0 ? 1.0 : -1.0;
  pkx_leg_b_eval r;
  int converged = 0;
  for (int it = 0; it < 30 && !converged; ++it) {
    if (pkx_leg_b_at(g, v, kB5, sg, phi, &r) != 0 || !(fabs(r.fp) > 0.0)) return out;
    const double step = r.f / r.fp;
    phi -= step;
    converged = fabs(step) <= 1e-12;
  }
  if (!converged || pkx_leg_b_at(g, v, kB5, sg, phi, &r) != 0) return out;
  const double Q[3] = {g->dB - g->l12B * r.a2[2], 0.0, g->l12B * r.a2[0]};
  double d[3];
  for (int i = 0; i < 3; ++i) d[i] = v[i] + r.s * kB5[i] - Q[i];
  const double q2 = pkx_dot(d, d) - g->l23B * g->l23B;
  if (!(q2 > 0.0)) return out;
  out.s = r.s;
  out.q = sqrt(q2);
  out.ok = 1;
  if (!derivs) return out;
  const double dkB5[3][3] = {
      {t->sb * t->sa, 0.0, t->sb * t->ca}, {eh[0], eh[1], eh[2]}, {0.0, 0.0, 0.0}};
  const double dal[3] = {t->cb * t->sa, 0.0, t->cb * t->ca}, dka[3] = {t->ca, 0.0, -t->sa};
  double dv[3][3];
  for (int i = 0; i < 3; ++i) {
    dv[0][i] = t->h * dal[i] + g->pB * dka[i];
    dv[1][i] = -t->h * kB5[i];
    dv[2][i] = eh[i];
  }
  for (int k = 0; k < 3; ++k) {
    const double a2dk = pkx_dot(r.a2, dkB5[k]);
    const double s_e = pkx_dot(Q, dkB5[k]) - sg * g->l23B * r.c * a2dk / r.n;
    const double f_e = pkx_dot(dv[k], r.a2) + s_e * r.c + r.s * a2dk;
    out.ds_de[k] = s_e + r.sp * (-f_e / r.fp);
    for (int i = 0; i < 3; ++i) tmp[i] = dv[k][i] + out.ds_de[k] * kB5[i] + r.s * dkB5[k][i];
    out.dq_de[k] = pkx_dot(d, tmp) / out.q;
  }
  return out;
}

/* s = P·kB5 and ds/de: Zoppi's −dB·cos α·sin β, or leg B's offset solve (NaN when it fails). */
static double pkx_offset_b(const pkm_exechon_params* g, const pkx_trig* t, double ds_de[3]) {
  if (!pkx_has_leg_b_offsets(g)) {
    ds_de[0] = g->dB * t->sa * t->sb, ds_de[1] = -g->dB * t->ca * t->cb, ds_de[2] = 0.0;
    return -g->dB * t->ca * t->sb;
  }
  const pkx_leg_b b = pkx_solve_leg_b(g, t, 1);
  for (int i = 0; i < 3; ++i) ds_de[i] = b.ok ? b.ds_de[i] : NAN;
  return b.ok ? b.s : NAN;
}

/* J (row-major) = d(S)/de for S = hx·kA2 + (h + hz)·eh + s·kB5. */
void pkx_wrist_jacobian(
    const pkm_exechon_params* g, const pkx_trig* t, double s, const double ds_de[3], double J[9]) {
  double kA2[3], kB5[3], eh[3];
  pkx_axes(t, kA2, kB5, eh);
  const double dkA2[3] = {t->ca, 0.0, -t->sa}, dkB5[3] = {t->sb * t->sa, 0.0, t->sb * t->ca};
  const double deh[3] = {t->cb * t->sa, 0.0, t->cb * t->ca};
  const double hh = t->h + g->hz;
  for (int i = 0; i < 3; ++i) {
    J[3 * i + 0] = g->hx * dkA2[i] + hh * deh[i] + ds_de[0] * kB5[i] + s * dkB5[i];
    J[3 * i + 1] = -hh * kB5[i] + ds_de[1] * kB5[i] + s * eh[i];
    J[3 * i + 2] = eh[i] + ds_de[2] * kB5[i];
  }
}

/* point = S(e) + R(e)·v (Zoppi frame) and, unless J is NULL, its derivative with respect to e.
 * Returns 0, or -1 when leg B's offset solve fails or a value is not finite. */
int pkx_platform_point(
    const pkm_exechon_params* g, const pkx_trig* t, const double v[3], double point[3], double* J) {
  double ds_de[3], kA2[3], kB5[3], eh[3];
  const double s = pkx_offset_b(g, t, ds_de);
  if (!isfinite(s)) return -1;
  pkx_axes(t, kA2, kB5, eh);
  for (int i = 0; i < 3; ++i)
    point[i] = g->hx * kA2[i] + (t->h + g->hz) * eh[i] + s * kB5[i] + v[0] * kA2[i] +
               v[1] * kB5[i] + v[2] * eh[i];
  int ok = isfinite(point[0]) && isfinite(point[1]) && isfinite(point[2]);
  if (J == NULL) return ok ? 0 : -1;
  pkx_wrist_jacobian(g, t, s, ds_de, J);
  const double dkA2[3] = {t->ca, 0.0, -t->sa}, dkB5[3] = {t->sb * t->sa, 0.0, t->sb * t->ca};
  const double deh[3] = {t->cb * t->sa, 0.0, t->cb * t->ca};
  for (int i = 0; i < 3; ++i) {
    J[3 * i + 0] += v[0] * dkA2[i] + v[1] * dkB5[i] + v[2] * deh[i];
    J[3 * i + 1] += v[1] * eh[i] - v[2] * kB5[i];
  }
  for (int i = 0; i < 9; ++i) ok = ok && isfinite(J[i]);
  return ok ? 0 : -1;
}

/* One of legs A, C: its length sqrt(u² + v²) and, unless row is NULL, d(length)/de. */
static double pkx_leg_ac(const pkx_trig* t,
                         double u,
                         double v,
                         double pL,
                         double hL,
                         double t2,
                         const double dt2[3],
                         const double dt3[3],
                         double* row) {
  const double q = sqrt(u * u + v * v);
  if (row == NULL) return q;
  const double du[3] = {dt3[0], dt3[1] - pL * t->cb + hL * t->sb, dt3[2]};
  const double dv[3] = {
      dt2[0] * t->sb, dt2[1] * t->sb + t2 * t->cb + pL * t->sb + hL * t->cb, t->sb};
  for (int j = 0; j < 3; ++j) row[j] = (u * du[j] + v * dv[j]) / q;
  return q;
}

int pkm_exechon_leg_lengths(const pkm_exechon_params* g,
                            const double e[3],
                            double lengths[3],
                            double* J) {
  const pkx_trig tr = pkx_trig_of(e);
  const pkx_trig* t = &tr;
  const double t1 = g->dB * t->sa - g->pB, t2 = g->dB * t->ca * t->cb + t->h;
  const double t3 = g->dB * t->ca - t2 * t->cb;
  const double uA = t3 - g->pA * t->sb - g->hA * t->cb + g->deltaA * g->l12A;
  const double vA = t2 * t->sb - g->pA * t->cb + g->hA * t->sb + g->dA;
  const double uC = t3 - g->pC * t->sb - g->hC * t->cb + g->deltaC * g->l12C;
  const double vC = t2 * t->sb - g->pC * t->cb + g->hC * t->sb + g->dC;
  const double dt1[3] = {g->dB * t->ca, 0.0, 0.0};
  const double dt2[3] = {-g->dB * t->sa * t->cb, -g->dB * t->ca * t->sb, 1.0};
  const double dt3[3] = {-g->dB * t->sa - dt2[0] * t->cb, -dt2[1] * t->cb + t2 * t->sb, -t->cb};
  lengths[0] = pkx_leg_ac(t, uA, vA, g->pA, g->hA, t2, dt2, dt3, J ? J : NULL);
  lengths[2] = pkx_leg_ac(t, uC, vC, g->pC, g->hC, t2, dt2, dt3, J ? J + 6 : NULL);
  if (pkx_has_leg_b_offsets(g)) {
    const pkx_leg_b b = pkx_solve_leg_b(g, t, J != NULL);
    if (!b.ok) return -1;
    lengths[1] = b.q;
    if (J != NULL)
      for (int j = 0; j < 3; ++j) J[3 + j] = b.dq_de[j];
    return 0;
  }
  lengths[1] = sqrt(t1 * t1 + t2 * t2);
  if (J != NULL)
    for (int j = 0; j < 3; ++j) J[3 + j] = (t1 * dt1[j] + t2 * dt2[j]) / lengths[1];
  return 0;
}
