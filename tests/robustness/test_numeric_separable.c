/* Numerical robustness of the separable kernels (Jimenez et al. 2019) over the sweep of sweep_util.h (every
 * measured medium x 5 eta x 3 scales, PBD and dipole): the 7-tap pre-integrated kernel has finite,
 * ascending offsets symmetric about 0, finite weights >= 0 summing to 1 per channel, and totals equal
 * to the profile's plane integral (sss_profile_total) within 1%; the rank-2 SVD of a 24 x 24 raster
 * has finite, non-negative, descending singular values and finite vectors. */
#include <math.h>

#include "sss/kernel.h"
#include "sweep_util.h"

#define SVD_GRID 24

static int reports;

static void sweep_separable(const sss_profile *p, const char *what)
{
    sss_separable_kernel k;
    sss_error err = {0};
    sss_result r = sss_kernel_preintegrated(p, 7, 0.0, &k, &err);
    CHECK_MSG(r == SSS_OK, "%s: %s", what, err.message);
    if (r == SSS_OK) {
        int ok = k.taps == 7 && isfinite(k.range) && k.range > 0;
        for (int i = 0; ok && i < k.taps; i++) {
            ok &= isfinite(k.offsets[i]) && fabsf(k.offsets[i] + k.offsets[k.taps - 1 - i]) <= 1e-6f * (float)k.range;
            if (i > 0) ok &= k.offsets[i] > k.offsets[i - 1];
        }
        for (int c = 0; c < 3; c++) {
            double sum = 0.0;
            for (int i = 0; i < k.taps; i++) {
                float w = k.weights[3 * i + c];
                ok &= isfinite(w) && w >= 0.0f;
                sum += w;
            }
            double total = sss_profile_total(p, c);
            ok &= fabs(sum - 1.0) <= 1e-5 && isfinite(k.total[c]) && fabs(k.total[c] - total) <= 0.01 * total + 1e-300;
        }
        if (!ok && reports++ < 10) fprintf(stderr, "%s: kernel not finite, normalised or symmetric\n", what);
        CHECK(ok);
        sss_separable_kernel_free(&k);
    }
    double extent = 0.0;
    for (int c = 0; c < 3; c++) {
        double rc = sss_profile_radius_for_fraction(p, c, 0.99);
        if (rc > extent) extent = rc;
    }
    sss_svd_kernel s;
    r = sss_kernel_svd(p, SVD_GRID, extent, 2, &s, &err);
    CHECK_MSG(r == SSS_OK, "%s: SVD: %s", what, err.message);
    if (r != SSS_OK) return;
    int ok = 1;
    for (int c = 0; c < 3; c++)
        for (int i = 0; i < SVD_GRID; i++) {
            double v = s.singular_values[c * SVD_GRID + i];
            ok &= isfinite(v) && v >= 0 && (i == 0 || v <= s.singular_values[c * SVD_GRID + i - 1] * (1 + 1e-12));
        }
    for (int i = 0; i < 2 * 3 * SVD_GRID; i++) ok &= isfinite(s.vectors[i]);
    if (!ok && reports++ < 10) fprintf(stderr, "%s: SVD kernel not finite or not descending\n", what);
    CHECK(ok);
    sss_svd_kernel_free(&s);
}

int main(void)
{
    int n = sweep_profiles(sweep_separable);
    CHECK(n >= 300);
    printf("built %d separable and %d SVD kernels\n", n, n);
    return CHECK_DONE();
}
