/* tests/gl/test_env_cut.c — the median cut of environment maps into directional lights (gl/env_cut.h)
 * on the maps that overflowed its buffers (small, black, one bright cell: regions that cannot split):
 * it never makes more lights than it has room for, keeps the map's energy, and puts a lone spike's
 * light at that cell's direction. Run under ASan by `make sanitize`. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "gl/core/env_cut.h"

typedef enum { MAP_UNIFORM, MAP_BLACK, MAP_SPIKE, MAP_SPARSE } map_kind;

/* A w x h map of the given kind (values are radiance x solid angle, as the cut takes them). */
static double *make_map(map_kind kind, int w, int h, unsigned seed, int *spike)
{
    double *m = calloc((size_t)w * h * 3, sizeof *m);
    *spike = (int)(seed % ((unsigned)w * h));
    for (int i = 0; i < w * h; i++) {
        double v = 0.0;
        if (kind == MAP_UNIFORM) v = 0.5;
        if (kind == MAP_SPIKE && i == *spike) v = 1e4;
        if (kind == MAP_SPARSE) {
            seed = seed * 1103515245u + 12345u;
            v = (seed >> 16) % 7 == 0 ? (double)((seed >> 8) % 1000) : 0.0;
        }
        for (int k = 0; k < 3; k++) m[3 * i + k] = v * (1.0 + 0.25 * k);
    }
    return m;
}

/* Every light is finite with a unit direction, there are at most max_lights, and together they carry
 * the map's energy per channel. */
static void check_cut(map_kind kind, int w, int h, int max_lights, unsigned seed)
{
    int spike;
    double *map = make_map(kind, w, h, seed, &spike);
    const double scale[3] = {1.0, 2.0, 0.5};
    gl_env_light *lights = calloc((size_t)max_lights, sizeof *lights);
    int count = -1;
    sss_error err = {0};
    CHECK(gl_env_median_cut(map, w, h, scale, 30.0, max_lights, lights, &count, &err) == SSS_OK);
    CHECK_MSG(count >= 0 && count <= max_lights, "%dx%d kind %d: %d lights for %d", w, h, kind, count, max_lights);
    double total[3] = {0, 0, 0}, sum[3] = {0, 0, 0};
    for (int i = 0; i < w * h; i++)
        for (int k = 0; k < 3; k++) total[k] += map[3 * i + k] * scale[k];
    for (int i = 0; i < count && i < max_lights; i++) {
        const double *d = lights[i].to_light;
        CHECK_NEAR(d[0] * d[0] + d[1] * d[1] + d[2] * d[2], 1.0, 1e-9);
        for (int k = 0; k < 3; k++) {
            CHECK(isfinite(lights[i].rgb[k]) && lights[i].rgb[k] > 0.0);
            sum[k] += lights[i].rgb[k];
        }
    }
    for (int k = 0; k < 3; k++) CHECK_NEAR(sum[k], total[k], 1e-9 * total[k]);
    if (kind == MAP_BLACK) CHECK(count == 0);
    if (kind == MAP_SPIKE) {
        CHECK_MSG(count == 1, "%dx%d spike: %d lights", w, h, count);
        /* the cell centre's direction, written out (docs/scene-format.md, environment lights) */
        double u = (spike % w + 0.5) / w, v = (spike / w + 0.5) / h;
        double p = 2.0 * M_PI * (u - 0.5) - 30.0 * M_PI / 180.0, t = M_PI * v;
        CHECK_NEAR(lights[0].to_light[0], sin(t) * sin(p), 1e-12);
        CHECK_NEAR(lights[0].to_light[1], cos(t), 1e-12);
        CHECK_NEAR(lights[0].to_light[2], -sin(t) * cos(p), 1e-12);
    }
    free(lights);
    free(map);
}

/* The maps of the overflow report (an 8x8 grey map, a 64x32 black one, 256x128 with one bright cell,
 * the 32x32 map `sss reference` writes) and every size to 9x9 for every light count to 70. */
static void test_small_maps(void)
{
    check_cut(MAP_UNIFORM, 8, 8, 32, 1);
    check_cut(MAP_BLACK, 64, 32, 32, 1);
    check_cut(MAP_SPIKE, 256, 128, 32, 12345);
    check_cut(MAP_SPARSE, 32, 32, 32, 7);
    for (int w = 1; w <= 9; w++)
        for (int h = 1; h <= 9; h++)
            for (int n = 1; n <= 70; n += (n < 8 ? 1 : 7)) {
                check_cut(MAP_UNIFORM, w, h, n, 3);
                check_cut(MAP_SPIKE, w, h, n, (unsigned)(w * 31 + h));
                check_cut(MAP_SPARSE, w, h, n, (unsigned)(w * 7 + h * 13 + n));
            }
}

/* A uniform map large enough to split everywhere gives exactly the requested number of lights,
 * each carrying about an equal share (Debevec's equal-energy regions, to a cell's quantisation). */
static void test_uniform_equal_energy(void)
{
    int w = 256, h = 128, n = 32, spike;
    double *map = make_map(MAP_UNIFORM, w, h, 0, &spike);
    /* radiance x exact solid angle of the cell, so that energy is uniform per steradian */
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            for (int k = 0; k < 3; k++)
                map[3 * ((size_t)y * w + x) + k] *= (cos(M_PI * y / h) - cos(M_PI * (y + 1) / h)) * 2.0 * M_PI / w;
    gl_env_light lights[32];
    int count = 0;
    sss_error err = {0};
    CHECK(gl_env_median_cut(map, w, h, (double[3]){1, 1, 1}, 0.0, n, lights, &count, &err) == SSS_OK);
    CHECK(count == n);
    double total = 0.0;
    for (int i = 0; i < w * h; i++) total += map[3 * i];
    for (int i = 0; i < count; i++) CHECK_REL(lights[i].rgb[0], total / n, 0.15);
    free(map);
}

static void test_errors(void)
{
    double cell[3] = {1, 1, 1};
    gl_env_light l;
    int count = 7;
    sss_error err = {0};
    CHECK(gl_env_median_cut(cell, 0, 1, (double[3]){1, 1, 1}, 0, 1, &l, &count, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(count == 0 && strstr(err.message, "0x1") != NULL);
    CHECK(gl_env_median_cut(cell, 1, 1, (double[3]){1, 1, 1}, 0, 0, &l, &count, &err) == SSS_ERROR_INVALID_ARGUMENT);
}

int main(void)
{
    test_small_maps();
    test_uniform_equal_energy();
    test_errors();
    return CHECK_DONE();
}
