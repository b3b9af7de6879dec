/// @file
/// @brief Internal helpers of the C Exechon kinematics (pkmexechonkins_*.c): vector algebra and the
/// tripod's forward map with its derivative. Not part of the component's interface.
#ifndef PKM_EXECHON_KINS_INTERNAL_H
#define PKM_EXECHON_KINS_INTERNAL_H

#include "pkmexechonkins_core.h"

/// sin/cos of alpha and beta, and h, of e = (alpha, beta, h).
typedef struct {
  double sa, ca, sb, cb, h;
} pkx_trig;

double pkx_dot(const double a[3], const double b[3]);
void pkx_cross(const double a[3], const double b[3], double out[3]);
pkx_trig pkx_trig_of(const double e[3]);
/// The platform axes kA2, kB5, eh (columns of zoppi_R_platform) at t.
void pkx_axes(const pkx_trig* t, double kA2[3], double kB5[3], double eh[3]);
/// J (row-major) = dS/de for S = hx·kA2 + (h + hz)·eh + s·kB5, given s = P·kB5 and ds/de.
void pkx_wrist_jacobian(
    const pkm_exechon_params* g, const pkx_trig* t, double s, const double ds_de[3], double J[9]);
/// point = S(e) + R(e)·v in the Zoppi frame (v in the platform frame, length unit) and, unless J is
/// NULL, d(point)/de (row-major). Returns 0, or -1 when leg B's solve fails or a value is not
/// finite.
int pkx_platform_point(
    const pkm_exechon_params* g, const pkx_trig* t, const double v[3], double point[3], double* J);

/// The tool offset v = L·W·Rz(θC)·Rx(θA)·ẑ (platform frame) for the wrist readings c, a (rad).
void pkx_tool_offset(const pkm_exechon_params* p, double c, double a, double L, double v[3]);
/// w = world_T_zoppi · z.
void pkx_world_from_zoppi(const pkm_exechon_params* p, const double z[3], double w[3]);
/// 1 when the n values are finite.
int pkx_all_finite(const double* x, int n);

#endif /* PKM_EXECHON_KINS_INTERNAL_H */
