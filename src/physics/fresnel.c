/* physics/fresnel.c — Fresnel reflectance, Fresnel moments and the diffuse Fresnel reflectance.
 *
 * sss_fresnel_dielectric follows PBRT-v3 FrDielectric (core/reflection.cpp); the moment fits are
 * PBRT-v3's FresnelMoment1/2 (core/bssrdf.cpp, docs/physics.md §1); F_dr is the fit of Mertens et al. 2003, Table 1. */
#include "sss/material.h"

#include <math.h>

double sss_fresnel_dielectric(double cos_theta_i, double eta_i, double eta_t)
{
    if (!(cos_theta_i == cos_theta_i)) return 1.0; /* NaN in: reflect everything, never propagate */
    cos_theta_i = cos_theta_i < -1.0 ? -1.0 : (cos_theta_i > 1.0 ? 1.0 : cos_theta_i);
    /* A negative cosine means the light travels from the eta_t side: swap the media (PBRT). */
    if (!(cos_theta_i > 0.0)) {
        double t = eta_i;
        eta_i = eta_t;
        eta_t = t;
        cos_theta_i = fabs(cos_theta_i);
    }
    /* Snell's law for the transmitted angle. */
    double sin_i = sqrt(fmax(0.0, 1.0 - cos_theta_i * cos_theta_i));
    double sin_t = eta_i / eta_t * sin_i;
    if (sin_t >= 1.0) return 1.0; /* total internal reflection */
    double cos_t = sqrt(fmax(0.0, 1.0 - sin_t * sin_t));
    /* Unpolarised: mean of the parallel and perpendicular amplitude ratios squared. */
    double r_parl = (eta_t * cos_theta_i - eta_i * cos_t) / (eta_t * cos_theta_i + eta_i * cos_t);
    double r_perp = (eta_i * cos_theta_i - eta_t * cos_t) / (eta_i * cos_theta_i + eta_t * cos_t);
    return 0.5 * (r_parl * r_parl + r_perp * r_perp);
}

/* docs/physics.md §1: PBRT-v3 FresnelMoment1 polynomial fit. */
double sss_fresnel_moment1(double eta)
{
    double e2 = eta * eta, e3 = e2 * eta, e4 = e3 * eta, e5 = e4 * eta;
    if (eta < 1.0)
        return 0.45966 - 1.73965 * eta + 3.37668 * e2 - 3.904945 * e3 + 2.49277 * e4 - 0.68441 * e5;
    return -4.61686 + 11.1136 * eta - 10.4646 * e2 + 5.11455 * e3 - 1.27198 * e4 + 0.12746 * e5;
}

/* docs/physics.md §1: PBRT-v3 FresnelMoment2 polynomial fit. */
double sss_fresnel_moment2(double eta)
{
    double e2 = eta * eta, e3 = e2 * eta, e4 = e3 * eta, e5 = e4 * eta;
    if (eta < 1.0)
        return 0.27614 - 0.87350 * eta + 1.12077 * e2 - 0.65095 * e3 + 0.07883 * e4 + 0.04860 * e5;
    double r = 1.0 / eta, r2 = r * r, r3 = r2 * r;
    return -547.033 + 45.3087 * r3 - 218.725 * r2 + 458.843 * r + 404.557 * eta - 189.519 * e2 +
           54.9327 * e3 - 9.00603 * e4 + 0.63942 * e5;
}

/* Mertens et al. 2003, Table 1: F_dr = -1.440/eta^2 + 0.710/eta + 0.668 + 0.0636 eta. */
double sss_fresnel_diffuse_reflectance(double eta)
{
    return -1.440 / (eta * eta) + 0.710 / eta + 0.668 + 0.0636 * eta;
}

/* docs/physics.md §1: c = 1 - 2 FM1(1/eta), the normalisation of PBRT's S_w. */
double sss_bssrdf_normalization(double eta)
{
    return 1.0 - 2.0 * sss_fresnel_moment1(1.0 / eta);
}
