/* mertens2003's importance-sampling tables (src/gl/techniques/mertens2003/tech_mertens2003_table.c), without GL:
 *  - the tabulated radii are the exact sampler's quantiles: sss_pbd_sample_radius at the nodes (PBD),
 *    and for the dipole the empirical CDF of sss_dipole_sample_radius (Mertens et al. 2003's two-uniform Newton
 *    sampler, 20000 draws) agrees with the table's CDF (Kolmogorov-Smirnov distance below 1.63 /
 *    sqrt(n), the 1% critical value);
 *  - the density the shader uses is that of the distribution it samples: it integrates to 1, and the
 *    fraction of u in [0, 1) mapping below r equals the integral of the density up to r;
 *  - it approximates R_d(r) 2 pi r / rho: E[R_d(r) 2 pi r / pdf(r)] over the table = rho (the plane
 *    integral, sss_profile_total) within 0.5%, the estimator of Mertens et al. 2003, Eq. 9 on a plane. */
#include <stdlib.h>

#include "check.h"
#include "gl/techniques/mertens2003/tech_mertens2003.h"
#include "sss/material.h"
#include "sss/profile.h"

static float table[MERTENS_TABLE_FLOATS];

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* Fraction of the table's distribution below r by integrating its density (midpoint, fine steps). */
static double table_cdf(int c, double r)
{
    int n = 20000;
    double s = 0.0, h = r / n;
    for (int i = 0; i < n; i++) s += mertens_table_pdf(table, c, (i + 0.5) * h) * h;
    return s;
}

/* The CDF of the sampled distribution directly: the u in [0,1) with r(u) <= x, by bisection. */
static double sampled_cdf(int c, double x)
{
    double lo = 0.0, hi = 1.0;
    for (int i = 0; i < 60; i++) {
        double mid = 0.5 * (lo + hi);
        if (mertens_table_sample(table, c, mid) <= x) lo = mid;
        else hi = mid;
    }
    return lo;
}

static void check_common(const sss_profile *prof, const char *name)
{
    sss_error err = {0};
    CHECK(mertens_table_build(prof, table, &err) == SSS_OK);
    for (int c = 0; c < 3; c++) {
        double rt = table[c];
        CHECK(rt > 0.0);
        /* density integrates to 1 and matches the sampled distribution's CDF */
        CHECK_NEAR(table_cdf(c, rt * 0.999999), 1.0, 2e-3);
        double probes[4] = {0.3 * rt / 64, rt / 64, rt / 8, rt / 2};
        for (int i = 0; i < 4; i++) CHECK_NEAR(table_cdf(c, probes[i]), sampled_cdf(c, probes[i]), 2e-3);
        /* E[f / p] = rho for f = R_d 2 pi r (midpoint rule over u: 100000 stratified u) */
        int n = 100000;
        double est = 0.0;
        for (int i = 0; i < n; i++) {
            double r = mertens_table_sample(table, c, (i + 0.5) / n);
            double p = mertens_table_pdf(table, c, r);
            if (p > 0.0) est += sss_profile_eval(prof, c, r) * 2.0 * M_PI * r / p;
        }
        est /= n;
        double rho = sss_profile_total(prof, c);
        printf("%s channel %d: r_T %.4g, E[f/p] %.6g, rho %.6g, guide scan <= %g\n", name, c, rt, est, rho, table[3]);
        CHECK_REL(est, rho, 5e-3);
    }
}

static void test_pbd(void)
{
    sss_error err = {0};
    static sss_pbd_table pbd;
    sss_material m;
    CHECK(sss_material_from_medium("Skin1", 1.0, 1.33, &m, &err) == SSS_OK);
    CHECK(sss_pbd_table_build(1.33, 0.0, &pbd, &err) == SSS_OK);
    sss_profile prof;
    CHECK(sss_profile_init(&prof, SSS_PROFILE_PBD, &m, &pbd, &err) == SSS_OK);
    check_common(&prof, "PBD Skin1");
    /* the nodes are the exact sampler's quantiles */
    for (int c = 0; c < 3; c++)
        for (int k = 1; k < MERTENS_T; k += 97) {
            double u = MERTENS_U_MAX * k / MERTENS_T;
            double r = sss_pbd_sample_radius(&pbd, m.sigma_a[c], m.sigma_s[c], u);
            CHECK_REL(mertens_table_sample(table, c, (double)k / MERTENS_T), r, 1e-5);
        }
}

static void test_dipole(void)
{
    sss_error err = {0};
    sss_material m;
    CHECK(sss_material_from_medium("Marble", 1.0, 1.3, &m, &err) == SSS_OK);
    sss_profile prof;
    CHECK(sss_profile_init(&prof, SSS_PROFILE_DIPOLE, &m, NULL, &err) == SSS_OK);
    check_common(&prof, "dipole Marble");
    /* Kolmogorov-Smirnov: draws of the two-uniform Newton sampler against the table's CDF */
    enum { N = 20000 };
    static double draws[N];
    srand(7);
    for (int c = 0; c < 3; c++) {
        for (int i = 0; i < N; i++) {
            double u1 = (rand() + 0.5) / ((double)RAND_MAX + 1.0), u2 = (rand() + 0.5) / ((double)RAND_MAX + 1.0);
            draws[i] = sss_dipole_sample_radius(&prof.dipole[c], u1, u2);
        }
        qsort(draws, N, sizeof draws[0], cmp_double);
        double ks = 0.0;
        for (int i = 0; i < N; i += 50) {
            double f = sampled_cdf(c, draws[i]) / MERTENS_U_MAX; /* table covers U_MAX of the mass */
            if (f > 1.0) f = 1.0;
            double d1 = fabs(f - (double)i / N), d2 = fabs(f - (double)(i + 1) / N);
            if (d1 > ks) ks = d1;
            if (d2 > ks) ks = d2;
        }
        printf("dipole channel %d: KS distance %.4f (1%% critical %.4f)\n", c, ks, 1.63 / sqrt((double)N));
        CHECK(ks < 1.63 / sqrt((double)N));
    }
}

int main(void)
{
    test_pbd();
    test_dipole();
    return CHECK_DONE();
}
