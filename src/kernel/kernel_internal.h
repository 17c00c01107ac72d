/* kernel/kernel_internal.h — quadrature helpers shared by the kernel module's files (and its tests).
 * Not part of the public API. */
#ifndef SSS_KERNEL_INTERNAL_H
#define SSS_KERNEL_INTERNAL_H

#include <math.h>

#include "sss/kernel.h"

#define KQ_PI 3.14159265358979323846

/* Gauss-Legendre nodes and weights of n points on [-1, 1] (Newton on P_n, ascending nodes). */
void kq_gauss_legendre(int n, double *x, double *w);

/* A vector integrand: writes f(x) for the three channels. */
typedef void (*kq_fn3)(double x, void *ctx, double out[3]);

/* Adaptive Gauss-Kronrod (7/15) of a 3-channel integrand over [a, b]: splits until each piece's
 * error estimate is below max(rel_tol * |piece|, abs_tol) per channel or the depth limit is hit.
 * b may be smaller than a (the result changes sign). */
void kq_integrate3(kq_fn3 f, void *ctx, double a, double b, double rel_tol, double abs_tol,
                   double out[3]);

/* The same over [a, b] cut into geometrically growing pieces starting at a: [a, a + s], [a + s,
 * a + 3s], ... (each twice the last), so features of size s near a are resolved. */
void kq_integrate3_graded(kq_fn3 f, void *ctx, double a, double b, double s, double rel_tol,
                          double abs_tol, double out[3]);

/* The shortest length on which the profile varies near r = 0 (smallest mean free path 1/sigma_t
 * over the channels, or the narrowest Gaussian): integration panels are graded down to it. */
double kq_profile_length_scale(const sss_profile *p);

/* Decay length of the profile far from the origin: 1 / sigma_tr of the fastest-decaying channel
 * (sigma_tr = sqrt(3 sigma_a sigma_t'), docs/physics.md §2.1); INFINITY without absorption. */
double kq_profile_decay_length(const sss_profile *p);

/* The discretised profile of the SVD and guided kernels (kernel/cells.c): out[c * grid^2 + i * grid + j]
 * = the integral of R_d(sqrt(x^2 + y^2)) for channel c over cell (i, j) of the grid x grid square
 * [-extent, extent]^2, cell i spanning [(2i - grid), (2i + 2 - grid)] * extent / grid (so its centre
 * is -extent + (i + 1/2) h, h = 2 extent / grid). Finite for any grid parity: the cell holding r = 0
 * (and the cells where R_d varies within a cell) as a radial integral of R_d(r) r times the angle of
 * the circle inside the cell, the rest by tensor Gauss-Legendre chosen from the profile's local
 * length scales. Exactly symmetric under the square's symmetries; 0 beyond the radius where R_d is
 * exactly 0. grid >= 1, extent > 0 and finite (unchecked). */
void kq_cell_integrals(const sss_profile *p, int grid, double extent, double *out);

/* arccos(y) for y = (nc - ns) / (nc + ns), nc, ns >= 0, without forming y near +-1 (where acos loses
 * digits): Abramowitz & Stegun 4.4.46, acos(y) = sqrt(1 - y) (a0 + ... + a7 y^7), |error| <= 2e-8
 * on [0, 1], mirrored with acos(-y) = pi - acos(y). Inline: it runs once per ring per texel.
 * Requires nc + ns > 0. */
static inline double kq_acos_ratio(double nc, double ns)
{
    /* Branch-free (a blend at the end) so that loops over rings vectorise; nc + ns > 0 required. */
    double inv = 1.0 / (nc + ns);
    double y = fabs(nc - ns) * inv;            /* |cos| in [0, 1] */
    double one_minus = 2.0 * (nc < ns ? nc : ns) * inv; /* 1 - |cos| without cancellation */
    double poly = ((((((-0.0012624911 * y + 0.0066700901) * y - 0.0170881256) * y + 0.0308918810) * y -
                     0.0501743046) * y + 0.0889789874) * y - 0.2145988016) * y + 1.5707963050;
    double v = sqrt(one_minus) * poly;
    double flip = ns > nc ? 1.0 : 0.0;
    return flip * KQ_PI + (1.0 - 2.0 * flip) * v;
}

#endif
