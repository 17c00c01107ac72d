/* physics/gaussian.c — Gaussian profiles: d'Eon et al. 2007 six-Gaussian skin fit (docs/physics.md §2.4) and
 * the artist-friendly two-Gaussian separable model of Jimenez et al. 2019 (Eq. 6, Table 2). */
#include "sss/profile.h"

#include <math.h>
#include <string.h>

#define PI 3.14159265358979323846

/* docs/physics.md §2.4: variances in mm^2 and RGB weights of the six terms. */
const double sss_gauss6_variance_mm2[SSS_GAUSS6_TERMS] = {0.0064, 0.0484, 0.187, 0.567, 1.99, 7.41};
const double sss_gauss6_weight[3][SSS_GAUSS6_TERMS] = {
    {0.233, 0.100, 0.118, 0.113, 0.358, 0.078},
    {0.455, 0.336, 0.198, 0.007, 0.004, 0.0},
    {0.649, 0.344, 0.0, 0.007, 0.0, 0.0},
};

double sss_gaussian_2d(double variance, double r)
{
    /* A zero variance is a Dirac delta: no finite value to return, and no area to contribute. */
    if (!(variance > 0.0) || !isfinite(r)) return 0.0;
    return exp(-r * r / (2.0 * variance)) / (2.0 * PI * variance);
}

typedef struct preset {
    const char *name;
    sss_artist_params p;
} preset;

/* Jimenez et al. 2019, Table 2 (s in mm). */
static const preset presets[] = {
    {"single-layer", {10.34, {0.077, 0.034, 0.02}, {1.0, 0.45, 0.25}, 0.5}},
    {"multi-layer", {9.27, {0.055, 0.044, 0.038}, {1.0, 0.2, 0.13}, 0.5}},
    {"production", {9.9, {0.22, 0.07, 0.07}, {1.0, 0.3, 0.15}, 0.65}},
};

sss_result sss_artist_preset(const char *name, sss_artist_params *out, sss_error *err)
{
    for (size_t i = 0; name && i < sizeof presets / sizeof presets[0]; i++) {
        if (strcmp(name, presets[i].name) == 0) {
            if (out) *out = presets[i].p;
            return SSS_OK;
        }
    }
    return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                         "unknown artist preset '%s' (known: single-layer, multi-layer, production)",
                         name ? name : "(null)");
}

/* Normalised 1D Gaussian of standard deviation sigma (0 for sigma <= 0: a delta has no value). */
static double gaussian_1d(double sigma, double x)
{
    if (!(sigma > 0.0)) return 0.0;
    return exp(-x * x / (2.0 * sigma * sigma)) / (sqrt(2.0 * PI) * sigma);
}

double sss_artist_eval_1d(const sss_artist_params *p, int channel, double x)
{
    if (!p || channel < 0 || channel > 2 || !isfinite(x)) return 0.0;
    /* Jimenez et al. 2019, Eq. 6: a_m(x) = w G(x, sigma_n) + (1 - w) G(x, sigma_f). */
    double sn = p->near[channel] * p->s, sf = p->far[channel] * p->s;
    double v = p->w * gaussian_1d(sn, x) + (1.0 - p->w) * gaussian_1d(sf, x);
    return isfinite(v) && v > 0.0 ? v : 0.0;
}
