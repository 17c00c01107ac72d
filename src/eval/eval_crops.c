/* eval/eval_crops.c — where the report zooms in: the worst-error window of a technique (largest mean
 * FLIP) and a silhouette window of the scene (most G-buffer coverage edges), found with summed-area
 * tables over every window position. */
#include <stdio.h>
#include <stdlib.h>

#include "eval/eval_internal.h"

int eval_crop_size(int w, int h)
{
    int s = (w < h ? w : h) / 8; /* 48 pixels at 384: a 3x zoom on the sheet */
    if (s < 12) s = 12;
    if (s > w) s = w;
    if (s > h) s = h;
    return s;
}

/* The window of side size with the largest sum of v (w x h values); ties keep the first (top-left). */
static eval_window best_window(const double *v, int w, int h, int size)
{
    eval_window best = {0, 0, size, 0};
    if (size < 1 || size > w || size > h) return best;
    /* sat[(y) (w + 1) + x] = sum of v over [0, x) x [0, y) */
    double *sat = calloc((size_t)(w + 1) * (size_t)(h + 1), sizeof *sat);
    if (!sat) return best;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            sat[(size_t)(y + 1) * (size_t)(w + 1) + (size_t)(x + 1)] =
                v[(size_t)y * (size_t)w + (size_t)x] + sat[(size_t)y * (size_t)(w + 1) + (size_t)(x + 1)] +
                sat[(size_t)(y + 1) * (size_t)(w + 1) + (size_t)x] - sat[(size_t)y * (size_t)(w + 1) + (size_t)x];
    double top = 0.0;
    for (int y = 0; y + size <= h; y++)
        for (int x = 0; x + size <= w; x++) {
            size_t y0 = (size_t)y * (size_t)(w + 1), y1 = (size_t)(y + size) * (size_t)(w + 1);
            double s = sat[y1 + (size_t)(x + size)] - sat[y0 + (size_t)(x + size)] - sat[y1 + (size_t)x] + sat[y0 + (size_t)x];
            if (s > top) {
                top = s;
                best.x = x;
                best.y = y;
                best.valid = 1;
            }
        }
    free(sat);
    return best;
}

eval_window eval_worst_window(const sss_image *flip_map, int size)
{
    eval_window none = {0, 0, size, 0};
    if (!flip_map || !flip_map->pixels) return none;
    int w = flip_map->width, h = flip_map->height;
    double *v = malloc(sizeof *v * (size_t)w * (size_t)h);
    if (!v) return none;
    for (size_t i = 0; i < (size_t)w * (size_t)h; i++) v[i] = flip_map->pixels[3 * i];
    eval_window win = best_window(v, w, h, size);
    free(v);
    return win;
}

eval_window eval_silhouette_window(const sss_image *object_ids, int w, int h, int size)
{
    eval_window none = {0, 0, size, 0};
    if (!object_ids || !object_ids->pixels || w < 1 || h < 1) return none;
    int W = object_ids->width, H = object_ids->height, k = W / w;
    if (k < 1 || W != k * w || H != k * h) return none;
    /* an output pixel counts the id changes to the right and below among its k x k samples */
    double *v = calloc((size_t)w * (size_t)h, sizeof *v);
    if (!v) return none;
    const float *id = object_ids->pixels;
    for (int Y = 0; Y < H; Y++)
        for (int X = 0; X < W; X++) {
            float c = id[((size_t)Y * (size_t)W + (size_t)X) * 3];
            int edges = (X + 1 < W && id[((size_t)Y * (size_t)W + (size_t)X + 1) * 3] != c) +
                        (Y + 1 < H && id[((size_t)(Y + 1) * (size_t)W + (size_t)X) * 3] != c);
            v[(size_t)(Y / k) * (size_t)w + (size_t)(X / k)] += edges;
        }
    eval_window win = best_window(v, w, h, size);
    free(v);
    return win;
}

void eval_crops_file(const sss_eval_scene *s, int k, char *out, size_t cap)
{
    if (s->has_time) snprintf(out, cap, "crops_%s_t%g_%d.png", s->stem, s->time, k);
    else snprintf(out, cap, "crops_%s_%d.png", s->stem, k);
}
