/* physics/material.c — the measured media table (docs/physics.md §2.3) and material constructors/validation.
 *
 * The table is Jensen et al. 2001 as PBRT-v3 ships it (core/medium.cpp SubsurfaceParameterTable):
 * reduced scattering sigma_s' and absorption sigma_a in mm^-1. PBRT's `subsurface` material multiplies
 * them by `scale` and forces g = 0 because the data are reduced coefficients (docs/physics.md §2.2). */
#include "sss/material.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

static const sss_measured_medium media[] = {
    {"Apple", {2.29, 2.39, 1.97}, {0.0030, 0.0034, 0.046}},
    {"Chicken1", {0.15, 0.21, 0.38}, {0.015, 0.077, 0.19}},
    {"Chicken2", {0.19, 0.25, 0.32}, {0.018, 0.088, 0.20}},
    {"Cream", {7.38, 5.47, 3.15}, {0.0002, 0.0028, 0.0163}},
    {"Ketchup", {0.18, 0.07, 0.03}, {0.061, 0.97, 1.45}},
    {"Marble", {2.19, 2.62, 3.00}, {0.0021, 0.0041, 0.0071}},
    {"Potato", {0.68, 0.70, 0.55}, {0.0024, 0.0090, 0.12}},
    {"Skimmilk", {0.70, 1.22, 1.90}, {0.0014, 0.0025, 0.0142}},
    {"Skin1", {0.74, 0.88, 1.01}, {0.032, 0.17, 0.48}},
    {"Skin2", {1.09, 1.59, 1.79}, {0.013, 0.070, 0.145}},
    {"Spectralon", {11.6, 20.4, 14.9}, {0.0, 0.0, 0.0}},
    {"Wholemilk", {2.55, 3.21, 3.77}, {0.0011, 0.0024, 0.014}},
};

#define MEDIA_COUNT (sizeof media / sizeof media[0])

size_t sss_measured_medium_count(void) { return MEDIA_COUNT; }

const sss_measured_medium *sss_measured_medium_at(size_t index)
{
    return index < MEDIA_COUNT ? &media[index] : NULL;
}

static int equal_ignore_case(const char *a, const char *b)
{
    for (; *a && *b; a++, b++)
        if (tolower((unsigned char)*a) != tolower((unsigned char)*b)) return 0;
    return *a == *b;
}

const sss_measured_medium *sss_measured_medium_find(const char *name)
{
    if (!name) return NULL;
    for (size_t i = 0; i < MEDIA_COUNT; i++)
        if (equal_ignore_case(name, media[i].name)) return &media[i];
    return NULL;
}

static const char *const channel_name[3] = {"R", "G", "B"};

static sss_result check_eta(double eta, sss_error *err)
{
    if (!isfinite(eta) || eta < SSS_ETA_MIN || eta > SSS_ETA_MAX)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                             "eta = %g is outside [%g, %g] (relative index of refraction)", eta,
                             SSS_ETA_MIN, SSS_ETA_MAX);
    return SSS_OK;
}

static sss_result check_g(double g, sss_error *err)
{
    if (!isfinite(g) || g <= -1.0 || g >= 1.0)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                             "g = %g is outside (-1, 1) (Henyey-Greenstein anisotropy)", g);
    return SSS_OK;
}

static sss_result check_scale(double scale, sss_error *err)
{
    if (!isfinite(scale) || scale <= 0.0)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                             "scale = %g must be a finite number > 0 (millimetres per scene unit)",
                             scale);
    return SSS_OK;
}

/* Non-negative, finite, and sigma_t > 0 in every channel. */
static sss_result check_coefficients(const double sigma_a[3], const double sigma_s[3], sss_error *err)
{
    for (int c = 0; c < 3; c++) {
        if (!isfinite(sigma_a[c]) || !isfinite(sigma_s[c]))
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                                 "%s channel: coefficients must be finite (sigma_a = %g, sigma_s = %g)",
                                 channel_name[c], sigma_a[c], sigma_s[c]);
        if (sigma_a[c] < 0.0)
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                                 "%s channel: negative absorption coefficient sigma_a = %g",
                                 channel_name[c], sigma_a[c]);
        if (sigma_s[c] < 0.0)
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                                 "%s channel: negative scattering coefficient sigma_s = %g",
                                 channel_name[c], sigma_s[c]);
        if (!(sigma_a[c] + sigma_s[c] > 0.0))
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                                 "%s channel: sigma_a + sigma_s is 0 (the medium must interact)",
                                 channel_name[c]);
    }
    return SSS_OK;
}

/* sigma_t within [SSS_SIGMA_T_MIN, SSS_SIGMA_T_MAX] (checked on the final, scaled coefficients). */
static sss_result check_extinction(const double sigma_a[3], const double sigma_s[3], sss_error *err)
{
    for (int c = 0; c < 3; c++) {
        double t = sigma_a[c] + sigma_s[c];
        if (t < SSS_SIGMA_T_MIN || t > SSS_SIGMA_T_MAX)
            return sss_error_set(err, SSS_ERROR_LIMIT,
                                 "%s channel: sigma_a + sigma_s = %g per scene unit is outside [%g, %g] "
                                 "(choose a scene unit nearer the mean free path)",
                                 channel_name[c], t, SSS_SIGMA_T_MIN, SSS_SIGMA_T_MAX);
    }
    return SSS_OK;
}

sss_result sss_material_validate(const sss_material *m, sss_error *err)
{
    if (!m) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "material is NULL");
    sss_result r = check_coefficients(m->sigma_a, m->sigma_s, err);
    if (r == SSS_OK) r = check_extinction(m->sigma_a, m->sigma_s, err);
    if (r == SSS_OK) r = check_eta(m->eta, err);
    if (r == SSS_OK) r = check_g(m->g, err);
    return r;
}

sss_result sss_material_from_coefficients(const double sigma_a[3], const double sigma_s[3], double scale,
                                          double eta, double g, sss_material *out, sss_error *err)
{
    if (!sigma_a || !sigma_s || !out)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "material coefficients or output is NULL");
    sss_result r = check_scale(scale, err);
    if (r != SSS_OK) return r;
    /* Check before scaling so that the message shows the caller's numbers. */
    if ((r = check_coefficients(sigma_a, sigma_s, err)) != SSS_OK) return r;
    if ((r = check_eta(eta, err)) != SSS_OK) return r;
    if ((r = check_g(g, err)) != SSS_OK) return r;
    sss_material m;
    for (int c = 0; c < 3; c++) {
        m.sigma_a[c] = sigma_a[c] * scale;
        m.sigma_s[c] = sigma_s[c] * scale;
    }
    m.eta = eta;
    m.g = g;
    /* Scaling can overflow a finite coefficient (1e300 x 1e10): validate the product too. */
    if ((r = sss_material_validate(&m, err)) != SSS_OK) {
        sss_error_prefix(err, "after applying scale");
        return r;
    }
    *out = m;
    return SSS_OK;
}

sss_result sss_material_from_medium(const char *name, double scale, double eta, sss_material *out,
                                    sss_error *err)
{
    if (!out) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "material output is NULL");
    const sss_measured_medium *med = sss_measured_medium_find(name);
    if (!med) {
        char known[256];
        size_t at = 0;
        known[0] = '\0';
        for (size_t i = 0; i < MEDIA_COUNT; i++) {
            int n = snprintf(known + at, sizeof known - at, "%s%s", i ? ", " : "", media[i].name);
            if (n < 0 || (size_t)n >= sizeof known - at) break;
            at += (size_t)n;
        }
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "unknown medium '%s' (known media: %s)",
                             name ? name : "(null)", known);
    }
    /* g = 0: the table holds reduced scattering coefficients, so sigma_s = sigma_s' (docs/physics.md §2.2). */
    sss_result r = sss_material_from_coefficients(med->sigma_a, med->sigma_s_prime, scale, eta, 0.0, out,
                                                  err);
    if (r != SSS_OK) sss_error_prefix(err, med->name);
    return r;
}
