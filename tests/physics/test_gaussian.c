/* Gaussian profiles (docs/physics.md §2.4): normalisation of the 2D and 1D Gaussians, the six-Gaussian skin fit
 * and the artist-friendly presets of Jimenez et al. 2019, Table 2. */
#include <string.h>

#include "check.h"
#include "physics/physics_test_util.h"
#include "sss/profile.h"

#define PI 3.14159265358979323846

typedef struct g2_ctx {
    double v;
} g2_ctx;

static double g2_radial(double r, void *p) { return sss_gaussian_2d(((g2_ctx *)p)->v, r) * 2.0 * PI * r; }

typedef struct am_ctx {
    const sss_artist_params *p;
    int ch;
} am_ctx;

static double am_fn(double x, void *p)
{
    const am_ctx *c = (const am_ctx *)p;
    return sss_artist_eval_1d(c->p, c->ch, x);
}

int main(void)
{
    /* 2D Gaussian: integrates to 1 over the plane and factors into two normalised 1D Gaussians. */
    for (double v = 1e-3; v < 100.0; v *= 7.0) {
        g2_ctx c = {v};
        double sd = sqrt(v);
        CHECK_REL(tu_integrate(g2_radial, &c, 0.0, 40.0 * sd, 1e-13), 1.0, 1e-9);
        for (double x = 0.0; x < 3.0 * sd; x += 0.4 * sd) {
            double y = 0.7 * sd;
            double g1x = exp(-x * x / (2 * v)) / sqrt(2 * PI * v), g1y = exp(-y * y / (2 * v)) / sqrt(2 * PI * v);
            CHECK_REL(sss_gaussian_2d(v, sqrt(x * x + y * y)), g1x * g1y, 1e-12);
        }
    }
    CHECK(sss_gaussian_2d(0.0, 0.1) == 0.0 && sss_gaussian_2d(-1.0, 0.1) == 0.0);
    CHECK(sss_gaussian_2d(1.0, NAN) == 0.0);

    /* Six-Gaussian fit: the values printed in docs/physics.md §2.4; each channel's weights sum to 1 (d'Eon's
     * fit is normalised), and the variances increase. */
    static const double var[6] = {0.0064, 0.0484, 0.187, 0.567, 1.99, 7.41};
    static const double wr[6] = {0.233, 0.100, 0.118, 0.113, 0.358, 0.078};
    static const double wb[6] = {0.649, 0.344, 0, 0.007, 0, 0};
    for (int k = 0; k < 6; k++) {
        CHECK(sss_gauss6_variance_mm2[k] == var[k]);
        CHECK(sss_gauss6_weight[0][k] == wr[k] && sss_gauss6_weight[2][k] == wb[k]);
        if (k) CHECK(sss_gauss6_variance_mm2[k] > sss_gauss6_variance_mm2[k - 1]);
    }
    CHECK(sss_gauss6_weight[1][0] == 0.455 && sss_gauss6_weight[1][4] == 0.004);
    for (int c = 0; c < 3; c++) {
        double s = 0;
        for (int k = 0; k < 6; k++) s += sss_gauss6_weight[c][k];
        CHECK_NEAR(s, 1.0, 1e-12);
    }

    /* Artist presets (Jimenez et al. 2019, Table 2) and normalisation of a_m over the line. */
    sss_artist_params p;
    sss_error err;
    CHECK(sss_artist_preset("single-layer", &p, &err) == SSS_OK);
    CHECK(p.s == 10.34 && p.near[0] == 0.077 && p.near[2] == 0.02 && p.far[1] == 0.45 && p.w == 0.5);
    CHECK(sss_artist_preset("multi-layer", &p, &err) == SSS_OK);
    CHECK(p.s == 9.27 && p.near[1] == 0.044 && p.far[2] == 0.13 && p.w == 0.5);
    CHECK(sss_artist_preset("production", &p, &err) == SSS_OK);
    CHECK(p.s == 9.9 && p.near[0] == 0.22 && p.far[0] == 1.0 && p.far[2] == 0.15 && p.w == 0.65);
    static const char *const names[3] = {"single-layer", "multi-layer", "production"};
    for (int i = 0; i < 3; i++) {
        CHECK(sss_artist_preset(names[i], &p, &err) == SSS_OK);
        for (int c = 0; c < 3; c++) {
            am_ctx ac = {&p, c};
            double L = 12.0 * p.far[c] * p.s;
            double integral = tu_integrate(am_fn, &ac, -L, L, 1e-13);
            CHECK_REL(integral, 1.0, 1e-8);
            /* Symmetric, peaked at 0, and the near lobe dominates at the centre. */
            CHECK_NEAR(sss_artist_eval_1d(&p, c, 0.3), sss_artist_eval_1d(&p, c, -0.3), 1e-15);
            CHECK(sss_artist_eval_1d(&p, c, 0.0) > sss_artist_eval_1d(&p, c, 0.5 * p.near[c] * p.s));
            double sn = p.near[c] * p.s;
            CHECK_REL(sss_artist_eval_1d(&p, c, 0.0),
                      p.w / (sqrt(2 * PI) * sn) + (1 - p.w) / (sqrt(2 * PI) * p.far[c] * p.s), 1e-12);
        }
    }
    CHECK(sss_artist_preset("skin", &p, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(err.message, "skin") && strstr(err.message, "production"));
    CHECK(sss_artist_eval_1d(&p, 3, 0.0) == 0.0);
    return CHECK_DONE();
}
