/* physics/pbd.c — the Photon Beam Diffusion profile table, built, evaluated and sampled exactly as
 * PBRT-v3 does (docs/physics.md §2.2; pbrt-v3 core/bssrdf.cpp: BeamDiffusionMS, BeamDiffusionSS,
 * ComputeBeamDiffusionBSSRDF, TabulatedBSSRDF::Sr / Sample_Sr / Pdf_Sr, SubsurfaceFromDiffuse).
 *
 * One difference in value: where PBRT's rho_eff exceeds 1, the rows nearest albedo 1 are scaled to
 * conserve energy (see conserve_energy). The others change no value beyond float rounding: double
 * precision; the 100 depth samples -ln(1 - (i + 0.5)/100) are computed once per build; the
 * single-scattering term is computed once per radius and scaled by rho (in optical units sigma_t = 1,
 * so BeamDiffusionSS is exactly rho times a function of r alone); S_r(0) returns the r -> 0+ limit
 * (see sss_pbd_sr). */
#include "sss/profile.h"

#include <math.h>

#include "physics/catmull_rom.h"

#define PI 3.14159265358979323846
#define N_SAMPLES 100 /* PBRT's nSamples in BeamDiffusionMS/SS */

/* PBRT-v3 PhaseHG (its sign convention: cos_theta between the two propagation directions). */
static double phase_hg(double cos_theta, double g)
{
    double denom = 1.0 + g * g + 2.0 * g * cos_theta;
    return (1.0 - g * g) / (4.0 * PI * denom * sqrt(denom));
}

/* BeamDiffusionSS / rho with sigma_t = 1 (docs/physics.md §2.2, single scattering). */
static double single_scattering_unit(double g, double eta, double r, const double *depth)
{
    double t_crit = r * sqrt(eta * eta - 1.0);
    double sum = 0.0;
    for (int i = 0; i < N_SAMPLES; i++) {
        double t = t_crit + depth[i];
        double d = sqrt(r * r + t * t);
        double cos_o = t / d;
        sum += exp(-(d + t_crit)) / (d * d) * phase_hg(cos_o, g) *
               (1.0 - sss_fresnel_dielectric(-cos_o, 1.0, eta)) * fabs(cos_o);
    }
    return sum / N_SAMPLES;
}

/* Per-albedo constants of BeamDiffusionMS (docs/physics.md §2.2, multiple scattering). */
typedef struct ms_params {
    double sigmap_t, rhop, D_g, sigma_tr, z_e, c_phi, c_E;
} ms_params;

static ms_params ms_setup(double sigma_s, double sigma_a, double g, double eta)
{
    ms_params p;
    double sigmap_s = sigma_s * (1.0 - g);
    p.sigmap_t = sigma_a + sigmap_s;
    p.rhop = sigmap_s / p.sigmap_t;
    /* Non-classical diffusion coefficient D_G (Grosjean; pbrt Eq. 15.24). */
    p.D_g = (2.0 * sigma_a + sigmap_s) / (3.0 * p.sigmap_t * p.sigmap_t);
    p.sigma_tr = sqrt(sigma_a / p.D_g);
    double fm1 = sss_fresnel_moment1(eta), fm2 = sss_fresnel_moment2(eta);
    /* Extrapolation distance (pbrt Eq. 15.28) and exitance factors (Eqs. 15.31, 15.32). */
    p.z_e = -2.0 * p.D_g * (1.0 + 3.0 * fm2) / (1.0 - 2.0 * fm1);
    p.c_phi = 0.25 * (1.0 - 2.0 * fm1);
    p.c_E = 0.5 * (1.0 - 3.0 * fm2);
    return p;
}

static double multiple_scattering(const ms_params *p, double r, const double *depth)
{
    double sum = 0.0;
    double k = 1.0 / (4.0 * PI);
    for (int i = 0; i < N_SAMPLES; i++) {
        double z_r = depth[i] / p->sigmap_t; /* real source depth, exponentially distributed */
        double z_v = -z_r + 2.0 * p->z_e;
        double d_r = sqrt(r * r + z_r * z_r), d_v = sqrt(r * r + z_v * z_v);
        double e_r = exp(-p->sigma_tr * d_r), e_v = exp(-p->sigma_tr * d_v);
        /* Dipole fluence and vector irradiance (pbrt Eq. 15.27). */
        double phi_D = k / p->D_g * (e_r / d_r - e_v / d_v);
        double E_DN = k * (z_r * (1.0 + p->sigma_tr * d_r) * e_r / (d_r * d_r * d_r) -
                           z_v * (1.0 + p->sigma_tr * d_v) * e_v / (d_v * d_v * d_v));
        double E = phi_D * p->c_phi + E_DN * p->c_E;
        double kappa = 1.0 - exp(-2.0 * p->sigmap_t * (d_r + z_r));
        sum += kappa * p->rhop * p->rhop * E;
    }
    return sum / N_SAMPLES;
}

/* Energy conservation. With no absorption (albedo 1) every photon that enters a half-space leaves it
 * again, so the plane integral of S_r is exactly 1 there and below 1 for any albedo < 1. PBRT's sum of
 * single scattering and the diffusion term overshoots near albedo 1 (rho_eff 1.085 at eta 1, 1.019 at
 * eta 1.33, docs/physics.md §1). When it does, rows above x0 = 2 - rho_max are remapped to
 * x0 + (rho_eff - x0) / 2: continuous, still strictly rising with the albedo (so SubsurfaceFromDiffuse
 * stays invertible), exactly 1 at albedo 1. Each remapped row keeps its shape (profile and CDF are
 * scaled together, so sampling is unchanged); every row at or below x0 is PBRT's exactly, which covers
 * albedos up to 0.9998 at eta 1.33 and 0.995 at eta 1 (g = 0). */
static void conserve_energy(sss_pbd_table *t)
{
    double rho_max = t->rho_eff[SSS_PBD_ALBEDOS - 1]; /* rho_eff rises with the albedo */
    if (!(rho_max > 1.0)) return;
    double x0 = 2.0 - rho_max;
    for (int i = 0; i < SSS_PBD_ALBEDOS; i++) {
        if (!(t->rho_eff[i] > x0)) continue;
        double target = x0 + 0.5 * (t->rho_eff[i] - x0), s = target / t->rho_eff[i];
        for (int j = 0; j < SSS_PBD_RADII; j++) {
            t->profile[i * SSS_PBD_RADII + j] *= s;
            t->profile_cdf[i * SSS_PBD_RADII + j] *= s;
        }
        t->rho_eff[i] = target;
    }
}

sss_result sss_pbd_table_build(double eta, double g, sss_pbd_table *t, sss_error *err)
{
    if (!t) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "PBD table is NULL");
    if (!isfinite(eta) || eta < SSS_ETA_MIN || eta > SSS_ETA_MAX)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "PBD table: eta = %g is outside [%g, %g]",
                             eta, SSS_ETA_MIN, SSS_ETA_MAX);
    if (!isfinite(g) || g <= -1.0 || g >= 1.0)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "PBD table: g = %g is outside (-1, 1)", g);
    /* PBRT's Fresnel-moment fits leave their fitted range near eta 2.5 and c_phi = (1 - 2 FM1)/4 turns
     * negative at eta ~ 2.85 (the exact moment integral stays positive), which makes the whole table
     * negative. Refuse rather than return a non-physical profile. */
    double cphi4 = 1.0 - 2.0 * sss_fresnel_moment1(eta), ce2 = 1.0 - 3.0 * sss_fresnel_moment2(eta);
    if (!(cphi4 > 0.0 && ce2 > 0.0))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                             "PBD table: eta = %g is beyond the range of PBRT's Fresnel-moment fits "
                             "(1 - 2 FM1 = %.4g, 1 - 3 FM2 = %.4g; use eta <= 2.8)",
                             eta, cphi4, ce2);
    t->eta = eta;
    t->g = g;

    /* Radii: 0, 2.5e-3, then x1.2 (ComputeBeamDiffusionBSSRDF). */
    t->radius[0] = 0.0;
    t->radius[1] = 2.5e-3;
    for (int j = 2; j < SSS_PBD_RADII; j++) t->radius[j] = t->radius[j - 1] * 1.2;
    /* Albedos: (1 - e^(-8 i/(n-1))) / (1 - e^(-8)), dense near 1 where profiles change fastest. */
    for (int i = 0; i < SSS_PBD_ALBEDOS; i++)
        t->rho[i] = -expm1(-8.0 * i / (double)(SSS_PBD_ALBEDOS - 1)) / -expm1(-8.0);

    /* Exponential depth samples -ln(1 - (i + .5)/n) shared by SS and MS. */
    double depth[N_SAMPLES];
    for (int i = 0; i < N_SAMPLES; i++) depth[i] = -log1p(-(i + 0.5) / N_SAMPLES);
    double ss_unit[SSS_PBD_RADII];
    for (int j = 0; j < SSS_PBD_RADII; j++) ss_unit[j] = single_scattering_unit(g, eta, t->radius[j], depth);

    for (int i = 0; i < SSS_PBD_ALBEDOS; i++) {
        double rho = t->rho[i];
        double *row = &t->profile[i * SSS_PBD_RADII];
        /* Optical units: sigma_s = rho, sigma_a = 1 - rho. */
        ms_params p = ms_setup(rho, 1.0 - rho, g, eta);
        for (int j = 0; j < SSS_PBD_RADII; j++) {
            double r = t->radius[j];
            double v = 2.0 * PI * r * (rho * ss_unit[j] + multiple_scattering(&p, r, depth));
            if (!isfinite(v))
                return sss_error_set(err, SSS_ERROR_NUMERIC,
                                     "PBD table: non-finite profile at albedo %g, radius %g (eta %g, g %g)",
                                     rho, r, eta, g);
            row[j] = v;
        }
        /* rho_eff and the CDF for sampling (IntegrateCatmullRom). */
        t->rho_eff[i] = cr_integrate(SSS_PBD_RADII, t->radius, row, &t->profile_cdf[i * SSS_PBD_RADII]);
    }
    conserve_energy(t);
    return SSS_OK;
}

/* Catmull-Rom weights of one channel: returns 0 if rho or r_opt lies outside the table. */
static int channel_weights(const sss_pbd_table *t, double rho, double r_opt, int *ro, double rw[4],
                           int *xo, double xw[4])
{
    return cr_weights(SSS_PBD_ALBEDOS, t->rho, rho, ro, rw) &&
           cr_weights(SSS_PBD_RADII, t->radius, r_opt, xo, xw);
}

/* The albedo-interpolated table value (2 pi r_opt S in optical units) at r_opt. Below 1e-9 of the
 * first non-zero radius, returns the value divided by 2 pi r_opt, taken to its limit r_opt -> 0+:
 * on [0, r_1] PBRT's spline through profile[.][0] = 0 is f(t) = (t + t^2 - t^3) f_1 + (t^3 - t^2) k f_2
 * with t = r_opt / r_1, so f / (2 pi r_opt) -> f_1 / (2 pi r_1), i.e. the interpolated S at r_1. */
static double interpolated_sr(const sss_pbd_table *t, double rho, double r_opt, int *ok)
{
    int ro, xo;
    double rw[4], xw[4];
    *ok = 0;
    if (r_opt < 1e-9 * t->radius[1]) {
        if (!cr_weights(SSS_PBD_ALBEDOS, t->rho, rho, &ro, rw)) return 0.0;
        double f1 = 0.0;
        for (int i = 0; i < 4; i++)
            if (rw[i] != 0.0) f1 += rw[i] * t->profile[(ro + i) * SSS_PBD_RADII + 1];
        *ok = 1;
        return f1 / (2.0 * PI * t->radius[1]);
    }
    if (!channel_weights(t, rho, r_opt, &ro, rw, &xo, xw)) return 0.0;
    double sr = 0.0;
    for (int i = 0; i < 4; i++) {
        if (rw[i] == 0.0) continue;
        for (int j = 0; j < 4; j++)
            if (xw[j] != 0.0) sr += rw[i] * xw[j] * t->profile[(ro + i) * SSS_PBD_RADII + xo + j];
    }
    *ok = 1;
    return sr / (2.0 * PI * r_opt);
}

double sss_pbd_sr(const sss_pbd_table *t, double sigma_a, double sigma_s, double r)
{
    double sigma_t = sigma_a + sigma_s;
    if (!t || !(sigma_t > 0.0) || !isfinite(sigma_t) || !isfinite(r) || sigma_s < 0.0) return 0.0;
    double rho = sigma_s / sigma_t;
    int ok;
    /* TabulatedBSSRDF::Sr: interpolate in (rho, r sigma_t), cancel 2 pi r_opt, scale to scene units. */
    double sr = interpolated_sr(t, rho, fabs(r) * sigma_t, &ok) * sigma_t * sigma_t;
    return ok && sr > 0.0 && isfinite(sr) ? sr : 0.0;
}

double sss_pbd_rho_eff(const sss_pbd_table *t, double rho)
{
    if (!t) return 0.0;
    double v = cr_eval(SSS_PBD_ALBEDOS, t->rho, t->rho_eff, rho);
    return v > 0.0 ? v : 0.0;
}

double sss_pbd_invert_rho_eff(const sss_pbd_table *t, double rho_eff)
{
    if (!t || !(rho_eff == rho_eff)) return 0.0;
    return cr_invert(SSS_PBD_ALBEDOS, t->rho, t->rho_eff, rho_eff);
}

double sss_pbd_sample_radius(const sss_pbd_table *t, double sigma_a, double sigma_s, double u)
{
    double sigma_t = sigma_a + sigma_s;
    if (!t || !(sigma_t > 0.0) || !isfinite(sigma_t) || !(sigma_s >= 0.0)) return -1.0;
    if (!(u >= 0.0)) u = 0.0;
    if (u > 1.0) u = 1.0;
    double pdf = 0.0;
    /* TabulatedBSSRDF::Sample_Sr: invert the albedo-interpolated CDF in optical units. */
    double r_opt = cr_sample_2d(SSS_PBD_ALBEDOS, SSS_PBD_RADII, t->rho, t->radius, t->profile,
                                t->profile_cdf, sigma_s / sigma_t, u, NULL, &pdf);
    if (!(pdf > 0.0) && !(r_opt > 0.0)) {
        /* cr_sample_2d returns 0 with pdf 0 when the interpolated profile has no mass. */
        double total = sss_pbd_rho_eff(t, sigma_s / sigma_t);
        if (!(total > 0.0)) return -1.0;
    }
    return r_opt / sigma_t;
}

double sss_pbd_pdf_radius(const sss_pbd_table *t, double sigma_a, double sigma_s, double r)
{
    double sigma_t = sigma_a + sigma_s;
    if (!t || !(sigma_t > 0.0) || !isfinite(sigma_t) || !(r >= 0.0) || !isfinite(r)) return 0.0;
    double rho = sigma_s / sigma_t, r_opt = r * sigma_t;
    int ro, xo;
    double rw[4], xw[4];
    if (!channel_weights(t, rho, r_opt, &ro, rw, &xo, xw)) return 0.0;
    /* Pdf_Sr times 2 pi r: the interpolated 2 pi r_opt S over the interpolated rho_eff, per unit r. */
    double f = 0.0, total = 0.0;
    for (int i = 0; i < 4; i++) {
        if (rw[i] == 0.0) continue;
        total += rw[i] * t->rho_eff[ro + i];
        for (int j = 0; j < 4; j++)
            if (xw[j] != 0.0) f += rw[i] * xw[j] * t->profile[(ro + i) * SSS_PBD_RADII + xo + j];
    }
    if (!(total > 0.0)) return 0.0;
    double p = f * sigma_t / total;
    return p > 0.0 && isfinite(p) ? p : 0.0;
}

sss_result sss_material_from_reflectance(const sss_pbd_table *t, const double reflectance[3],
                                         const double mfp[3], double eta, sss_material *out,
                                         sss_error *err)
{
    static const char *const ch[3] = {"R", "G", "B"};
    if (!t || !reflectance || !mfp || !out)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "material from reflectance: NULL argument");
    if (t->eta != eta)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                             "material from reflectance: the PBD table was built for eta %g, not %g",
                             t->eta, eta);
    sss_material m;
    for (int c = 0; c < 3; c++) {
        if (!(reflectance[c] > 0.0 && reflectance[c] < 1.0))
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                                 "%s channel: reflectance %g is outside (0, 1)", ch[c], reflectance[c]);
        if (!(mfp[c] > 0.0) || !isfinite(mfp[c]))
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                                 "%s channel: mean free path %g must be a finite number > 0", ch[c], mfp[c]);
        /* SubsurfaceFromDiffuse: albedo from rho_eff, sigma_t = 1/mfp (kdsubsurface). */
        double rho = sss_pbd_invert_rho_eff(t, reflectance[c]);
        m.sigma_s[c] = rho / mfp[c];
        m.sigma_a[c] = (1.0 - rho) / mfp[c];
    }
    m.eta = eta;
    m.g = t->g;
    sss_result r = sss_material_validate(&m, err);
    if (r != SSS_OK) return r;
    *out = m;
    return SSS_OK;
}
