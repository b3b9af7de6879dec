/// @file
/// @brief Internal helpers of pkmhexkins' C core (pkmhexkins_core.c, pkmhexkins_fk.c): the legs
/// at a pose, the scaled strut Jacobian and its LU. Not part of the component's interface.
#ifndef PKM_HEXKINS_INTERNAL_H
#define PKM_HEXKINS_INTERNAL_H

#include <math.h>

#include "pkmhexkins_core.h"

/// The legs at a pose: what the residual and the Jacobian need.
typedef struct {
  double r_joint[PKM_HEX_STRUTS][3]; /* R·a'_i, world */
  double unit[PKM_HEX_STRUTS][3];    /* unit leg vector u_i, base to platform */
  double q[PKM_HEX_STRUTS];          /* readings */
} legs;

/// LU factorisation of the scaled 6×6 Jacobian with partial pivoting (rows swapped by index).
typedef struct {
  double m[PKM_HEX_STRUTS][PKM_HEX_STRUTS];
  int row[PKM_HEX_STRUTS];
  double inverse_pivot[PKM_HEX_STRUTS];
  int valid;
} lu6;

static inline double norm3(const double v[3]) {
  return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

static inline int all_finite(const double* v, int n) {
  for (int i = 0; i < n; ++i)
    if (!isfinite(v[i])) return 0;
  return 1;
}

/* The effective joints b'_i, a'_i of the header's model. */
static inline void effective_joints(const pkm_hex_geometry* g,
                                    double base[PKM_HEX_STRUTS][3],
                                    double platform[PKM_HEX_STRUTS][3]) {
  for (int i = 0; i < PKM_HEX_STRUTS; ++i) {
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
static inline void compute_legs(const double* base,
                                const double* platform,
                                const double* length_offset,
                                const double* p,
                                const double* R,
                                legs* out) {
  for (int i = 0; i < PKM_HEX_STRUTS; ++i) {
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

/* Factorises A into lu; returns min|pivot|/max|pivot| (0 when singular) and the sign of det A. */
static inline double factor6(const double A[PKM_HEX_STRUTS][PKM_HEX_STRUTS],
                             lu6* lu,
                             int* det_sign) {
  memcpy(lu->m, A, sizeof lu->m);
  for (int i = 0; i < PKM_HEX_STRUTS; ++i) lu->row[i] = i;
  lu->valid = 0;
  *det_sign = 0;
  double min_pivot = INFINITY, max_pivot = 0.0;
  int sign = 1;
  for (int k = 0; k < PKM_HEX_STRUTS; ++k) {
    int p = k;
    double best = fabs(lu->m[lu->row[k]][k]);
    for (int i = k + 1; i < PKM_HEX_STRUTS; ++i) {
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
    for (int i = k + 1; i < PKM_HEX_STRUTS; ++i) {
      double* r = lu->m[lu->row[i]];
      const double f = r[k] * inv;
      for (int j = k + 1; j < PKM_HEX_STRUTS; ++j) r[j] -= f * pivot_row[j];
      r[k] = f;
    }
  }
  lu->valid = 1;
  *det_sign = sign;
  return min_pivot / max_pivot;
}

/* The strut Jacobian at the legs `at`, angular columns scaled by inv_length (1/L): row i is
 * [u_i, (R·a'_i × u_i)/L]. */
static inline void scaled_jacobian(const legs* at,
                                   double inv_length,
                                   double J[PKM_HEX_STRUTS][PKM_HEX_STRUTS]) {
  for (int i = 0; i < PKM_HEX_STRUTS; ++i) {
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

#endif /* PKM_HEXKINS_INTERNAL_H */
