/* gl/techniques/burley/tech_burley.h — screen-space subsurface scattering with Burley's normalized
 * diffusion profile, as Unity HDRP, Blender EEVEE and Unreal ship it (Christensen & Burley 2015,
 * "Approximate Reflectance Profiles for Efficient Subsurface Scattering"; Golubev 2018, "Efficient
 * Screen-Space Subsurface Scattering Using Burley's Normalized Diffusion in Real-Time"; docs/burley.md).
 *
 * Internals shared by tech_burley.c (the GL passes) and burley_fit.c (the profile, its CDF and inverse,
 * the transmittance integral, the fits of A and d to a material, the per-material block).
 *
 * The profile, per channel, with A the surface albedo (the total diffuse reflectance) and d a length:
 *     R(r) = A (e^(-r/d) + e^(-r/(3d))) / (8 pi d r),    int_0^inf R(r) 2 pi r dr = A
 * (Christensen & Burley 2015, section 3; they write d = l / s, s a scaling factor of the albedo). Its radial CDF (the fraction of the
 * energy within r), with x = r / d:  F(x) = 1 - e^(-x)/4 - 3 e^(-x/3)/4, inverted in closed form
 * (burley_inverse_cdf). The transmittance through a slab of thickness t lit uniformly from behind,
 * int R(sqrt(r^2 + t^2)) dA = A (1 - F(t/d)) = A/4 (e^(-t/d) + 3 e^(-t/(3d))).
 *
 * Material block (SSBO of vec4 at BURLEY_SSBO_BINDING, BURLEY_MAT_VEC4 per GL material record):
 *   [3m + 0]  rgb: A; w: 1 for a subsurface material, 0 otherwise
 *   [3m + 1]  rgb: 1/d per channel (per scene unit); w: d of the widest channel (the one sampled)
 *   [3m + 2]  x: the kernel radius (scene units), holding `filter_cdf` of the widest channel's energy */
#ifndef SSS_GL_TECH_BURLEY_H
#define SSS_GL_TECH_BURLEY_H

#include "gl/technique.h"
#include "sss/profile.h"

#define BURLEY_SSBO_BINDING 12
#define BURLEY_MAT_VEC4 3

/* How d follows from the material (parameter `fit`). */
typedef enum burley_fit_kind {
    BURLEY_FIT_SEARCHLIGHT = 0, /* Christensen & Burley 2015's fit for perpendicular illumination (the
                                   "searchlight" configuration) and the mean free path l = 1 / sigma_t:
                                   s = 1.85 - A + 7 |A - 0.8|^3, d = l / s */
    BURLEY_FIT_DIFFUSE,         /* their fit for diffuse surface transmission: s = 1.9 - A + 3.5 (A - 0.8)^2,
                                   d = l / s */
    BURLEY_FIT_DMFP,            /* their fit for the searchlight configuration and the diffuse mean free path
                                   l_d = 1 / sigma_tr, sigma_tr = sqrt(3 sigma_a sigma_t'): s = 3.5 + 100 (A - 0.33)^4,
                                   d = l_d / s */
    BURLEY_FIT_PROFILE,         /* d of least distance to the material's own profile (burley_tv_distance) */
    BURLEY_FIT_COUNT
} burley_fit_kind;

/* Transmission through thin parts (parameter `transmission`). */
enum { BURLEY_TRANS_OFF = 0, BURLEY_TRANS_THICK, BURLEY_TRANS_THIN };

/* ---- Parameters (technique.h's X(name, type, default, min, max, doc) rows) ----------------------- */

#define BURLEY_PARAMS(X)                                                                                          \
    X(samples, SSS_GL_PARAM_INT, 40, 1, 1024,                                                                     \
      "sample budget: at most this many samples per pixel (HDRP's quality levels: 20 low, 40 medium, 80 high)")   \
    X(pixels_per_sample, SSS_GL_PARAM_FLOAT, 4, 0.25, 1024,                                                       \
      "samples = the kernel disc's area in output pixels / this, capped at `samples`; under one sample the pixel " \
      "keeps its own light (HDRP's SSS_PIXELS_PER_SAMPLE: 4)")                                                    \
    X(filter_cdf, SSS_GL_PARAM_FLOAT, 0.997, 0.5, 0.999999,                                                       \
      "the kernel radius holds this fraction of the widest channel's energy (HDRP: 0.997)")                       \
    X(fit, SSS_GL_PARAM_INT, 3, 0, 3,                                                                              \
      "d from the material (Christensen & Burley 2015): 0 perpendicular illumination, mean free path; 1 diffuse "  \
      "surface transmission; 2 perpendicular, diffuse mean free path; 3 nearest to the material's own profile") \
    X(rotation, SSS_GL_PARAM_BOOL, 1, 0, 1,                                                                       \
      "a per-pixel random rotation of the golden-angle pattern (HDRP's SSS_RANDOM_ROTATION)")                     \
    X(bilateral, SSS_GL_PARAM_BOOL, 0, 0, 1,                                                                      \
      "samples weighted by R(sqrt(r^2 + dz^2)), dz the depth difference (HDRP's SSS_BILATERAL_FILTER)")            \
    X(center, SSS_GL_PARAM_BOOL, 1, 0, 1,                                                                         \
      "1: the pixel's own disc (radius sqrt(area / pi)) integrated exactly and the samples drawn beyond it; "     \
      "0: every sample from the whole profile (HDRP)")                                                            \
    X(transmission, SSS_GL_PARAM_INT, 1, 0, 2,                                                                    \
      "light through thin parts, with the profile's transmittance A/4 (e^(-t/d) + 3 e^(-t/3d)): 0 off; 1 thick, t " \
      "from the light's shadow map (HDRP); 2 thin, t = `thickness`")                                              \
    X(thickness, SSS_GL_PARAM_FLOAT, 0.1, 0, 1e30, "thin transmission: the thickness t, scene units")             \
    X(transmission_wrap, SSS_GL_PARAM_FLOAT, 0.2588, 0, 1,                                                        \
      "back-side cosine wrapped by w: (-n.l + w) / (1 + w)^2 (HDRP: w = sin 15 deg = 0.2588; 0: max(-n.l, 0))")

GL_PARAM_STRUCT(burley_params, BURLEY_PARAMS);

/* Its state (tests read tex_scatter: rgb the scattered light, a the sample count per pixel). */
typedef struct burley_state {
    GLuint prog_prep, prog_scatter, prog_resolve;
    GLuint ssbo, samp_cube, samp_2d;
    GLuint tex_signal, tex_scatter, fbo_signal, fbo_scatter;
    int width, height;
    double built_fit, built_cdf; /* the parameters the block was built with */
    int have_block;
    size_t target_bytes, block_bytes;
} burley_state;

/* ---- The profile (burley_fit.c) ------------------------------------------------------------------ */

/* R(r) of one channel. */
double burley_profile(double A, double d, double r);
/* F(x), x = r / d: the fraction of the energy within r. */
double burley_cdf(double x);
/* x with F(x) = u, u in [0, 1): closed form (the cubic in e^(-x/3)). */
double burley_inverse_cdf(double u);
/* A (1 - F(t / d)): the light through a slab of thickness t per unit irradiance behind it. */
double burley_transmittance(double A, double d, double t);
/* s(A) of a Christensen & Burley 2015 fit (BURLEY_FIT_SEARCHLIGHT, _DIFFUSE, _DMFP). */
double burley_scale_factor(burley_fit_kind fit, double A);
/* The total variation distance between the radial distributions of Burley's profile (length d) and
 * of channel c of p, both normalised: 1/2 int |2 pi r (R_B / A_B - R_p / A_p)| dr, in [0, 1]. */
double burley_tv_distance(const sss_profile *p, int c, double d);

/* A and d of a material's three channels under a fit: A from the material's resolved profile (its
 * total diffuse reflectance), d from sigma_t (or sigma_tr) and the fit. Fails with SSS_ERROR_NUMERIC
 * on a channel without a finite, positive A or d. */
sss_result burley_fit_material(const sss_scene_material *m, burley_fit_kind fit, double A[3], double d[3],
                               sss_error *err);

/* The material block (layout above) for every GL material record of the context's scene:
 * n_vec4 = BURLEY_MAT_VEC4 x the records; *out is malloc'ed. Errors name the object. */
sss_result burley_block_build(const gl_tech_ctx *c, float **out, int *n_vec4, sss_error *err);

#endif
