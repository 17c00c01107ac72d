/* The shared animation definition (sss/scene.h): geometric properties of twist, bend and wave, rest
 * poses, continuity, normals against finite-difference tangents, validation. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "sss/scene.h"

static const double PI = 3.14159265358979323846;
static const float LO[3] = {-1.0f, 0.5f, -0.5f}, HI[3] = {1.0f, 2.5f, 0.5f}; /* H = 2, W = 2 */

static double frand(double a, double b)
{
    return a + (b - a) * (rand() / (double)RAND_MAX);
}

static void random_point(float p[3])
{
    for (int i = 0; i < 3; i++) p[i] = (float)frand(LO[i], HI[i]);
}

static double dist3f(const float a[3], const float b[3])
{
    double d0 = a[0] - b[0], d1 = a[1] - b[1], d2 = a[2] - b[2];
    return sqrt(d0 * d0 + d1 * d1 + d2 * d2);
}

static void test_rest_poses(void)
{
    sss_animation tw = {SSS_ANIMATION_TWIST, 40, 2}, be = {SSS_ANIMATION_BEND, 30, 2}, no = {SSS_ANIMATION_NONE, 5, 1};
    srand(1);
    for (int k = 0; k < 100; k++) {
        float p[3], q[3];
        random_point(p);
        /* twist and bend are the identity at t = 0 and every half period. */
        const double times[3] = {0.0, 1.0, 4.0};
        for (int i = 0; i < 3; i++) {
            sss_animation_deform_point(&tw, LO, HI, times[i], p, q);
            CHECK(dist3f(p, q) < 1e-5);
            sss_animation_deform_point(&be, LO, HI, times[i], p, q);
            CHECK(dist3f(p, q) < 1e-5);
        }
        /* No animation: unchanged at any time. */
        sss_animation_deform_point(&no, LO, HI, 0.37, p, q);
        CHECK(memcmp(p, q, sizeof p) == 0);
        sss_animation_deform_point(NULL, LO, HI, 0.37, p, q);
        CHECK(memcmp(p, q, sizeof p) == 0);
        /* The base of the box (h = 0) never moves under twist and bend. */
        float base[3] = {p[0], LO[1], p[2]};
        sss_animation_deform_point(&tw, LO, HI, 0.5, base, q);
        CHECK(dist3f(base, q) < 1e-6);
        sss_animation_deform_point(&be, LO, HI, 0.5, base, q);
        CHECK(dist3f(base, q) < 1e-6);
    }
}

static void test_twist(void)
{
    sss_animation a = {SSS_ANIMATION_TWIST, 40, 2};
    srand(2);
    for (int k = 0; k < 100; k++) {
        float p[3], q[3];
        random_point(p);
        double t = frand(0, 5);
        sss_animation_deform_point(&a, LO, HI, t, p, q);
        /* A rotation about the vertical axis through the box centre (0, *, 0): height and distance from
         * the axis are kept. */
        CHECK_NEAR(q[1], p[1], 1e-6);
        CHECK_NEAR(hypot(q[0], q[2]), hypot(p[0], p[2]), 1e-5);
    }
    /* At the peak (t = period / 4) the top turns by the amplitude, the middle by half of it,
     * counter-clockwise seen from +y (x towards -z). */
    float top[3] = {1, HI[1], 0}, mid[3] = {1, 0.5f * (LO[1] + HI[1]), 0}, q[3];
    sss_animation_deform_point(&a, LO, HI, 0.5, top, q);
    CHECK_NEAR(atan2(-q[2], q[0]) * 180 / PI, 40, 1e-4);
    sss_animation_deform_point(&a, LO, HI, 0.5, mid, q);
    CHECK_NEAR(atan2(-q[2], q[0]) * 180 / PI, 20, 1e-4);
    /* Half a period later it turns the other way. */
    sss_animation_deform_point(&a, LO, HI, 1.5, top, q);
    CHECK_NEAR(atan2(-q[2], q[0]) * 180 / PI, -40, 1e-4);
}

static void test_bend(void)
{
    sss_animation a = {SSS_ANIMATION_BEND, 30, 2};
    srand(3);
    const double pivot[2] = {0, LO[1]};
    for (int k = 0; k < 100; k++) {
        float p[3], q[3];
        random_point(p);
        double t = frand(0, 5);
        sss_animation_deform_point(&a, LO, HI, t, p, q);
        /* A rotation about +z around the pivot at the base centre: z and the distance to the pivot are
         * kept. */
        CHECK_NEAR(q[2], p[2], 1e-6);
        CHECK_NEAR(hypot(q[0] - pivot[0], q[1] - pivot[1]), hypot(p[0] - pivot[0], p[1] - pivot[1]), 1e-5);
    }
    /* At the peak the top centre tilts by the amplitude (towards -x), a quarter of the height by
     * amplitude / 16 (the angle grows with height^2). */
    float top[3] = {0, HI[1], 0}, quarter[3] = {0, LO[1] + 0.25f * (HI[1] - LO[1]), 0}, q[3];
    sss_animation_deform_point(&a, LO, HI, 0.5, top, q);
    CHECK_NEAR(atan2(-q[0], q[1] - pivot[1]) * 180 / PI, 30, 1e-4);
    sss_animation_deform_point(&a, LO, HI, 0.5, quarter, q);
    CHECK_NEAR(atan2(-q[0], q[1] - pivot[1]) * 180 / PI, 30.0 / 16, 1e-4);
}

static void test_wave(void)
{
    sss_animation a = {SSS_ANIMATION_WAVE, 0.1, 2};
    srand(4);
    for (int k = 0; k < 100; k++) {
        float p[3], q[3], q2[3], q3[3];
        random_point(p);
        double t = frand(0, 5);
        sss_animation_deform_point(&a, LO, HI, t, p, q);
        /* Only y moves, by at most the amplitude. */
        CHECK(q[0] == p[0] && q[2] == p[2]);
        CHECK(fabs(q[1] - p[1]) <= 0.1 + 1e-6);
        /* Periodic in time; half a period flips the displacement. */
        sss_animation_deform_point(&a, LO, HI, t + 2, p, q2);
        CHECK_NEAR(q2[1], q[1], 1e-5);
        sss_animation_deform_point(&a, LO, HI, t + 1, p, q3);
        CHECK_NEAR(q3[1] - p[1], -(q[1] - p[1]), 1e-5);
        /* One wavelength across the box: x and x + W move alike. */
        float p2[3] = {p[0] + (HI[0] - LO[0]), p[1], p[2]};
        sss_animation_deform_point(&a, LO, HI, t, p2, q2);
        CHECK_NEAR(q2[1] - p2[1], q[1] - p[1], 1e-5);
    }
    /* A travelling wave moves points at t = 0 (only where sin(2 pi x / W) = 0 do they stay). */
    float p[3] = {-0.5f, 1, 0}, q[3];
    sss_animation_deform_point(&a, LO, HI, 0, p, q);
    CHECK_NEAR(q[1] - p[1], 0.1 * sin(2 * PI * 0.25), 1e-6);
    float p0[3] = {LO[0], 1, 0};
    sss_animation_deform_point(&a, LO, HI, 0, p0, q);
    CHECK_NEAR(q[1], p0[1], 1e-7);
}

/* Continuity: nearby points stay nearby (a Lipschitz bound with a modest constant), including points
 * slightly outside the box (the map is not clamped). */
static void test_continuity(void)
{
    const sss_animation anims[3] = {{SSS_ANIMATION_TWIST, 90, 1.5}, {SSS_ANIMATION_BEND, 45, 1.5},
                                    {SSS_ANIMATION_WAVE, 0.3, 1.5}};
    srand(5);
    for (int a = 0; a < 3; a++)
        for (int k = 0; k < 200; k++) {
            float p[3], p2[3], q[3], q2[3];
            for (int i = 0; i < 3; i++) p[i] = (float)frand(LO[i] - 0.2, HI[i] + 0.2);
            for (int i = 0; i < 3; i++) p2[i] = p[i] + (float)frand(-1e-3, 1e-3);
            double t = frand(0, 3);
            sss_animation_deform_point(&anims[a], LO, HI, t, p, q);
            sss_animation_deform_point(&anims[a], LO, HI, t, p2, q2);
            CHECK_MSG(dist3f(q, q2) <= 5 * dist3f(p, p2) + 1e-6, "animation %d: jump %g for step %g", a,
                      dist3f(q, q2), dist3f(p, p2));
            /* ... and in time. */
            sss_animation_deform_point(&anims[a], LO, HI, t + 1e-4, p, q2);
            CHECK(dist3f(q, q2) < 1e-2);
        }
}

/* Deformed normals are perpendicular to deformed tangents, the latter by central differences of the
 * point map (independent of the analytic Jacobian). */
static void test_normals(void)
{
    const sss_animation anims[3] = {{SSS_ANIMATION_TWIST, 70, 2}, {SSS_ANIMATION_BEND, 35, 2},
                                    {SSS_ANIMATION_WAVE, 0.25, 2}};
    srand(6);
    for (int a = 0; a < 3; a++)
        for (int k = 0; k < 200; k++) {
            float p[3], n[3], nn[3];
            random_point(p);
            double t = frand(0, 4), len = 0, d[3], e[3];
            for (int i = 0; i < 3; i++) {
                d[i] = frand(-1, 1);
                e[i] = frand(-1, 1);
            }
            /* n = d x e, tangents d and e. */
            double nd[3] = {d[1] * e[2] - d[2] * e[1], d[2] * e[0] - d[0] * e[2], d[0] * e[1] - d[1] * e[0]};
            len = sqrt(nd[0] * nd[0] + nd[1] * nd[1] + nd[2] * nd[2]);
            if (len < 1e-3) continue;
            for (int i = 0; i < 3; i++) n[i] = (float)(nd[i] / len);
            sss_animation_deform_normal(&anims[a], LO, HI, t, p, n, nn);
            CHECK_NEAR(sqrt((double)nn[0] * nn[0] + (double)nn[1] * nn[1] + (double)nn[2] * nn[2]), 1, 1e-5);
            const double *tans[2] = {d, e};
            for (int j = 0; j < 2; j++) {
                const double h = 1e-3;
                float pp[3], pm[3], qp[3], qm[3];
                for (int i = 0; i < 3; i++) {
                    pp[i] = (float)(p[i] + h * tans[j][i]);
                    pm[i] = (float)(p[i] - h * tans[j][i]);
                }
                sss_animation_deform_point(&anims[a], LO, HI, t, pp, qp);
                sss_animation_deform_point(&anims[a], LO, HI, t, pm, qm);
                double tg[3], tl = 0, dt = 0;
                for (int i = 0; i < 3; i++) {
                    tg[i] = ((double)qp[i] - qm[i]) / (2 * h);
                    tl += tg[i] * tg[i];
                    dt += tg[i] * nn[i];
                }
                CHECK_MSG(fabs(dt) / sqrt(tl) < 2e-3, "animation %d: normal . tangent = %g", a, dt / sqrt(tl));
            }
            /* The deformed normal keeps its side: it points like the cross product of the deformed
             * tangents (det J > 0 for these amplitudes). */
            double jd[3], je[3];
            for (int j = 0; j < 2; j++) {
                const double h = 1e-3;
                float pp[3], pm[3], qp[3], qm[3];
                for (int i = 0; i < 3; i++) {
                    pp[i] = (float)(p[i] + h * tans[j][i]);
                    pm[i] = (float)(p[i] - h * tans[j][i]);
                }
                sss_animation_deform_point(&anims[a], LO, HI, t, pp, qp);
                sss_animation_deform_point(&anims[a], LO, HI, t, pm, qm);
                for (int i = 0; i < 3; i++) (j ? je : jd)[i] = ((double)qp[i] - qm[i]) / (2 * h);
            }
            double cr[3] = {jd[1] * je[2] - jd[2] * je[1], jd[2] * je[0] - jd[0] * je[2], jd[0] * je[1] - jd[1] * je[0]};
            CHECK(cr[0] * nn[0] + cr[1] * nn[1] + cr[2] * nn[2] > 0);
        }
}

static void test_validation_and_mesh(void)
{
    sss_error err = {0};
    sss_animation bad = {SSS_ANIMATION_TWIST, 10, 0};
    CHECK(sss_animation_validate(&bad, &err) == SSS_ERROR_INVALID_ARGUMENT && strstr(err.message, "period"));
    bad.period = -1;
    CHECK(sss_animation_validate(&bad, &err) == SSS_ERROR_INVALID_ARGUMENT);
    bad.period = NAN;
    CHECK(sss_animation_validate(&bad, &err) == SSS_ERROR_INVALID_ARGUMENT);
    bad.period = 1;
    bad.amplitude = INFINITY;
    CHECK(sss_animation_validate(&bad, &err) == SSS_ERROR_INVALID_ARGUMENT);
    bad.amplitude = 1;
    bad.type = (sss_animation_type)17;
    CHECK(sss_animation_validate(&bad, &err) == SSS_ERROR_INVALID_ARGUMENT);

    /* Whole-mesh helper: the same as the point functions, the input left alone. */
    float pos[9] = {0, 0.5f, 0, 1, 2.5f, 0, -1, 1.5f, 0.5f}, nor[9] = {0, 0, 1, 0, 0, 1, 0, 0, 1};
    uint32_t idx[3] = {0, 1, 2};
    sss_mesh m = {3, 1, pos, nor, NULL, idx, 0};
    sss_animation tw = {SSS_ANIMATION_TWIST, 60, 1};
    sss_mesh out;
    CHECK(sss_animation_deform_mesh(&tw, LO, HI, 0.25, &m, &out, &err) == SSS_OK);
    for (int v = 0; v < 3; v++) {
        float q[3], n[3];
        sss_animation_deform_point(&tw, LO, HI, 0.25, &pos[3 * v], q);
        sss_animation_deform_normal(&tw, LO, HI, 0.25, &pos[3 * v], &nor[3 * v], n);
        CHECK(memcmp(q, &out.positions[3 * v], sizeof q) == 0);
        CHECK(memcmp(n, &out.normals[3 * v], sizeof n) == 0);
    }
    CHECK(pos[3] == 1 && out.indices[2] == 2 && out.indices != idx);
    sss_mesh_free(&out);
    bad.type = SSS_ANIMATION_WAVE;
    bad.period = 0;
    CHECK(sss_animation_deform_mesh(&bad, LO, HI, 0, &m, &out, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(sss_animation_deform_mesh(&tw, LO, HI, INFINITY, &m, &out, &err) == SSS_ERROR_INVALID_ARGUMENT);
}

int main(void)
{
    test_rest_poses();
    test_twist();
    test_bend();
    test_wave();
    test_continuity();
    test_normals();
    test_validation_and_mesh();
    return CHECK_DONE();
}
