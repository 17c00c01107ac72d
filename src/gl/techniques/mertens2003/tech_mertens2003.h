/* gl/tech_mertens2003.h — the CPU side of mertens2003's importance sampling (Mertens et al. 2003, section 4):
 * per material and colour channel, a table of radii at T + 1 quantiles of R_d(r) 2 pi r / rho from
 * the physics module's exact sampler, and a guide grid that finds the table segment holding any r.
 *
 * The distribution the shader draws from is the piecewise-linear interpolation of those quantiles:
 * u in [0, 1) -> k = floor(u T), r = r_k + (u T - k) (r_(k+1) - r_k), whose density is exactly
 * 1 / (T (r_(k+1) - r_k)) on segment k. The balance heuristic (section 6.1) weighs every sample with
 * the densities of exactly these distributions, so the estimator stays unbiased; with T = 1024 they
 * match R_d 2 pi r / rho closely (the quantiles themselves are exact). r_T is the quantile
 * MERTENS_U_MAX: the last 1e-5 of each channel's energy is left to the uniform samples. */
#ifndef SSS_GL_TECH_MERTENS2003_H
#define SSS_GL_TECH_MERTENS2003_H

#include "sss/common.h"
#include "sss/profile.h"

#define MERTENS_T 1024      /* quantile segments per channel */
#define MERTENS_G 2048      /* guide cells per channel, uniform in sqrt(r / r_T) */
#define MERTENS_U_MAX (1.0 - 1e-5)
/* Floats per material: [0..2] r_T per channel, [3] max guide scan; then 3 x (T + 1) radii; then
 * 3 x G guide entries (segment index at each guide cell's lower edge, stored as float). */
#define MERTENS_RADII_AT 4
#define MERTENS_GUIDE_AT (MERTENS_RADII_AT + 3 * (MERTENS_T + 1))
#define MERTENS_TABLE_FLOATS (MERTENS_GUIDE_AT + 3 * MERTENS_G)

/* Fills out[MERTENS_TABLE_FLOATS] for a profile; a channel with a zero profile gets r_T = 0 (its
 * importance samples are then skipped by the shader). */
sss_result mertens_table_build(const sss_profile *profile, float *out, sss_error *err);

/* CPU mirrors of the shader's sampling and density (tests): r(u) for u in [0, 1), and the density
 * per unit length of r (0 outside [0, r_T]). */
double mertens_table_sample(const float *table, int channel, double u);
double mertens_table_pdf(const float *table, int channel, double r);

#endif
