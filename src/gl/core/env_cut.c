/* gl/env_cut.c — median cut of an environment map into directional lights (gl/env_cut.h). */
#include "gl/core/env_cut.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct env_region {
    int x0, y0, x1, y1; /* cell rectangle [x0, x1) x [y0, y1) */
} env_region;

typedef struct env_map {
    int w, h;
    double *lum; /* solid-angle weighted luminance per cell */
    double *rgb; /* radiance * solid angle per cell, scaled */
    double *sum; /* summed-area table of lum, (w + 1) x (h + 1) */
} env_map;

void gl_env_direction(double u, double v, double rotate_y, double out[3])
{
    double phi = 2.0 * M_PI * (u - 0.5) - rotate_y * M_PI / 180.0, th = M_PI * v;
    out[0] = sin(th) * sin(phi);
    out[1] = cos(th);
    out[2] = -sin(th) * cos(phi);
}

static double region_energy(const env_map *e, env_region r)
{
    size_t W = (size_t)e->w + 1;
    return e->sum[(size_t)r.y1 * W + (size_t)r.x1] - e->sum[(size_t)r.y0 * W + (size_t)r.x1] -
           e->sum[(size_t)r.y1 * W + (size_t)r.x0] + e->sum[(size_t)r.y0 * W + (size_t)r.x0];
}

/* The first cut c in (lo, hi) along one axis whose lower part holds half of the region's energy. */
static int median_cut(const env_map *e, env_region r, int along_x, double half)
{
    int lo = along_x ? r.x0 : r.y0, hi = along_x ? r.x1 : r.y1, best = lo + 1;
    for (int c = lo + 1; c < hi; c++) {
        env_region t = r;
        if (along_x) t.x1 = c;
        else t.y1 = c;
        best = c;
        if (region_energy(e, t) >= half) break;
    }
    return best;
}

/* Splits along the longer side (angular width: columns shrink by sin(theta)) at the energy median;
 * returns 0 for a region of one cell. */
static int split_region(const env_map *e, env_region r, env_region *a, env_region *b)
{
    double th = M_PI * 0.5 * (r.y0 + r.y1) / e->h;
    double wx = (r.x1 - r.x0) * sin(th) * 2.0, wy = (r.y1 - r.y0); /* u spans 2 pi, v spans pi */
    double half = 0.5 * region_energy(e, r);
    *a = *b = r;
    if ((wx >= wy && r.x1 - r.x0 > 1) || r.y1 - r.y0 <= 1) {
        if (r.x1 - r.x0 <= 1) return 0;
        a->x1 = b->x0 = median_cut(e, r, 1, half);
    } else {
        a->y1 = b->y0 = median_cut(e, r, 0, half);
    }
    return 1;
}

static void env_map_free(env_map *e)
{
    free(e->lum);
    free(e->rgb);
    free(e->sum);
}

static int env_map_init(env_map *e, const double *rgb, int w, int h, const double scale[3])
{
    size_t cells = (size_t)w * h, W = (size_t)w + 1;
    e->w = w;
    e->h = h;
    e->lum = calloc(cells, sizeof *e->lum);
    e->rgb = calloc(cells * 3, sizeof *e->rgb);
    e->sum = calloc(W * ((size_t)h + 1), sizeof *e->sum);
    if (!e->lum || !e->rgb || !e->sum) return 0;
    for (size_t idx = 0; idx < cells; idx++) {
        for (int k = 0; k < 3; k++) e->rgb[3 * idx + k] = rgb[3 * idx + k] * scale[k];
        e->lum[idx] = 0.2126 * e->rgb[3 * idx] + 0.7152 * e->rgb[3 * idx + 1] + 0.0722 * e->rgb[3 * idx + 2];
    }
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            e->sum[(size_t)(y + 1) * W + x + 1] = e->lum[(size_t)y * w + x] + e->sum[(size_t)y * W + x + 1] +
                                                  e->sum[(size_t)(y + 1) * W + x] - e->sum[(size_t)y * W + x];
    return 1;
}

/* Rounds of splitting every region in two (Debevec's cut) until max_regions. A region that cannot
 * split stays whole, and a region splits only while the regions after it still fit: with unsplittable
 * regions a round would otherwise make up to twice max_regions - 1. */
static int cut_regions(const env_map *e, env_region *reg, env_region *tmp, int max_regions)
{
    int count = 1;
    reg[0] = (env_region){0, 0, e->w, e->h};
    while (count < max_regions) {
        int m = 0;
        for (int k = 0; k < count; k++) {
            env_region a, b;
            int rest = count - k - 1; /* regions still to place after this one */
            if (m + 2 + rest <= max_regions && split_region(e, reg[k], &a, &b)) {
                tmp[m++] = a;
                tmp[m++] = b;
            } else {
                tmp[m++] = reg[k];
            }
        }
        if (m == count) break;
        memcpy(reg, tmp, sizeof *reg * (size_t)m);
        count = m;
    }
    return count;
}

/* The region's light; returns 0 for a dark region (its rgb integral is zero too). */
static int region_light(const env_map *e, env_region r, double rotate_y, gl_env_light *out)
{
    double rgb[3] = {0, 0, 0}, dir[3] = {0, 0, 0}, wsum = 0.0;
    for (int y = r.y0; y < r.y1; y++)
        for (int x = r.x0; x < r.x1; x++) {
            size_t idx = (size_t)y * e->w + x;
            double w = e->lum[idx], m[3];
            gl_env_direction((x + 0.5) / e->w, (y + 0.5) / e->h, rotate_y, m);
            for (int ch = 0; ch < 3; ch++) {
                rgb[ch] += e->rgb[3 * idx + ch];
                dir[ch] += m[ch] * w;
            }
            wsum += w;
        }
    if (!(wsum > 0.0)) return 0;
    double len = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    for (int ch = 0; ch < 3; ch++) {
        /* energy spread evenly over the sphere has no centroid: any direction carries it */
        out->to_light[ch] = len > 0.0 ? dir[ch] * (1.0 / len) : (ch == 1);
        out->rgb[ch] = rgb[ch];
    }
    return 1;
}

sss_result gl_env_median_cut(const double *rgb, int w, int h, const double scale[3], double rotate_y,
                             int max_lights, gl_env_light *lights, int *count, sss_error *err)
{
    *count = 0;
    if (w < 1 || h < 1 || max_lights < 1)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                             "environment median cut: map %dx%d into %d lights (each must be >= 1)", w, h,
                             max_lights);
    env_map e = {0};
    env_region *reg = calloc((size_t)max_lights, sizeof *reg), *tmp = calloc((size_t)max_lights, sizeof *tmp);
    sss_result res = SSS_OK;
    if (!reg || !tmp || !env_map_init(&e, rgb, w, h, scale)) {
        res = sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (environment lights)");
    } else {
        int regions = cut_regions(&e, reg, tmp, max_lights);
        for (int k = 0; k < regions; k++) *count += region_light(&e, reg[k], rotate_y, &lights[*count]);
    }
    free(reg);
    free(tmp);
    env_map_free(&e);
    return res;
}
