/* Numerical robustness of the disc-integrated LUT (Maisch & Ropinski 2020) over the sweep of sweep_util.h (every
 * measured medium x 5 eta x 3 scales, PBD and dipole), at size 32, with the default r_max (Maisch & Ropinski 2020's
 * source cut-off) and with r_max holding 99.9% of the widest channel's energy: the build succeeds,
 * every texel is finite and >= 0, row A = 0 is R_d itself, bilinear lookups stay finite and >= 0; with
 * the energy r_max, the disc of radius r_max centred on the origin (texel (0, A_max) x A_max) holds
 * between 99% and 101% of the plane integral (sss_profile_total, an independent integral).
 * (The default rule keeps 72-97% depending on the scene's unit scale: a cut-off on the source
 * function in absolute units, as the paper has it; the renderers choose r_max by energy.) */
#include <float.h>
#include <math.h>

#include "sss/kernel.h"
#include "sweep_util.h"

#define LUT_N 32

static int reports;

static void sweep_lut(const sss_profile *p, const char *what, int by_energy)
{
    sss_lut lut;
    sss_error err = {0};
    sss_lut_desc desc = {LUT_N, SSS_LUT_AXES_LINEAR, 0.0, 0.0};
    for (int c = 0; by_energy && c < 3; c++) {
        double r = sss_profile_radius_for_fraction(p, c, 0.999);
        if (r > desc.r_max) desc.r_max = r;
    }
    sss_result r = sss_lut_build(p, &desc, &lut, &err);
    CHECK_MSG(r == SSS_OK, "%s: %s", what, err.message);
    if (r != SSS_OK) return;
    CHECK(lut.size == LUT_N && isfinite(lut.r_max) && lut.r_max > 0 && isfinite(lut.a_max) && lut.a_max > 0);
    int bad = 0;
    for (size_t k = 0; k < 3u * LUT_N * LUT_N; k++)
        if (!isfinite(lut.texels[k]) || lut.texels[k] < 0.0f) bad++;
    if (bad && reports++ < 10) fprintf(stderr, "%s: %d texels not finite or negative\n", what, bad);
    CHECK(bad == 0);
    /* Row A = 0 stores R_d (in float: relative 1e-6, or the float's smallest step for denormals). */
    for (int i = 0; i < LUT_N; i++) {
        double v[3];
        sss_profile_eval_rgb(p, sss_lut_texel_r(&lut, i), v);
        for (int c = 0; c < 3; c++) {
            double t = lut.texels[3 * i + c];
            CHECK_MSG(fabs(t - v[c]) <= 1e-6 * v[c] + FLT_TRUE_MIN, "%s: row A = 0 texel %d channel %d: %g vs R_d %g",
                      what, i, c, t, v[c]);
        }
    }
    for (int c = 0; by_energy && c < 3; c++) {
        double total = sss_profile_total(p, c);
        double disc = lut.a_max * lut.texels[3 * ((size_t)(LUT_N - 1) * LUT_N) + c];
        int ok = isfinite(disc) && disc <= total * 1.01 + 1e-300 && disc >= 0.99 * total;
        if (!ok && reports++ < 10) fprintf(stderr, "%s channel %d: disc of r_max holds %g of %g\n", what, c, disc, total);
        CHECK(ok);
    }
    for (int k = 0; k <= 16; k++) {
        double out[3];
        sss_lut_lookup(&lut, lut.r_max * k / 13.0, lut.a_max * k / 11.0, out);
        CHECK(isfinite(out[0]) && isfinite(out[1]) && isfinite(out[2]) && out[0] >= 0 && out[1] >= 0 && out[2] >= 0);
    }
    sss_lut_free(&lut);
}

static void both(const sss_profile *p, const char *what)
{
    sweep_lut(p, what, 0);
    sweep_lut(p, what, 1);
}

int main(void)
{
    int n = sweep_profiles(both);
    CHECK(n >= 300);
    printf("built %d LUTs of %d x %d\n", 2 * n, LUT_N, LUT_N);
    return CHECK_DONE();
}
