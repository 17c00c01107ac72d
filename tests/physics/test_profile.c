/* sss_profile_*: init checks, eval non-negative and finite, total = quadrature of the plane integral,
 * radius_for_fraction against the quadrature, and the GAUSS6 unit conversion. */
#include <string.h>

#include "check.h"
#include "physics/physics_test_util.h"
#include "sss/profile.h"

#define PI 3.14159265358979323846

static sss_pbd_table table;

typedef struct pctx {
    const sss_profile *p;
    int ch;
} pctx;

static double radial(double r, void *c)
{
    const pctx *q = (const pctx *)c;
    return sss_profile_eval(q->p, q->ch, r) * 2.0 * PI * r;
}

/* Plane integral over [0, R] on a log scale from 1e-9 R (the disc below is S(0) pi r^2). */
static double integral_to(const sss_profile *p, int ch, double R)
{
    pctx q = {p, ch};
    double r0 = 1e-9 * R;
    return sss_profile_eval(p, ch, 0.0) * PI * r0 * r0 + tu_integrate_log(radial, &q, r0, R, 1e-12);
}

static void check_model(const sss_profile *p, const char *label, double rel_total, double rel_fraction,
                        double r_far)
{
    for (int c = 0; c < 3; c++) {
        double out[3];
        for (double r = 0.0; r < 2.0 * r_far; r += r_far / 97.0) {
            double v = sss_profile_eval(p, c, r);
            CHECK(v >= 0.0 && isfinite(v));
            sss_profile_eval_rgb(p, r, out);
            CHECK(out[c] == v);
        }
        CHECK(isfinite(sss_profile_eval(p, c, 1e300)) && sss_profile_eval(p, c, 1e300) >= 0.0);
        CHECK(sss_profile_eval(p, c, NAN) == 0.0);
        double total = sss_profile_total(p, c);
        double q = integral_to(p, c, r_far);
        CHECK_MSG(fabs(q - total) <= rel_total * total, "%s ch %d: quadrature %.9g vs total %.9g", label, c, q,
                  total);
        static const double fractions[4] = {0.25, 0.5, 0.9, 0.999};
        double prev = 0.0;
        for (int k = 0; k < 4; k++) {
            double R = sss_profile_radius_for_fraction(p, c, fractions[k]);
            CHECK(R > prev);
            prev = R;
            double f = integral_to(p, c, R) / q;
            CHECK_MSG(fabs(f - fractions[k]) <= rel_fraction * fractions[k],
                      "%s ch %d: fraction %g at R = %g, quadrature says %g", label, c, fractions[k], R, f);
        }
        CHECK(sss_profile_radius_for_fraction(p, c, 0.0) == 0.0);
        CHECK(isfinite(sss_profile_radius_for_fraction(p, c, 1.0)));
    }
    CHECK(sss_profile_eval(p, 3, 0.1) == 0.0 && sss_profile_eval(p, -1, 0.1) == 0.0);
}

int main(void)
{
    sss_error err;
    CHECK(sss_pbd_table_build(1.33, 0.0, &table, &err) == SSS_OK);
    sss_material m;
    CHECK(sss_material_from_medium("Skin1", 1.0, 1.33, &m, &err) == SSS_OK);
    sss_profile p;

    /* PBD needs a table built for the material's eta and g. */
    CHECK(sss_profile_init(&p, SSS_PROFILE_PBD, &m, NULL, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(err.message, "table") != NULL);
    sss_material m2 = m;
    m2.eta = 1.5;
    CHECK(sss_profile_init(&p, SSS_PROFILE_PBD, &m2, &table, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(err.message, "1.5") != NULL);
    m2 = m;
    m2.g = 0.5;
    CHECK(sss_profile_init(&p, SSS_PROFILE_PBD, &m2, &table, &err) == SSS_ERROR_INVALID_ARGUMENT);
    m2 = m;
    m2.sigma_a[1] = -1.0;
    CHECK(sss_profile_init(&p, SSS_PROFILE_DIPOLE, &m2, NULL, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(err.message, "negative") != NULL);
    CHECK(sss_profile_init(&p, SSS_PROFILE_DIPOLE, NULL, NULL, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(sss_profile_init(&p, (sss_profile_model)7, &m, &table, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(sss_profile_init(NULL, SSS_PROFILE_GAUSS6, NULL, NULL, &err) == SSS_ERROR_INVALID_ARGUMENT);

    /* PBD: the profile is PBRT's S_r; its total is rho_eff of each channel's albedo. */
    CHECK(sss_profile_init(&p, SSS_PROFILE_PBD, &m, &table, &err) == SSS_OK);
    for (int c = 0; c < 3; c++) {
        CHECK(sss_profile_eval(&p, c, 0.3) == sss_pbd_sr(&table, m.sigma_a[c], m.sigma_s[c], 0.3));
        CHECK(sss_profile_total(&p, c) ==
              sss_pbd_rho_eff(&table, m.sigma_s[c] / (m.sigma_a[c] + m.sigma_s[c])));
    }
    /* Skin1 R: sigma_t = 0.772/mm, the table ends at r_opt ~ 203 -> 263 mm. */
    check_model(&p, "pbd", 0.01, 2e-3, 300.0);

    /* Dipole: reduced scattering sigma_s (1 - g) per channel; closed-form total. */
    sss_material mg = m;
    mg.g = 0.6;
    CHECK(sss_profile_init(&p, SSS_PROFILE_DIPOLE, &mg, NULL, &err) == SSS_OK);
    for (int c = 0; c < 3; c++) {
        sss_dipole d;
        sss_dipole_init(&d, mg.sigma_a[c], mg.sigma_s[c] * 0.4, mg.eta);
        CHECK(sss_profile_eval(&p, c, 0.7) == sss_dipole_rd(&d, 0.7));
    }
    CHECK(sss_profile_init(&p, SSS_PROFILE_DIPOLE, &m, NULL, &err) == SSS_OK);
    check_model(&p, "dipole", 1e-6, 1e-5, 2000.0);

    /* Gaussians, a scene unit of 1 mm. */
    CHECK(sss_profile_init(&p, SSS_PROFILE_GAUSS6, NULL, NULL, &err) == SSS_OK);
    CHECK(p.gauss6_mm_per_unit == 1.0);
    for (int c = 0; c < 3; c++) CHECK_NEAR(sss_profile_total(&p, c), 1.0, 1e-12);
    check_model(&p, "gauss6", 1e-8, 1e-6, 60.0);
    /* A scene unit of s mm: R(r) per unit^2 = s^2 R_mm(r s), same total. */
    sss_profile pm = p;
    p.gauss6_mm_per_unit = 10.0;
    for (double r = 0.0; r < 3.0; r += 0.05)
        CHECK_REL(sss_profile_eval(&p, 0, r), 100.0 * sss_profile_eval(&pm, 0, 10.0 * r), 1e-12);
    CHECK_REL(sss_profile_radius_for_fraction(&p, 1, 0.9), 0.1 * sss_profile_radius_for_fraction(&pm, 1, 0.9),
              1e-9);
    check_model(&p, "gauss6 10mm", 1e-8, 1e-6, 6.0);
    return CHECK_DONE();
}
