/* gl/tech_ssss.h — internals shared by the separable subsurface scattering techniques (Jimenez et al. 2019):
 * tech_ssss.c (GL passes, technique entries ssss, ssss-gauss6, ssss-svd) and tech_ssss_kernel.c (the
 * per-material kernel data: 1D taps of every separable term, transmittance profiles T(s)).
 *
 * Kernel block (one SSBO of vec4, binding SSSS_SSBO_BINDING, read by src/gl/ssss/ssss_blur.frag.glsl
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

#include "gl/gl_internal.h"

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

/* Builds the block for every material of the renderer's GPU scene. Errors name the object and the
 * kernel that failed. */
sss_result ssss_kernel_build(const sss_gl_renderer *r, const ssss_kernel_opts *o, ssss_kernel_data *out,
                             sss_error *err);
void ssss_kernel_data_free(ssss_kernel_data *d);

#endif
