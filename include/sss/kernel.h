/* sss/kernel.h — kernels the real-time techniques sample: the disc-integrated 2D LUT of Maisch & Ropinski 2020 and
 * the separable 1D kernels of Jimenez et al. 2019.
 *
 * Does: tabulate R'_d(r, A) = (1/A) * integral of R_d over a disc of area A centred at distance r
 * (Maisch & Ropinski 2020, Eq. 5, sections 7.1-7.2) as a float RGB texture; build separable kernels by
 * pre-integration (Jimenez et al. 2019, Eq. 4-5), from the artist model (Eq. 6) and by SVD (rank N, LAPACKE).
 * Does not: upload to GL (the arrays are texture-ready), know about scenes.
 * Memory: every _build/_create allocates inside its output struct; pair it with the matching _free.
 */
#ifndef SSS_KERNEL_H
#define SSS_KERNEL_H

#include "sss/common.h"
#include "sss/profile.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- Disc-integrated LUT (Maisch & Ropinski 2020) ---------------------------------------------------------- */

/* Accuracy of bilinear sss_lut_lookup against sss_lut_exact, 512 x 512, Marble at scale 1, eta 1.33
 * (bench/bench_lut.c; relative error per channel over 2000 points):
 *                                      PBD max    PBD mean   dipole max  dipole mean
 *   linear, (r, A) uniform             4.2e-2     7.2e-5     2.8e-2      3.1e-5
 *   sqrt,   (r, A) uniform             6.8e-3     7.3e-5     4.6e-4      3.1e-5
 *   linear, r/r_max, A/A_max log-uniform in [1e-4, 1]   96     5.3        8.2e-2      7.8e-3
 *   sqrt,   same                       3.7e-2     6.2e-4     4.1e-4      4.5e-5
 * The linear axes (the paper's) fail near r = 0 and A = 0, where the PBD profile grows like 1/r and
 * the first texel spans r_max / 511: prefer SSS_LUT_AXES_SQRT. The build itself agrees with a
 * brute-force 2D quadrature to ~1e-4 (PBD) and ~2e-5 (dipole) per texel. */
typedef enum sss_lut_axes {
    SSS_LUT_AXES_LINEAR = 0, /* texel i at r = r_max i/(N-1), texel j at A = A_max j/(N-1) (Maisch & Ropinski 2020) */
    SSS_LUT_AXES_SQRT        /* r = r_max (i/(N-1))^2, A = A_max (j/(N-1))^2: denser near 0; a lookup
                                takes u = sqrt(r / r_max), v = sqrt(A / A_max) = r_A / r_max */
} sss_lut_axes;

/* Zero-initialised means defaults. */
typedef struct sss_lut_desc {
    int size;              /* texels per axis; 0 -> 512 */
    sss_lut_axes axes;     /* 0 -> linear, as the paper */
    double source_cutoff;  /* r_max solves Q(r_max) = alpha' sigma_t' e^(-sigma_t' r_max) = cutoff,
                              largest over the channels; 0 -> 1e-7 (Maisch & Ropinski 2020, section 7.1). Q is in
                              scene units, so r_max depends on the scale; for weakly absorbing media it
                              leaves energy outside (Marble at scale 1: 6.7% of red, 1.9% of blue).
                              For SSS_PROFILE_GAUSS6: where the widest Gaussian falls to cutoff of
                              its peak. */
    double r_max;          /* > 0 overrides the cut-off rule */
} sss_lut_desc;

typedef struct sss_lut {
    int size;
    sss_lut_axes axes;
    double r_max, a_max;   /* scene units, scene units^2; a_max = pi r_max^2 */
    float *texels;         /* size * size * 3 floats: texel (i along r, j along A) at
                              texels[3 * (j * size + i) + channel]; row j = 0 is A = 0 (R_d itself) */
} sss_lut;

SSS_API sss_result sss_lut_build(const sss_profile *profile, const sss_lut_desc *desc, sss_lut *out,
                                 sss_error *err);
SSS_API void sss_lut_free(sss_lut *lut);
/* r_max of the source-function cut-off for a material (Maisch & Ropinski 2020, section 7.1). */
SSS_API double sss_lut_r_max(const sss_material *m, double source_cutoff);
/* (r, A) that texel (i, j) stands for. */
SSS_API double sss_lut_texel_r(const sss_lut *lut, int i);
SSS_API double sss_lut_texel_area(const sss_lut *lut, int j);
/* Bilinear lookup with clamping, as a GPU sampler with the same axes does. */
SSS_API void sss_lut_lookup(const sss_lut *lut, double r, double area, double out[3]);
/* R'_d(r, A) at one point by the build's ring integration with R_d evaluated directly (no table) and
 * finer panels: slow (~1e4 profile evaluations), a reference for checks and for other modules'
 * tests. out = R_d(r) for A = 0; zeros for negative or non-finite input. */
SSS_API void sss_lut_exact(const sss_profile *profile, double r, double area, double out[3]);

/* ---- Separable kernels (Jimenez et al. 2019) ------------------------------------------------------------ */

/* A 1D kernel of `taps` samples, applied horizontally then vertically. Offsets are in the profile's
 * length unit, ascending and symmetric around 0; weights per tap and channel. For the pre-integrated
 * and artist kernels each channel's weights sum to 1 (energy: the profile's total reflectance is
 * applied separately, see `total`). */
typedef struct sss_separable_kernel {
    int taps;
    float *offsets;    /* taps */
    float *weights;    /* taps * 3, weights[3 * k + channel] */
    double total[3];   /* plane integral of the profile per channel (1 for the artist model) */
    double range;      /* half-width covered by the taps */
} sss_separable_kernel;

/* The pre-integrated 1D kernel a_p(x) = integral of R_d(sqrt(x^2 + y^2)) dy (Jimenez et al. 2019, Eq. 4).
 * Its integral over x is ||R_d||_1. An adaptive quadrature per call (~1e3 profile evaluations). */
SSS_API double sss_kernel_preintegrated_eval(const sss_profile *profile, int channel, double x);
/* The same for the three channels at once (one quadrature). */
SSS_API void sss_kernel_preintegrated_eval_rgb(const sss_profile *profile, double x, double out[3]);

/* Discretised a_p / ||R_d||_1 (Eq. 5): tap positions importance-sample the dominant channel (the one
 * with the widest a_p): tap k sits at the quantile (k + 1/2) / taps of its a_p restricted to
 * [-range, range] (so the middle tap is at 0). Each tap's weight integrates every channel's a_p over
 * the tap's interval (midpoints between taps; the outer taps' intervals reach to -inf / +inf, so no
 * energy is lost) divided by the channel's plane integral. taps >= 1 and odd (0 -> 7); range <= 0 ->
 * the radius holding 99.9% of the dominant channel's a_p. ~0.1 s for the PBD profile. */
SSS_API sss_result sss_kernel_preintegrated(const sss_profile *profile, int taps, double range,
                                            sss_separable_kernel *out, sss_error *err);
/* The artist model's a_m, discretised the same way. */
SSS_API sss_result sss_kernel_artist(const sss_artist_params *params, int taps, sss_separable_kernel *out,
                                     sss_error *err);
SSS_API void sss_separable_kernel_free(sss_separable_kernel *k);

/* Rank-N SVD approximation of the profile discretised on a grid x grid raster of half-width extent:
 * cells of side h = 2 extent / grid, centres at -extent + (i + 1/2) h, each holding the integral of
 * R_d(sqrt(x^2 + y^2)) over the cell (not its centre value times h^2, which for an odd grid puts the
 * PBD profile's r -> 0 peak, ~1/r, into the centre cell). So any grid parity works, each cell holds its
 * true energy and the cells sum to the profile's integral over the square. The cell holding r = 0 (and
 * those where R_d varies within a cell) is integrated radially, in rings whose angle inside the cell
 * is in closed form, with panels split at the PBD table's radii; smooth cells by 2- to 6-point tensor
 * Gauss-Legendre. Agrees with the closed form for the six Gaussians to 1e-7 of each cell, and for PBD
 * and the dipole with brute-force quadrature to ~1e-6 of each cell near the origin and of the
 * largest cell anywhere (tests/kernel/test_kernel_cells.c). Cost: ~4500 profile evaluations at grid 24,
 * ~75000 at 256 (the matrix's symmetry leaves 1/8 of the cells to compute). */
typedef struct sss_svd_kernel {
    int grid, rank;
    double extent;
    double *singular_values; /* 3 * grid: all singular values per channel, descending */
    float *vectors;          /* rank * 3 * grid: sqrt(s_k) * u_k per channel (u = v by symmetry),
                                vectors[(k * 3 + channel) * grid + x] */
    float *signs;            /* rank * 3: +1 or -1, signs[k * 3 + channel]. The matrix is symmetric, so
                                v_k = +-u_k: term k of the approximation is signs * a_k(x) a_k(y) with
                                a_k = vectors[k]; -1 only where the matrix has a negative eigenvalue. */
} sss_svd_kernel;

/* grid in [1, 1024], extent > 0, rank in [1, grid]. */
SSS_API sss_result sss_kernel_svd(const sss_profile *profile, int grid, double extent, int rank,
                                  sss_svd_kernel *out, sss_error *err);
SSS_API void sss_svd_kernel_free(sss_svd_kernel *k);

/* Guided rank-1 approximation (Jimenez et al. 2019, Appendix A, Eq. 8-9): the a_s minimising
 *   int Gamma(x, y) (R_d(x, y) - a(x) a(y))^2 dx dy  subject to  ||a||_1^2 = ||R_d||_1,
 *   Gamma(x, y; k) = (x^2 + y^2)^(k/2) (1 - e^(-b x^2)) (1 - e^(-b y^2)),
 * on grid cells of half-width extent (cell centres x_i = -extent + (i + 1/2) 2 extent / grid; the
 * constraint is h sum_i a_i = sqrt(sss_profile_total), h the cell width). R_d(x, y) is each cell's
 * average (its integral as in sss_kernel_svd over h^2; finite for odd grids too), Gamma its value at
 * the cell's centre, a(x) a constant a_i per cell. k emphasises far (large k)
 * or near scattering; b (1 / length^2) the width of the axes Gamma ignores. Gamma gets a floor of 1e-3
 * of its maximum so that a is determined on the axes. out: 3 * grid values, out[channel * grid + i]
 * (densities, 1 / length). grid in [2, 512]; ~grid^2 * iterations work. */
SSS_API sss_result sss_kernel_guided(const sss_profile *profile, int grid, double extent, double k, double b,
                                     double *out, sss_error *err);

#ifdef __cplusplus
}
#endif
#endif
