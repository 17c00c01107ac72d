/* The disc-integrated LUT R'_d(r, A) (Maisch & Ropinski 2020, Eq. 5, sections 7.1-7.2; docs/physics.md §3) against its
 * defining properties and independent quadratures: A -> 0 gives R_d(r); r = 0 gives the disc average
 * (1/A) int_0^r_A R_d 2 pi x dx; random texels agree with a brute-force 2D integral in polar
 * coordinates around the disc's centre; a disc holding the whole profile holds its whole energy;
 * the six-Gaussian fit has a closed form at r = 0; r_max solves Q(r_max) = cut-off. */
#include <math.h>
#include <string.h>

#include "check.h"
#include "kernel/kernel_internal.h"
#include "kernel_test_util.h"
#include "sss/kernel.h"

static sss_pbd_table table;

static sss_lut build(const sss_profile *p, int size, sss_lut_axes axes, double r_max)
{
    sss_lut_desc d;
    memset(&d, 0, sizeof d);
    d.size = size;
    d.axes = axes;
    d.r_max = r_max;
    sss_lut lut;
    sss_error err = {0};
    sss_result res = sss_lut_build(p, &d, &lut, &err);
    CHECK_MSG(res == SSS_OK, "%s", err.message);
    if (res != SSS_OK) exit(1);
    return lut;
}

static const float *texel(const sss_lut *lut, int i, int j) { return lut->texels + 3 * ((size_t)j * lut->size + i); }

/* Every texel finite and non-negative. */
static void check_finite(const sss_lut *lut, const char *what)
{
    size_t bad = 0, n = 3 * (size_t)lut->size * lut->size;
    for (size_t k = 0; k < n; k++)
        if (!isfinite(lut->texels[k]) || lut->texels[k] < 0.0f) bad++;
    CHECK_MSG(bad == 0, "%s: %zu texels non-finite or negative", what, bad);
}

/* Row j = 0 is R_d itself; row 1 of a sqrt-axes LUT (r_A = r_max / (size - 1)) differs from R_d(r)
 * only by the curvature term r_A^2 / 8 * laplacian(R_d) ~ (r_A / r)^2 / 8 for r >= 20 r_A. */
static void check_small_area(const sss_profile *p, const char *what)
{
    sss_lut lut = build(p, 512, SSS_LUT_AXES_SQRT, 0.0);
    check_finite(&lut, what);
    double ra = sqrt(sss_lut_texel_area(&lut, 1) / TU_PI), worst = 0.0;
    CHECK_REL(ra, lut.r_max / 511.0, 1e-12);
    for (int i = 0; i < 512; i++) {
        double r = sss_lut_texel_r(&lut, i), rd[3];
        sss_profile_eval_rgb(p, r, rd);
        for (int c = 0; c < 3; c++) {
            CHECK_MSG(texel(&lut, i, 0)[c] == (float)rd[c], "%s: row 0 at r %g", what, r);
            if (r < 20.0 * ra || rd[c] < 1e-6 * texel(&lut, 0, 0)[c]) continue;
            double e = fabs(texel(&lut, i, 1)[c] - rd[c]) / rd[c];
            if (e > worst) worst = e;
        }
    }
    CHECK_MSG(worst < 1e-3, "%s: smallest area row vs R_d: worst relative difference %.3g", what, worst);
    sss_lut_free(&lut);
}

/* Column i = 0 (a disc centred on the origin) against an independent 1D quadrature. */
static void check_origin_column(const sss_profile *p, sss_lut_axes axes, const char *what)
{
    sss_lut lut = build(p, 128, axes, 0.0);
    double worst = 0.0;
    for (int j = 1; j < 128; j += 9) {
        double a = sss_lut_texel_area(&lut, j), ref[3];
        tu_disc_at_origin(p, sqrt(a / TU_PI), ref);
        for (int c = 0; c < 3; c++) {
            double e = fabs(texel(&lut, 0, j)[c] - ref[c] / a) / (ref[c] / a);
            if (e > worst) worst = e;
        }
    }
    CHECK_MSG(worst < 2e-4, "%s: r = 0 column vs 1D quadrature: worst relative difference %.3g", what, worst);
    sss_lut_free(&lut);
}

/* Random texels (and a few near r = r_A and near the origin) against the brute-force 2D integral.
 * Relative tolerance 0.5%, measured against the value or, where a channel's tail has fallen below
 * 1e-4 of that row's value at r = 0, against that floor (the PBD table's spline wiggles there). */
static void check_random(const sss_profile *p, sss_lut_axes axes, int count, const char *what)
{
    sss_lut lut = build(p, 64, axes, 0.0);
    check_finite(&lut, what);
    unsigned long long s = 12345;
    double worst = 0.0;
    for (int k = 0; k < count; k++) {
        int i = 1 + (int)(tu_rand(&s) * 63), j = 1 + (int)(tu_rand(&s) * 63);
        if (k == 0) i = j = 1;                      /* both small */
        if (k == 1) i = 40, j = 40;                 /* near the diagonal r ~ r_A */
        if (k == 2) i = 63, j = 1;                  /* small disc far out */
        double r = sss_lut_texel_r(&lut, i), a = sss_lut_texel_area(&lut, j), ref[3];
        tu_disc_average(p, r, a, ref);
        for (int c = 0; c < 3; c++) {
            double floor = 1e-4 * texel(&lut, 0, j)[c];
            double e = fabs(texel(&lut, i, j)[c] - ref[c]) / fmax(ref[c], floor);
            if (e > worst) worst = e;
            CHECK_MSG(e < 5e-3, "%s: texel (%d, %d) r %g A %g channel %d: LUT %g, brute force %g", what, i,
                      j, r, a, c, texel(&lut, i, j)[c], ref[c]);
        }
    }
    printf("%s: worst relative difference to the brute force %.3g\n", what, worst);
    sss_lut_free(&lut);
}

/* A disc much larger than the profile: A R'_d = the plane integral (closed form for the dipole). */
static void check_energy(void)
{
    sss_profile p = tu_profile("Skin1", SSS_PROFILE_DIPOLE, NULL);
    /* e^(-sigma_tr r) < 1e-10 beyond 25 / sigma_tr of the slowest channel; the disc of radius r_max
     * centred at r <= 0.25 r_max covers that. */
    double r_max = 0.0;
    for (int c = 0; c < 3; c++) r_max = fmax(r_max, 25.0 / p.dipole[c].sigma_tr / 0.75);
    sss_lut lut = build(&p, 64, SSS_LUT_AXES_LINEAR, r_max);
    CHECK_REL(lut.a_max, TU_PI * r_max * r_max, 1e-12);
    for (int i = 0; i <= 16; i += 4)
        for (int c = 0; c < 3; c++)
            CHECK_REL(lut.a_max * texel(&lut, i, 63)[c], sss_dipole_total_reflectance(&p.dipole[c]), 1e-4);
    sss_lut_free(&lut);
}

/* The six-Gaussian fit at r = 0: (1/A) sum_k w_k (1 - e^(-r_A^2 / 2 v_k)). */
static void check_gauss6(void)
{
    sss_profile p;
    CHECK(sss_profile_init(&p, SSS_PROFILE_GAUSS6, NULL, NULL, NULL) == SSS_OK);
    sss_lut lut = build(&p, 64, SSS_LUT_AXES_SQRT, 0.0);
    check_finite(&lut, "gauss6");
    for (int j = 1; j < 64; j += 7) {
        double a = sss_lut_texel_area(&lut, j), ra2 = a / TU_PI;
        for (int c = 0; c < 3; c++) {
            double ref = 0.0;
            for (int k = 0; k < SSS_GAUSS6_TERMS; k++)
                ref -= sss_gauss6_weight[c][k] * expm1(-ra2 / (2.0 * sss_gauss6_variance_mm2[k]));
            CHECK_REL(texel(&lut, 0, j)[c], ref / a, 1e-4);
        }
    }
    sss_lut_free(&lut);
}

/* Maisch & Ropinski 2020, section 7.1: Q(r_max) = alpha' sigma_t' e^(-sigma_t' r_max) equals the cut-off in the
 * channel that sets r_max and is below it in the others. */
static void check_r_max(void)
{
    sss_material m;
    CHECK(sss_material_from_medium("Ketchup", 2.0, 1.33, &m, NULL) == SSS_OK);
    double cut = 1e-7, r_max = sss_lut_r_max(&m, 0.0);
    CHECK(r_max == sss_lut_r_max(&m, cut));
    double qmax = 0.0;
    for (int c = 0; c < 3; c++) {
        double stp = m.sigma_a[c] + m.sigma_s[c], ap = m.sigma_s[c] / stp;
        double q = ap * stp * exp(-stp * r_max);
        CHECK(q <= cut * (1.0 + 1e-9));
        qmax = fmax(qmax, q);
    }
    CHECK_REL(qmax, cut, 1e-9);
    /* Larger cut-off, shorter r_max; no channel above the cut-off gives 0. */
    CHECK(sss_lut_r_max(&m, 1e-3) < r_max);
    CHECK(sss_lut_r_max(&m, 1e3) == 0.0);
    CHECK(sss_lut_r_max(NULL, cut) == 0.0);
}

/* Bilinear lookups return texels at texel coordinates, interpolate between them, clamp outside. */
static void check_lookup(const sss_profile *p)
{
    for (int axes = 0; axes < 2; axes++) {
        sss_lut lut = build(p, 32, (sss_lut_axes)axes, 0.0);
        double v[3], v2[3];
        for (int i = 0; i < 32; i += 5)
            for (int j = 0; j < 32; j += 6) {
                sss_lut_lookup(&lut, sss_lut_texel_r(&lut, i), sss_lut_texel_area(&lut, j), v);
                for (int c = 0; c < 3; c++) CHECK_REL(v[c], texel(&lut, i, j)[c], 1e-5);
            }
        /* Half-way in the lookup coordinate: the mean of the neighbours. */
        double u = axes ? 0.5 * (sqrt(sss_lut_texel_r(&lut, 3) / lut.r_max) + sqrt(sss_lut_texel_r(&lut, 4) / lut.r_max))
                        : 0.5 * (sss_lut_texel_r(&lut, 3) + sss_lut_texel_r(&lut, 4)) / lut.r_max;
        double r = axes ? u * u * lut.r_max : u * lut.r_max;
        sss_lut_lookup(&lut, r, sss_lut_texel_area(&lut, 7), v);
        for (int c = 0; c < 3; c++)
            CHECK_REL(v[c], 0.5 * (texel(&lut, 3, 7)[c] + texel(&lut, 4, 7)[c]), 1e-5);
        /* Clamping: beyond the ranges and negative inputs give the edge texels. */
        sss_lut_lookup(&lut, 10.0 * lut.r_max, 10.0 * lut.a_max, v);
        for (int c = 0; c < 3; c++) CHECK(v[c] == texel(&lut, 31, 31)[c]);
        sss_lut_lookup(&lut, -1.0, -1.0, v);
        sss_lut_lookup(&lut, 0.0, 0.0, v2);
        for (int c = 0; c < 3; c++) CHECK(v[c] == v2[c] && v[c] == texel(&lut, 0, 0)[c]);
        sss_lut_free(&lut);
    }
}

/* sss_lut_exact agrees with the brute force too (it is the reference of the bench's axes study). */
static void check_exact(const sss_profile *p, const char *what)
{
    double pts[4][2] = {{0.0, 1.0}, {0.3, 0.05}, {2.0, 12.0}, {5.0, 80.0}};
    for (int k = 0; k < 4; k++) {
        double e[3], b[3];
        sss_lut_exact(p, pts[k][0], pts[k][1], e);
        tu_disc_average(p, pts[k][0], pts[k][1], b);
        for (int c = 0; c < 3; c++) CHECK_MSG(fabs(e[c] - b[c]) <= 1e-4 * b[c], "%s: exact (%g, %g) ch %d: %g vs %g", what, pts[k][0], pts[k][1], c, e[c], b[c]);
    }
    double v[3], rd[3];
    sss_lut_exact(p, 0.7, 0.0, v);
    sss_profile_eval_rgb(p, 0.7, rd);
    for (int c = 0; c < 3; c++) CHECK(v[c] == rd[c]);
    sss_lut_exact(p, NAN, 1.0, v);
    CHECK(v[0] == 0.0 && v[1] == 0.0 && v[2] == 0.0);
}

/* The fast arccos of the ring weights (Abramowitz & Stegun 4.4.46: |error| <= 2e-8). */
static void check_acos(void)
{
    double worst = 0.0;
    for (int k = 0; k <= 20000; k++) {
        double y = -1.0 + k / 10000.0, nc = 1.0 + y, ns = 1.0 - y; /* y = (nc - ns) / (nc + ns) */
        worst = fmax(worst, fabs(kq_acos_ratio(nc, ns) - acos(y)));
    }
    CHECK_MSG(worst < 3e-8, "fast acos: worst error %.3g", worst);
}

static void check_errors(const sss_profile *p)
{
    sss_lut lut;
    sss_error err = {0};
    sss_lut_desc d;
    memset(&d, 0, sizeof d);
    d.size = 1;
    CHECK(sss_lut_build(p, &d, &lut, &err) == SSS_ERROR_INVALID_ARGUMENT && strstr(err.message, "size 1"));
    CHECK(lut.texels == NULL);
    d.size = 16;
    d.r_max = -2.0;
    CHECK(sss_lut_build(p, &d, &lut, &err) == SSS_ERROR_INVALID_ARGUMENT && strstr(err.message, "r_max"));
    d.r_max = 0.0;
    d.source_cutoff = 1e6; /* above every channel's source function: no r_max */
    CHECK(sss_lut_build(p, &d, &lut, &err) == SSS_ERROR_INVALID_ARGUMENT && strstr(err.message, "cut-off"));
    d.source_cutoff = 0.0;
    d.axes = (sss_lut_axes)7;
    CHECK(sss_lut_build(p, &d, &lut, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(sss_lut_build(NULL, NULL, &lut, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(sss_lut_build(p, NULL, NULL, &err) == SSS_ERROR_INVALID_ARGUMENT);
    sss_lut_free(&lut); /* zeroed by the failed build: safe */
    sss_lut_free(NULL);
    /* NULL desc means defaults: 512 x 512, linear, Q cut-off 1e-7. */
    CHECK(sss_lut_build(p, NULL, &lut, &err) == SSS_OK);
    CHECK(lut.size == 512 && lut.axes == SSS_LUT_AXES_LINEAR);
    CHECK(lut.r_max == sss_lut_r_max(&p->material, 1e-7));
    sss_lut_free(&lut);
    CHECK(lut.texels == NULL);
}

int main(void)
{
    sss_error err = {0};
    if (sss_pbd_table_build(1.33, 0.0, &table, &err) != SSS_OK) {
        fprintf(stderr, "PBD table: %s\n", err.message);
        return 1;
    }
    sss_profile dip = tu_profile("Marble", SSS_PROFILE_DIPOLE, NULL);
    sss_profile pbd = tu_profile("Marble", SSS_PROFILE_PBD, &table);
    sss_profile skin = tu_profile("Skin1", SSS_PROFILE_PBD, &table);

    check_acos();
    check_r_max();
    check_small_area(&dip, "Marble dipole");
    check_small_area(&pbd, "Marble PBD");
    check_origin_column(&dip, SSS_LUT_AXES_LINEAR, "Marble dipole linear");
    check_origin_column(&pbd, SSS_LUT_AXES_SQRT, "Marble PBD sqrt");
    check_origin_column(&skin, SSS_LUT_AXES_LINEAR, "Skin1 PBD linear");
    check_random(&dip, SSS_LUT_AXES_LINEAR, 12, "Marble dipole linear");
    check_random(&dip, SSS_LUT_AXES_SQRT, 8, "Marble dipole sqrt");
    check_random(&pbd, SSS_LUT_AXES_LINEAR, 8, "Marble PBD linear");
    check_random(&skin, SSS_LUT_AXES_SQRT, 6, "Skin1 PBD sqrt");
    check_energy();
    check_gauss6();
    check_lookup(&dip);
    check_exact(&pbd, "Marble PBD");
    check_errors(&dip);
    return CHECK_DONE();
}
