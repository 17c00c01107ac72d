/* bench_lut — median build time of the disc-integrated LUT (Maisch & Ropinski 2020, section 7.2): 512 x 512 x 3
 * for Marble at scale 1 (PBD, as the paper) and for the dipole; plus the accuracy of bilinear lookups
 * in the linear and the sqrt axes against sss_lut_exact (relative errors, max and mean); and the
 * SVD kernel's build (Jimenez et al. 2019, section 3) at grids 24, 25 and 128.
 * Usage: bench_lut [runs] [medium] [size]   (defaults 15 Marble 512) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "bench.h"
#include "sss/kernel.h"
#include "sss/material.h"

typedef struct ctx {
    const sss_profile *profile;
    sss_lut_desc desc;
} ctx;

static void build_once(void *p)
{
    ctx *c = p;
    sss_lut lut;
    sss_error err;
    if (sss_lut_build(c->profile, &c->desc, &lut, &err) != SSS_OK) {
        fprintf(stderr, "bench_lut: %s\n", err.message);
        exit(1);
    }
    sss_lut_free(&lut);
}

/* The SVD kernel (Jimenez et al. 2019, section 3; its cost is mostly the cell integrals of R_d at small grids). */
typedef struct svd_ctx {
    const sss_profile *profile;
    int grid;
    double extent;
} svd_ctx;

static void svd_once(void *p)
{
    svd_ctx *c = p;
    sss_svd_kernel k;
    sss_error err;
    if (sss_kernel_svd(c->profile, c->grid, c->extent, 3, &k, &err) != SSS_OK) {
        fprintf(stderr, "bench_lut: %s\n", err.message);
        exit(1);
    }
    sss_svd_kernel_free(&k);
}

/* Deterministic uniform numbers in [0, 1) (xorshift64*), so runs are comparable. */
static double rnd(unsigned long long *s)
{
    *s ^= *s >> 12;
    *s ^= *s << 25;
    *s ^= *s >> 27;
    return (double)((*s * 2685821657736338717ULL) >> 11) * (1.0 / 9007199254740992.0);
}

/* Lookup errors against sss_lut_exact at n points: (r, A) uniform, or log-uniform in [1e-4, 1] of
 * the axes (near r = 0 and A = 0). Relative error per channel where the exact value is above 1e-6 of
 * the row's R_d(0) scale. */
static void accuracy(const sss_profile *profile, sss_lut_axes axes, int size, int near_zero, int n)
{
    sss_lut_desc d = {0};
    d.size = size;
    d.axes = axes;
    sss_lut lut;
    sss_error err;
    if (sss_lut_build(profile, &d, &lut, &err) != SSS_OK) {
        fprintf(stderr, "bench_lut: %s\n", err.message);
        exit(1);
    }
    unsigned long long s = 0x9E3779B97F4A7C15ULL;
    double max_e = 0.0, sum_e = 0.0;
    int count = 0;
    for (int k = 0; k < n; k++) {
        double u = rnd(&s), v = rnd(&s);
        if (near_zero) {
            u = pow(10.0, -4.0 * u);
            v = pow(10.0, -4.0 * v);
        }
        double r = u * lut.r_max, a = v * lut.a_max, ex[3], lk[3];
        sss_lut_exact(profile, r, a, ex);
        sss_lut_lookup(&lut, r, a, lk);
        for (int c = 0; c < 3; c++) {
            if (!(ex[c] > 1e-300)) continue;
            double e = fabs(lk[c] - ex[c]) / ex[c];
            if (e > max_e) max_e = e;
            sum_e += e;
            count++;
        }
    }
    printf("  %-6s axes, %s: max rel err %.3e  mean %.3e  (%d values)\n",
           axes == SSS_LUT_AXES_SQRT ? "sqrt" : "linear", near_zero ? "near r=0/A=0 (log-uniform)" : "uniform (r, A)   ",
           max_e, count ? sum_e / count : 0.0, count);
    sss_lut_free(&lut);
}

int main(int argc, char **argv)
{
    int runs = argc > 1 ? atoi(argv[1]) : 15;
    const char *medium = argc > 2 ? argv[2] : "Marble";
    int size = argc > 3 ? atoi(argv[3]) : 512;
    if (runs < 1) runs = 1;
    sss_error err;
    sss_material m;
    static sss_pbd_table table;
    if (sss_material_from_medium(medium, 1.0, 1.33, &m, &err) != SSS_OK ||
        sss_pbd_table_build(1.33, 0.0, &table, &err) != SSS_OK) {
        fprintf(stderr, "bench_lut: %s\n", err.message);
        return 1;
    }
    const char *names[2] = {"PBD", "dipole"};
    sss_profile_model models[2] = {SSS_PROFILE_PBD, SSS_PROFILE_DIPOLE};
    for (int k = 0; k < 2; k++) {
        sss_profile p;
        if (sss_profile_init(&p, models[k], &m, &table, &err) != SSS_OK) {
            fprintf(stderr, "bench_lut: %s\n", err.message);
            return 1;
        }
        ctx c = {&p, {0}};
        c.desc.size = size;
        char label[96];
        build_once(&c); /* warm up (OpenMP threads, page faults) */
        snprintf(label, sizeof label, "LUT %dx%dx3 %s %s linear", size, size, medium, names[k]);
        bench_run(label, runs, build_once, &c);
        c.desc.axes = SSS_LUT_AXES_SQRT;
        snprintf(label, sizeof label, "LUT %dx%dx3 %s %s sqrt", size, size, medium, names[k]);
        bench_run(label, runs, build_once, &c);
        /* SVD kernels over the square holding 99.9% of the energy (as the ssss-svd technique) */
        svd_ctx sc = {&p, 0, 0.0};
        for (int ch = 0; ch < 3; ch++) sc.extent = fmax(sc.extent, sss_profile_radius_for_fraction(&p, ch, 0.999));
        const int grids[3] = {24, 25, 128};
        for (int g = 0; g < 3; g++) {
            sc.grid = grids[g];
            snprintf(label, sizeof label, "SVD kernel grid %d rank 3 %s %s", sc.grid, medium, names[k]);
            bench_run(label, runs, svd_once, &sc);
        }
    }
    /* Accuracy of bilinear lookups, linear vs sqrt axes (the numbers quoted in sss/kernel.h). */
    for (int k = 0; k < 2; k++) {
        sss_profile p;
        sss_profile_init(&p, models[k], &m, &table, &err);
        printf("lookup accuracy, %s %s, %dx%d:\n", medium, names[k], size, size);
        for (int near_zero = 0; near_zero < 2; near_zero++) {
            accuracy(&p, SSS_LUT_AXES_LINEAR, size, near_zero, 2000);
            accuracy(&p, SSS_LUT_AXES_SQRT, size, near_zero, 2000);
        }
    }
    return 0;
}
