/* Numerical robustness of the profiles: every measured medium x eta in {1.0, 1.2, 1.33, 1.5, 2.0} x
 * scale in {1e-3, 1, 1e3} (millimetres per scene unit, so coefficients from 1e-3 to 1e3 times the
 * table's), through the PBD table and the dipole: R_d(r) finite and >= 0 at radii from 0 through
 * denormal-small and astronomically large ones; the plane integral (rho_eff) finite and in [0, 1] (energy);
 * a quadrature of R_d 2 pi r dr agreeing with it (the profile and its total are consistent at every
 * scale, so nothing under- or overflows along the way); sampling radii and densities finite.
 * Units: R_d(r; s sigma) = s^2 R_d(s r; sigma) exactly (dimensional analysis) and rho_eff does not
 * depend on s, across the sweep's scales and out to the accepted extinction range
 * [SSS_SIGMA_T_MIN, SSS_SIGMA_T_MAX], beyond which materials are refused.
 * (Kernel LUTs and separable kernels over the same sweep: test_numeric_lut.c, test_numeric_separable.c.) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "sss/material.h"
#include "sss/profile.h"

static const double etas[] = {1.0, 1.2, 1.33, 1.5, 2.0};
static const double scales[] = {1e-3, 1.0, 1e3};
#define NETA (sizeof etas / sizeof etas[0])
#define NSCALE (sizeof scales / sizeof scales[0])

static int bad_reports; /* print the first few failures in full, count the rest */

static void report(const char *what, const char *medium, double eta, double scale, const char *model, int c,
                   double r, double v)
{
    if (bad_reports++ < 20)
        fprintf(stderr, "%s: %s eta %g scale %g %s channel %d r %g: %g\n", what, medium, eta, scale, model, c, r, v);
}

/* Plane integral of R_d by composite Simpson in u = ln(r) over 40 decades around the profile's own
 * length scale: int R_d(r) 2 pi r dr = int R_d(e^u) 2 pi e^(2u) du. Independent of the closed form
 * (dipole) and of the table's stored rho_eff (PBD). */
static double plane_integral(const sss_profile *p, int c, double length)
{
    const double u0 = log(length) - 20.0 * log(10.0), u1 = log(length) + 8.0 * log(10.0);
    const int n = 4000; /* even */
    double h = (u1 - u0) / n, sum = 0.0;
    for (int i = 0; i <= n; i++) {
        double u = u0 + h * i, r = exp(u);
        double f = sss_profile_eval(p, c, r) * 2.0 * M_PI * r * r;
        sum += f * (i == 0 || i == n ? 1.0 : (i % 2 ? 4.0 : 2.0));
    }
    return sum * h / 3.0;
}

static void sweep_profile(const sss_profile *p, const char *medium, double eta, double scale, const char *model)
{
    for (int c = 0; c < 3; c++) {
        double sig_t = p->material.sigma_a[c] + p->material.sigma_s[c];
        double length = 1.0 / sig_t; /* mean free path in scene units */
        /* Radii: 0, tiny (down to denormals), the profile's range on a fine log grid, huge. */
        double radii[80];
        int nr = 0;
        radii[nr++] = 0.0;
        radii[nr++] = 4.9e-324;
        radii[nr++] = 1e-300;
        radii[nr++] = 1e-30 * length;
        for (int k = 0; k <= 64; k++) radii[nr++] = length * pow(10.0, -4.0 + k / 8.0);
        radii[nr++] = 1e30 * length;
        radii[nr++] = 1e300;
        radii[nr++] = INFINITY;
        int ok = 1;
        for (int i = 0; i < nr; i++) {
            double v = sss_profile_eval(p, c, radii[i]);
            if (!isfinite(v) || v < 0.0) {
                report("R_d not finite or negative", medium, eta, scale, model, c, radii[i], v);
                ok = 0;
            }
        }
        CHECK(ok);
        double total = sss_profile_total(p, c);
        /* Energy: a half-space reflects at most what enters (PBD: sss keeps PBRT's table <= 1, see
         * conserve_energy in pbd.c; dipole: alpha'/2 (e^(-sigma_tr z_r) + e^(-sigma_tr z_v)) <= 1). */
        if (!(isfinite(total) && total >= 0.0 && total <= 1.0 + 1e-12))
            report("rho_eff", medium, eta, scale, model, c, 0, total);
        CHECK(isfinite(total) && total >= 0.0 && total <= 1.0 + 1e-12);
        /* The profile integrates to its total (1.5% covers PBRT's Catmull-Rom table interpolation). */
        double q = plane_integral(p, c, length);
        if (!(fabs(q - total) <= 0.015 * total + 1e-12))
            report("quadrature != total", medium, eta, scale, model, c, q, total);
        CHECK(fabs(q - total) <= 0.015 * total + 1e-12);
        double r999 = sss_profile_radius_for_fraction(p, c, 0.999);
        CHECK(isfinite(r999) && r999 > 0.0);
        /* Importance sampling (the reference renderer's path): finite radii, finite densities. */
        for (int k = 0; k <= 8; k++) {
            double u = k == 0 ? 0.0 : k == 8 ? 1.0 - 1e-16 : k / 8.0;
            double r, pdf;
            if (p->model == SSS_PROFILE_DIPOLE) {
                r = sss_dipole_sample_radius(&p->dipole[c], u, u);
                pdf = sss_dipole_pdf_radius(&p->dipole[c], r);
            } else {
                r = sss_pbd_sample_radius(p->table, p->material.sigma_a[c], p->material.sigma_s[c], u);
                pdf = r >= 0.0 ? sss_pbd_pdf_radius(p->table, p->material.sigma_a[c], p->material.sigma_s[c], r) : 0.0;
            }
            if (!(isfinite(r) && r >= 0.0 && isfinite(pdf) && pdf >= 0.0))
                report("sampling", medium, eta, scale, model, c, r, pdf);
            CHECK(isfinite(r) && r >= 0.0 && isfinite(pdf) && pdf >= 0.0);
        }
    }
}

/* R_d of the material scaled by s against the unscaled one at the same optical radius. */
static int scaling_holds(const sss_profile *unit, const sss_profile *scaled, double s, const char *what)
{
    int ok = 1;
    for (int c = 0; c < 3; c++) {
        double mfp = 1.0 / (unit->material.sigma_a[c] + unit->material.sigma_s[c]);
        for (int k = 0; k <= 12; k++) {
            double r = mfp * pow(10.0, -3.0 + k / 2.0);
            double a = sss_profile_eval(unit, c, r), b = sss_profile_eval(scaled, c, r / s) / (s * s);
            if (!(fabs(a - b) <= 1e-9 * a + 1e-300)) {
                if (ok && bad_reports++ < 20)
                    fprintf(stderr, "%s: scale %g channel %d r %g mfp: R_d %g, scaled %g\n", what, s, c, r / mfp, a, b);
                ok = 0;
            }
        }
        double ta = sss_profile_total(unit, c), tb = sss_profile_total(scaled, c);
        if (!(fabs(ta - tb) <= 1e-12 * ta)) {
            if (bad_reports++ < 20) fprintf(stderr, "%s: scale %g channel %d: rho_eff %g vs %g\n", what, s, c, ta, tb);
            ok = 0;
        }
    }
    return ok;
}

static void test_units(const sss_pbd_table *table)
{
    for (size_t i = 0; i < sss_measured_medium_count(); i++) {
        const char *name = sss_measured_medium_at(i)->name;
        sss_material m1;
        CHECK(sss_material_from_medium(name, 1.0, table->eta, &m1, NULL) == SSS_OK);
        double t_min = 1e300, t_max = 0.0;
        for (int c = 0; c < 3; c++) {
            double t = m1.sigma_a[c] + m1.sigma_s[c];
            t_min = t < t_min ? t : t_min;
            t_max = t > t_max ? t : t_max;
        }
        /* The sweep's scales and the largest and smallest the range admits for this medium. */
        double scales_[4] = {1e-3, 1e3, SSS_SIGMA_T_MAX / t_max * (1 - 1e-9), SSS_SIGMA_T_MIN / t_min * (1 + 1e-9)};
        for (int model = 0; model < 2; model++) {
            sss_profile unit;
            CHECK(sss_profile_init(&unit, model ? SSS_PROFILE_DIPOLE : SSS_PROFILE_PBD, &m1, table, NULL) == SSS_OK);
            for (int k = 0; k < 4; k++) {
                sss_material ms;
                sss_error err = {0};
                sss_result r = sss_material_from_medium(name, scales_[k], table->eta, &ms, &err);
                CHECK_MSG(r == SSS_OK, "%s scale %g: %s", name, scales_[k], err.message);
                if (r != SSS_OK) continue;
                sss_profile sp;
                CHECK(sss_profile_init(&sp, unit.model, &ms, table, NULL) == SSS_OK);
                CHECK(scaling_holds(&unit, &sp, scales_[k], name));
            }
        }
        /* Just beyond the range: refused, naming the limit. */
        double beyond[2] = {10.0 * SSS_SIGMA_T_MAX / t_min, 0.1 * SSS_SIGMA_T_MIN / t_max};
        for (int k = 0; k < 2; k++) {
            sss_material ms;
            sss_error err = {0};
            CHECK_MSG(sss_material_from_medium(name, beyond[k], table->eta, &ms, &err) == SSS_ERROR_LIMIT,
                      "%s scale %g accepted", name, beyond[k]);
        }
    }
}

int main(void)
{
    sss_pbd_table *tables = malloc(NETA * sizeof *tables);
    CHECK(tables != NULL);
    if (!tables) return CHECK_DONE();
    for (size_t e = 0; e < NETA; e++) {
        sss_error err = {0};
        CHECK_MSG(sss_pbd_table_build(etas[e], 0.0, &tables[e], &err) == SSS_OK, "eta %g: %s", etas[e], err.message);
        /* The table itself: finite, non-negative rho_eff over all albedos. */
        for (int i = 0; i < SSS_PBD_ALBEDOS; i++)
            CHECK(isfinite(tables[e].rho_eff[i]) && tables[e].rho_eff[i] >= 0.0 &&
                  tables[e].rho_eff[i] <= 1.0);
    }
    size_t media = sss_measured_medium_count(), materials = 0;
    CHECK(media >= 10);
    for (size_t i = 0; i < media; i++) {
        const char *name = sss_measured_medium_at(i)->name;
        for (size_t e = 0; e < NETA; e++)
            for (size_t s = 0; s < NSCALE; s++) {
                sss_material m;
                sss_error err = {0};
                sss_result r = sss_material_from_medium(name, scales[s], etas[e], &m, &err);
                CHECK_MSG(r == SSS_OK, "%s eta %g scale %g: %s", name, etas[e], scales[s], err.message);
                if (r != SSS_OK) continue;
                materials++;
                sss_profile pbd, dip;
                CHECK(sss_profile_init(&pbd, SSS_PROFILE_PBD, &m, &tables[e], &err) == SSS_OK);
                CHECK(sss_profile_init(&dip, SSS_PROFILE_DIPOLE, &m, NULL, &err) == SSS_OK);
                sweep_profile(&pbd, name, etas[e], scales[s], "pbd");
                sweep_profile(&dip, name, etas[e], scales[s], "dipole");
            }
    }
    test_units(&tables[2]); /* eta 1.33 */
    printf("swept %zu materials (%zu media x %zu eta x %zu scales) through PBD and dipole\n", materials, media,
           NETA, NSCALE);
    if (bad_reports > 20) fprintf(stderr, "... %d failures in all\n", bad_reports);
    free(tables);
    return CHECK_DONE();
}
