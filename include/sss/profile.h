/* sss/profile.h — radial diffusion profiles R_d(r) and the Gaussian kernels of the real-time models.
 *
 * Does: the classical dipole (Jensen et al. 2001; Mertens et al. 2003, Table 1) with its closed-form total
 * reflectance and exact importance sampling (Mertens et al. 2003, section 4); the Photon Beam Diffusion table
 * exactly as PBRT-v3 builds and evaluates it (docs/physics.md §2.2), except that rows whose rho_eff PBRT lets
 * exceed 1 (albedo near 1 with eta near 1 or g < 0) are scaled to conserve energy; the six-Gaussian skin fit (d'Eon 2007)
 * and the artist-friendly two-Gaussian model (Jimenez et al. 2019, Eq. 6, Table 2).
 * Does not: directional terms (Fresnel factors and 1/pi live with the caller), GL, allocation
 * (sss_pbd_table is a plain struct the caller owns).
 *
 * R_d(r) is "S_r(r)" in PBRT's words: per scene unit^2, before the 1/pi and Fresnel factors, such that
 * the plane integral  int_0^inf R_d(r) 2 pi r dr  is the total diffuse reflectance (rho_eff).
 */
#ifndef SSS_PROFILE_H
#define SSS_PROFILE_H

#include "sss/common.h"
#include "sss/material.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- Classical dipole, one channel ---------------------------------------------------------- */

typedef struct sss_dipole {
    double sigma_tr, z_r, z_v, alpha_prime, sigma_t_prime;
} sss_dipole;

/* sigma_s_prime = sigma_s (1 - g). */
SSS_API void sss_dipole_init(sss_dipole *d, double sigma_a, double sigma_s_prime, double eta);
SSS_API double sss_dipole_rd(const sss_dipole *d, double r);
/* Closed form of the plane integral: alpha'/2 (e^(-sigma_tr z_r) + e^(-sigma_tr z_v)). */
SSS_API double sss_dipole_total_reflectance(const sss_dipole *d);
/* Exact importance sampling of R_d(r) 2 pi r (Mertens et al. 2003, section 4): u_source picks the real or the
 * virtual source, u_radius inverts that source's radial CDF by Newton iteration on u. */
SSS_API double sss_dipole_sample_radius(const sss_dipole *d, double u_source, double u_radius);
/* Density of r (per unit length, integrates to 1 over [0, inf)) of sss_dipole_sample_radius. */
SSS_API double sss_dipole_pdf_radius(const sss_dipole *d, double r);

/* ---- Photon Beam Diffusion table (PBRT-v3 BSSRDFTable + ComputeBeamDiffusionBSSRDF) -------- */

#define SSS_PBD_ALBEDOS 100
#define SSS_PBD_RADII 64

typedef struct sss_pbd_table {
    double eta, g;
    double rho[SSS_PBD_ALBEDOS];                          /* single-scattering albedos */
    double radius[SSS_PBD_RADII];                         /* optical radii */
    double profile[SSS_PBD_ALBEDOS * SSS_PBD_RADII];      /* 2 pi r (SS + MS), row i = albedo i */
    double rho_eff[SSS_PBD_ALBEDOS];                      /* integral of each row over r */
    double profile_cdf[SSS_PBD_ALBEDOS * SSS_PBD_RADII];  /* running integral of each row */
} sss_pbd_table;

/* Builds the table for a relative index eta and anisotropy g (about 100 kB; caller allocates it). */
SSS_API sss_result sss_pbd_table_build(double eta, double g, sss_pbd_table *table, sss_error *err);

/* S_r(r) of one channel for coefficients in scene units, exactly as PBRT-v3 TabulatedBSSRDF::Sr:
 * Catmull-Rom in (rho, r sigma_t), divided by 2 pi r_opt (when r_opt > 0), times sigma_t^2, >= 0.
 * At r = 0 this returns the limit r -> 0+ (PBRT returns 0 there: an artefact of storing 2 pi r S): on
 * [0, r_1] the spline through the stored 2 pi r S is t f_1 + O(t^2), t = r_opt / r_1, so the limit is
 * the albedo-interpolated S at the first non-zero node r_1 = 0.0025, times sigma_t^2. */
SSS_API double sss_pbd_sr(const sss_pbd_table *table, double sigma_a, double sigma_s, double r);
/* rho_eff for a single-scattering albedo rho (Catmull-Rom in the table's albedos). */
SSS_API double sss_pbd_rho_eff(const sss_pbd_table *table, double rho);
/* The albedo rho whose rho_eff is the given value (PBRT InvertCatmullRom); clamps to the table. */
SSS_API double sss_pbd_invert_rho_eff(const sss_pbd_table *table, double rho_eff);
/* Importance sampling of r ~ R_d(r) 2 pi r (PBRT SampleCatmullRom2D); returns < 0 when the profile
 * is zero (an albedo of 0). */
SSS_API double sss_pbd_sample_radius(const sss_pbd_table *table, double sigma_a, double sigma_s, double u);
/* Density of r (per unit length) of sss_pbd_sample_radius. */
SSS_API double sss_pbd_pdf_radius(const sss_pbd_table *table, double sigma_a, double sigma_s, double r);

/* PBRT `kdsubsurface`: coefficients from the multiple-scattering albedo (each in (0, 1)) and the mean
 * free path (scene units, > 0) by inverting rho_eff (PBRT SubsurfaceFromDiffuse). */
SSS_API sss_result sss_material_from_reflectance(const sss_pbd_table *table, const double reflectance[3],
                                                 const double mfp[3], double eta, sss_material *out,
                                                 sss_error *err);

/* ---- Gaussian profiles ---------------------------------------------------------------------- */

/* Normalised 2D Gaussian of variance v: e^(-r^2 / 2v) / (2 pi v). */
SSS_API double sss_gaussian_2d(double variance, double r);

/* d'Eon et al. 2007 six-Gaussian skin fit (docs/physics.md §2.4), variances in mm^2. */
#define SSS_GAUSS6_TERMS 6
extern SSS_API const double sss_gauss6_variance_mm2[SSS_GAUSS6_TERMS];
extern SSS_API const double sss_gauss6_weight[3][SSS_GAUSS6_TERMS];

/* Artist-friendly separable model (Jimenez et al. 2019, Eq. 6): a_m(x) = w G(x, sigma_n) + (1 - w) G(x, sigma_f),
 * sigma_n = near * s, sigma_f = far * s, G(x, sigma) = e^(-x^2 / 2 sigma^2) / (sqrt(2 pi) sigma)
 * We use the normalised 1D Gaussian so that A_m(x, y) = a_m(x) a_m(y) integrates to 1 over the plane;
 * the paper prints the factor as 1/(2 pi sigma), which integrates to neither 1 in 1D nor in 2D. */
typedef struct sss_artist_params {
    double s;        /* global scale, in the caller's length unit */
    double near[3];  /* sigma_n' per channel, [0, 1] */
    double far[3];   /* sigma_f' per channel, [0, 1] */
    double w;        /* weight of the near Gaussian, [0, 1] */
} sss_artist_params;

/* Presets of Jimenez et al. 2019, Table 2 (s in mm): "single-layer", "multi-layer", "production".
 * Returns SSS_ERROR_INVALID_ARGUMENT for an unknown name. */
SSS_API sss_result sss_artist_preset(const char *name, sss_artist_params *out, sss_error *err);
SSS_API double sss_artist_eval_1d(const sss_artist_params *p, int channel, double x); /* a_m(x) */

/* ---- One radial profile for all the kernel builders ----------------------------------------- */

typedef enum sss_profile_model {
    SSS_PROFILE_PBD = 0,  /* Photon Beam Diffusion table (PBRT), the default */
    SSS_PROFILE_DIPOLE,   /* classical dipole */
    SSS_PROFILE_GAUSS6    /* six-Gaussian skin fit (material ignored but for gauss6_mm_per_unit) */
} sss_profile_model;

typedef struct sss_profile {
    sss_profile_model model;
    sss_material material;
    const sss_pbd_table *table;  /* PBD: borrowed, built for material.eta and material.g */
    sss_dipole dipole[3];        /* DIPOLE: per channel */
    double gauss6_mm_per_unit;   /* GAUSS6: millimetres per scene unit; init sets 1, change it after */
} sss_profile;

/* table is required for SSS_PROFILE_PBD and must match the material's eta and g. m is validated for
 * PBD and DIPOLE; for GAUSS6 it may be NULL. Sets gauss6_mm_per_unit = 1 (assign it afterwards). */
SSS_API sss_result sss_profile_init(sss_profile *p, sss_profile_model model, const sss_material *m,
                                    const sss_pbd_table *table, sss_error *err);
SSS_API double sss_profile_eval(const sss_profile *p, int channel, double r);     /* R_d(r), >= 0 */
SSS_API void sss_profile_eval_rgb(const sss_profile *p, double r, double out[3]);
SSS_API double sss_profile_total(const sss_profile *p, int channel);             /* plane integral */
/* Radius within which the given fraction (e.g. 0.999) of the channel's plane integral lies: closed-form
 * CDF + bisection for DIPOLE and GAUSS6 (fraction capped at 1 - 1e-12); for PBD the table's inverse CDF
 * (PBRT Sample_Sr), and fraction >= 1 gives the table's last radius. 0 for fraction <= 0 or a zero
 * profile. */
SSS_API double sss_profile_radius_for_fraction(const sss_profile *p, int channel, double fraction);
/* The reach of a profile: the largest radius over the three channels within which `fraction` of each
 * channel's plane integral lies (sss_profile_radius_for_fraction), non-finite radii left out; 0 when none
 * is finite and positive. */
SSS_API double sss_profile_reach(const sss_profile *p, double fraction);

/* A measured medium ready to evaluate (what `sss profile`, `sss lut` and `sss kernel` take): its
 * coefficients at `scale` and `eta` (sss_material_from_medium), the PBD table for them (model PBD: built
 * and owned here; NULL for the dipole) and the profile, which borrows the table. Release with
 * sss_medium_profile_free (also after a failed init: out is then empty). */
typedef struct sss_medium_profile {
    sss_material material;
    sss_pbd_table *table;
    sss_profile profile;
} sss_medium_profile;
SSS_API sss_result sss_medium_profile_init(sss_medium_profile *out, const char *medium, double scale, double eta,
                                           sss_profile_model model, sss_error *err);
SSS_API void sss_medium_profile_free(sss_medium_profile *p);

#ifdef __cplusplus
}
#endif
#endif
