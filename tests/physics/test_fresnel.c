/* Fresnel reflectance against the textbook closed forms; Fresnel moments and F_dr against numerical
 * hemispherical integrals of the Fresnel reflectance; the check values of docs/physics.md §1. */
#include "check.h"
#include "physics/physics_test_util.h"
#include "sss/material.h"

/* Fresnel equations in Fresnel's own (sine/tangent) form, an independent derivation:
 * R = (sin^2(i - t)/sin^2(i + t) + tan^2(i - t)/tan^2(i + t)) / 2, for eta_i -> eta_t. */
static double fresnel_sine_form(double cos_i, double eta_i, double eta_t)
{
    double ti = acos(cos_i);
    double st = eta_i / eta_t * sin(ti);
    if (st >= 1.0) return 1.0;
    double tt = asin(st);
    double a = sin(ti - tt) / sin(ti + tt), b = tan(ti - tt) / tan(ti + tt);
    return 0.5 * (a * a + b * b);
}

typedef struct moment_ctx {
    double eta;
    int power;
} moment_ctx;

/* Fresnel reflectance seen from inside the medium (index eta, leaving into index 1) times mu^power. */
static double moment_integrand(double mu, void *c)
{
    const moment_ctx *m = (const moment_ctx *)c;
    return sss_fresnel_dielectric(mu, m->eta, 1.0) * pow(mu, m->power);
}

int main(void)
{
    /* Normal incidence: ((eta - 1)/(eta + 1))^2 from either side. */
    for (double eta = 1.0; eta <= 3.0; eta += 0.25) {
        double r0 = (eta - 1.0) / (eta + 1.0);
        CHECK_NEAR(sss_fresnel_dielectric(1.0, 1.0, eta), r0 * r0, 1e-14);
        CHECK_NEAR(sss_fresnel_dielectric(-1.0, 1.0, eta), r0 * r0, 1e-14);
        CHECK_NEAR(sss_fresnel_dielectric(1.0, eta, 1.0), r0 * r0, 1e-14);
    }

    /* Oblique incidence equals the sine/tangent form, from outside and from inside below critical. */
    for (double eta = 1.1; eta <= 2.5; eta += 0.2) {
        for (double c = 0.05; c < 1.0; c += 0.05) {
            CHECK_NEAR(sss_fresnel_dielectric(c, 1.0, eta), fresnel_sine_form(c, 1.0, eta), 1e-12);
            CHECK_NEAR(sss_fresnel_dielectric(c, eta, 1.0), fresnel_sine_form(c, eta, 1.0), 1e-12);
            /* A negative cosine swaps the sides (PBRT FrDielectric). */
            CHECK_NEAR(sss_fresnel_dielectric(-c, 1.0, eta), fresnel_sine_form(c, eta, 1.0), 1e-12);
        }
    }

    /* Total internal reflection beyond the critical angle sin(theta_c) = 1/eta gives exactly 1. */
    for (double eta = 1.1; eta <= 3.0; eta += 0.3) {
        double cos_c = sqrt(1.0 - 1.0 / (eta * eta));
        CHECK(sss_fresnel_dielectric(0.9 * cos_c, eta, 1.0) == 1.0);
        CHECK(sss_fresnel_dielectric(-0.5 * cos_c, 1.0, eta) == 1.0);
        CHECK(sss_fresnel_dielectric(1.05 * cos_c, eta, 1.0) < 1.0);
    }
    /* Grazing incidence reflects everything; eta = 1 reflects nothing. */
    CHECK_NEAR(sss_fresnel_dielectric(0.0, 1.0, 1.5), 1.0, 1e-12);
    CHECK_NEAR(sss_fresnel_dielectric(0.3, 1.0, 1.0), 0.0, 1e-15);
    /* Reciprocity: F(i; 1 -> eta) = F(t; eta -> 1) for the refracted angle t. */
    for (double c = 0.1; c < 1.0; c += 0.1) {
        double eta = 1.4, s = sqrt(1 - c * c) / eta, ct = sqrt(1 - s * s);
        CHECK_NEAR(sss_fresnel_dielectric(c, 1.0, eta), sss_fresnel_dielectric(ct, eta, 1.0), 1e-14);
    }

    /* docs/physics.md §1 check values at eta = 1.33 (printed to 4 decimals: half a unit of the last digit). */
    double fm1 = sss_fresnel_moment1(1.33), fm2 = sss_fresnel_moment2(1.33);
    CHECK_NEAR(fm1, 0.2365, 5.01e-5);
    CHECK_NEAR(fm2, 0.1086, 5.01e-5);
    CHECK_NEAR((1.0 - 2.0 * fm1) / 4.0, 0.1318, 5.01e-5); /* c_phi */
    CHECK_NEAR((1.0 - 3.0 * fm2) / 2.0, 0.3372, 5.01e-5); /* c_E */
    CHECK_NEAR(sss_bssrdf_normalization(1.33), 0.9341, 5.01e-5);
    CHECK_NEAR(sss_bssrdf_normalization(1.33), 1.0 - 2.0 * sss_fresnel_moment1(1.0 / 1.33), 1e-15);

    /* The moment fits approximate FM_i(eta) = int_0^1 F_r(mu) mu^i dmu for light inside the medium.
     * The polynomial fits are good to about 1.5e-3 over eta in [1.1, 2] (their fitted range); we allow
     * 2.5e-3. F_dr (Mertens et al. 2003) is the same hemispherical average, 2 int F mu dmu; same tolerance. */
    for (double eta = 1.1; eta <= 2.0001; eta += 0.1) {
        moment_ctx m1 = {eta, 1}, m2 = {eta, 2};
        double n1 = tu_integrate(moment_integrand, &m1, 0.0, 1.0, 1e-10);
        double n2 = tu_integrate(moment_integrand, &m2, 0.0, 1.0, 1e-10);
        CHECK_NEAR(sss_fresnel_moment1(eta), n1, 2.5e-3);
        CHECK_NEAR(sss_fresnel_moment2(eta), n2, 2.5e-3);
        CHECK_NEAR(sss_fresnel_diffuse_reflectance(eta), 2.0 * n1, 2.5e-3);
        /* The fit for e < 1 describes light arriving from outside: FM1(1/eta) = int F(1 -> eta) mu. */
        moment_ctx ext = {1.0 / eta, 1};
        double ne = tu_integrate(moment_integrand, &ext, 0.0, 1.0, 1e-10);
        CHECK_NEAR(sss_fresnel_moment1(1.0 / eta), ne, 2.5e-3);
    }
    return CHECK_DONE();
}
