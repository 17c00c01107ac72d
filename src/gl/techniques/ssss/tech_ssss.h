/* gl/techniques/ssss/tech_ssss.h — internals shared by the separable subsurface scattering techniques (Jimenez et al. 2019):
 * tech_ssss.c (GL passes, technique entries ssss, ssss-gauss6, ssss-svd) and tech_ssss_kernel.c (the
 * per-material kernel data: 1D taps of every separable term, transmittance profiles T(s)).
 *
 * Kernel block (one SSBO of vec4, binding SSSS_SSBO_BINDING, read by src/gl/techniques/ssss/ssss_blur.frag.glsl
 * and ssss_combine.frag.glsl):
 *   [0]                 (terms T, material count, 0, 0)
 *   material m, base b = 1 + m (SSSS_MAT_VEC4 + 2 T):
 *   [b + 0]             rgb: multiplier after the passes (total reflectance, Eq. 5's ||R_d||_1); w: 1
 *                       for a subsurface material, 0 otherwise
 *   [b + 1]             rgb: transmittance scale T(0) / multiplier; w: row of the T(s) table, -1: none
 *   [b + 2]             x: s_max of the T(s) table (scene units)
 *   [b + 3]             reserved
 *   term t:
 *   [b + 4 + 2t]        (first tap vec4 index, tap count, kernel range (scene units), 0)
 *   [b + 5 + 2t]        rgb: sigma of the depth correction (Eq. 7, scene units)
 *   tap k of a term: [first + 2k] = (horizontal weights rgb, offset in scene units),
 *                    [first + 2k + 1] = (vertical weights rgb, 0).
 * The T(s) table: SSSS_TRANS_SIZE texels per row, rgb = T(s) / T(0) at s = s_max i / (size - 1). */
#ifndef SSS_GL_TECH_SSSS_H
#define SSS_GL_TECH_SSSS_H

#include "gl/technique.h"

#define SSSS_SSBO_BINDING 12
#define SSSS_MAT_VEC4 4
#define SSSS_TRANS_SIZE 256

typedef enum ssss_variant {
    SSSS_VARIANT_SEPARABLE = 0, /* one separable term: pre-integrated, artist or guided (Jimenez et al. 2019) */
    SSSS_VARIANT_GAUSS6,        /* six Gaussians, one term each (d'Eon et al. 2007) */
    SSSS_VARIANT_SVD            /* rank-N SVD of the discretised profile (Jimenez et al. 2019, section 3) */
} ssss_variant;

/* Kernel choice of the separable variant (parameter `kernel`). */
enum { SSSS_KERNEL_AUTO = 0, SSSS_KERNEL_PREINTEGRATED, SSSS_KERNEL_ARTIST, SSSS_KERNEL_GUIDED };

typedef struct ssss_kernel_opts {
    ssss_variant variant;
    int kernel;        /* SSSS_KERNEL_* (separable variant) */
    int preset;        /* 0: the material's artist profile; 1..3: Table 2 single-layer, multi-layer, production */
    int taps;          /* odd: taps per 1D pass (separable, gauss6) */
    int rank, grid;    /* svd */
    double guide_k, guide_b_mm; /* guided: Eq. 9's k and b (b in mm^-2) */
} ssss_kernel_opts;

typedef struct ssss_kernel_data {
    int terms, materials;
    int vec4_count;
    float *block;      /* vec4_count * 4 floats */
    int trans_rows;
    float *trans;      /* trans_rows * SSSS_TRANS_SIZE * 4 floats (RGBA) */
} ssss_kernel_data;

/* Builds the block for every material of the context's GPU scene. Errors name the object and the
 * kernel that failed. */
sss_result ssss_kernel_build(const gl_tech_ctx *c, const ssss_kernel_opts *o, ssss_kernel_data *out,
                             sss_error *err);

/* ---- Parameters (technique.h's X(name, type, default, min, max, doc) rows) ----------------------- */

#define SSSS_TAPS(X) \
    X(taps, SSS_GL_PARAM_INT, 7, 1, 63, "importance-sampled taps per 1D pass, odd (Jimenez et al. 2019, section 7: 7)")
#define SSSS_FOLLOW(X)                                                                                            \
    X(follow_surface, SSS_GL_PARAM_BOOL, 1, 0, 1,                                                                 \
      "depth correction of Eq. 7: taps lerp to the centre colour by 1 - e^(-dz^2/2 sigma^2) (SSSS follow surface)")
#define SSSS_ROTATE(X)                                                                                            \
    X(rotation, SSS_GL_PARAM_FLOAT, 0.1, 0, 0.3,                                                                  \
      "per-pixel random rotation of the taps nearer than this fraction of the kernel range (section 6: 10%, 30%)")
#define SSSS_TRANS(X)                                                                                             \
    X(transmittance, SSS_GL_PARAM_BOOL, 1, 0, 1,                                                                  \
      "light through thin parts: T(thickness from the shadow maps) (Jimenez et al. 2010, SSSS reference code)")

/* ssss: one separable kernel */
#define SSSS_PARAMS(X)                                                                                            \
    SSSS_TAPS(X)                                                                                                  \
    X(kernel, SSS_GL_PARAM_INT, 0, 0, 3,                                                                          \
      "0 auto (artist for {\"artist\"} profiles, else pre-integrated); 1 pre-integrated (Eq. 4-5); 2 artist "    \
      "(Eq. 6); 3 guided rank-1 (Appendix A)")                                                                    \
    X(artist_preset, SSS_GL_PARAM_INT, 0, 0, 3,                                                                   \
      "artist kernel: 0 the material's profile (production for others); Table 2: 1 single-layer, 2 multi-layer, " \
      "3 production (s in mm / material scale)")                                                                  \
    X(guide_k, SSS_GL_PARAM_FLOAT, 2, 0, 4, "guided kernel: guide parameter k of Eq. 9 (Appendix A: k ~ 2 fits R_d)") \
    X(guide_b, SSS_GL_PARAM_FLOAT, 50, 1e-3, 1e6, "guided kernel: suppression term b of Eq. 9, mm^-2 (Appendix A: 50)") \
    SSSS_FOLLOW(X) SSSS_ROTATE(X) SSSS_TRANS(X)
/* ssss-gauss6: six Gaussians */
#define SSSS_GAUSS6_PARAMS(X) SSSS_TAPS(X) SSSS_FOLLOW(X) SSSS_ROTATE(X) SSSS_TRANS(X)
/* ssss-svd: rank N */
#define SSSS_SVD_PARAMS(X)                                                                                        \
    X(rank, SSS_GL_PARAM_INT, 3, 1, 8, "rank N of the SVD approximation: 2N 1D passes (Jimenez et al. 2019, section 3: 3)") \
    X(svd_grid, SSS_GL_PARAM_INT, 24, 2, 255,                                                                     \
      "cells per axis of the discretised profile = uniform taps per pass (even: no cell sampled at the profile's " \
      "r = 0 peak)")                                                                                              \
    SSSS_FOLLOW(X) SSSS_ROTATE(X) SSSS_TRANS(X)

GL_PARAM_STRUCT(ssss_params, SSSS_PARAMS);
GL_PARAM_STRUCT(ssss_gauss6_params, SSSS_GAUSS6_PARAMS);
GL_PARAM_STRUCT(ssss_svd_params, SSSS_SVD_PARAMS);

extern const gl_technique gl_technique_ssss, gl_technique_ssss_gauss6, gl_technique_ssss_svd;
void ssss_kernel_data_free(ssss_kernel_data *d);

#endif
