/* sss/material.h — optical materials: Fresnel terms, the measured media table, material parameters.
 *
 * Units: coefficients are per scene unit. Measured media are tabulated in mm^-1 (Jensen et al. 2001)
 * and multiplied by the material's `scale`, the number of millimetres in one scene unit, exactly as
 * PBRT-v3's `subsurface` material does (docs/physics.md §2.2, 2.3). RGB arrays are indexed 0 = R, 1 = G, 2 = B.
 * Nothing here touches GL; nothing allocates.
 */
#ifndef SSS_MATERIAL_H
#define SSS_MATERIAL_H

#include "sss/common.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Accepted range of the relative index of refraction. eta < 1 (a medium optically thinner than its
 * surroundings) is rejected: the Fresnel-moment fits and PBRT's table assume eta >= 1. Above 2.5 PBRT's
 * polynomial fit of FM1 degrades (1 - 2 FM1 turns negative near 2.85 and the table with it). */
#define SSS_ETA_MIN 1.0
#define SSS_ETA_MAX 2.5

/* Accepted range of the extinction sigma_t = sigma_a + sigma_s per scene unit in every channel (after
 * scale). R_d grows as sigma_t^2 and lives in floats in the kernels and renderers; far outside this
 * range the profiles lose all precision (the dipole returns 0 beyond ~1e100, PBD beyond ~1e150) instead
 * of failing. A mean free path of 1e-12 to 1e12 scene units covers any sensible choice of unit. */
#define SSS_SIGMA_T_MIN 1e-12
#define SSS_SIGMA_T_MAX 1e12

/* ---- Fresnel ------------------------------------------------------------------------------- */

/* Unpolarised dielectric Fresnel reflectance for light arriving with cosine cos_theta_i on the eta_i
 * side of an interface to eta_t (PBRT-v3 FrDielectric: a negative cosine means the light arrives from
 * the eta_t side, and the indices are swapped). Total internal reflection returns 1. */
SSS_API double sss_fresnel_dielectric(double cos_theta_i, double eta_i, double eta_t);

/* First and second Fresnel moments, PBRT-v3's polynomial fits (docs/physics.md §1). */
SSS_API double sss_fresnel_moment1(double eta);
SSS_API double sss_fresnel_moment2(double eta);

/* Diffuse Fresnel reflectance F_dr of the classical dipole (Mertens et al. 2003, Table 1). */
SSS_API double sss_fresnel_diffuse_reflectance(double eta);

/* PBRT-v3's normalisation c = 1 - 2 FM1(1/eta) of S_w (docs/physics.md §1); 4 C_phi(1/eta) = c, so the
 * exit constant of the subsurface integral is c_o = F_t(x_o) / (pi c). */
SSS_API double sss_bssrdf_normalization(double eta);

/* ---- Measured media (docs/physics.md §2.3; mm^-1) -------------------------------------------------- */

typedef struct sss_measured_medium {
    const char *name;        /* as PBRT names it, e.g. "Skin1" */
    double sigma_s_prime[3]; /* reduced scattering, mm^-1 */
    double sigma_a[3];       /* absorption, mm^-1 */
} sss_measured_medium;

SSS_API size_t sss_measured_medium_count(void);
SSS_API const sss_measured_medium *sss_measured_medium_at(size_t index);   /* NULL past the end */
SSS_API const sss_measured_medium *sss_measured_medium_find(const char *name); /* case-insensitive; NULL if unknown */

/* ---- Material parameters ------------------------------------------------------------------- */

typedef struct sss_material {
    double sigma_a[3]; /* absorption per scene unit (scale applied) */
    double sigma_s[3]; /* scattering per scene unit (scale applied) */
    double eta;        /* relative index of refraction, [SSS_ETA_MIN, SSS_ETA_MAX] */
    double g;          /* Henyey-Greenstein anisotropy, (-1, 1); 0 for measured media */
} sss_material;

/* PBRT `subsurface` with "name": measured coefficients x scale, g = 0 (sigma_s = sigma_s').
 * Errors: unknown name (the message lists the known ones), scale <= 0 or not finite, eta out of range. */
SSS_API sss_result sss_material_from_medium(const char *name, double scale, double eta, sss_material *out,
                                            sss_error *err);

/* PBRT `subsurface` with explicit coefficients (per scene unit before scale).
 * Errors: negative or non-finite coefficients, sigma_a + sigma_s == 0 in a channel, scale <= 0, eta or g
 * out of range. */
SSS_API sss_result sss_material_from_coefficients(const double sigma_a[3], const double sigma_s[3], double scale,
                                                  double eta, double g, sss_material *out, sss_error *err);

/* Checks a filled material (finite, non-negative, sigma_t in [SSS_SIGMA_T_MIN, SSS_SIGMA_T_MAX], eta
 * and g in range). The constructors below validate their result with it. */
SSS_API sss_result sss_material_validate(const sss_material *m, sss_error *err);

#ifdef __cplusplus
}
#endif
#endif
