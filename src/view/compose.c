/* view/compose.c — the images the viewer builds on the CPU: the split view (a wipe between two
 * images) and the error map (per-pixel DSSIM in colours with a colour bar). */
#include <math.h>
#include <string.h>

#include "view/view_internal.h"

static sss_result ensure_size(sss_image *img, int width, int height, sss_error *err)
{
    if (img->pixels && img->width == width && img->height == height) return SSS_OK;
    sss_image_free(img);
    return sss_image_create(img, width, height, err);
}

sss_result view_compose_split(const sss_image *left, const sss_image *right, double position, sss_image *out,
                              sss_error *err)
{
    if (left->width != right->width || left->height != right->height)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "split view: images of %dx%d and %dx%d", left->width,
                             left->height, right->width, right->height);
    sss_result res = ensure_size(out, left->width, left->height, err);
    if (res != SSS_OK) return res;
    int w = left->width, cut = (int)lround(position * w);
    cut = cut < 0 ? 0 : cut > w ? w : cut;
    for (int y = 0; y < left->height; y++) {
        size_t row = (size_t)y * (size_t)w * 3;
        memcpy(out->pixels + row, left->pixels + row, (size_t)cut * 3 * sizeof(float));
        memcpy(out->pixels + row + (size_t)cut * 3, right->pixels + row + (size_t)cut * 3,
               (size_t)(w - cut) * 3 * sizeof(float));
    }
    return SSS_OK;
}

void view_error_colour(double value, float rgb[3])
{
    /* inferno (matplotlib), five control points in sRGB 8-bit */
    static const double stops[5][3] = {{0, 0, 4}, {87, 16, 110}, {188, 55, 84}, {249, 142, 9}, {252, 255, 164}};
    if (isnan(value)) {
        rgb[0] = rgb[1] = rgb[2] = 0.0f;
        return;
    }
    double x = (value < 0.0 ? 0.0 : value > 1.0 ? 1.0 : value) * 4.0;
    int i = x >= 4.0 ? 3 : (int)x;
    double f = x - i;
    for (int c = 0; c < 3; c++)
        rgb[c] = (float)sss_srgb_decode(((1.0 - f) * stops[i][c] + f * stops[i + 1][c]) / 255.0);
}

/* The smallest of 1, 2, 5 x 10^k that is >= v (and >= 0.01). */
static double nice_range(double v)
{
    double r = 0.01;
    for (int k = 0; r < v && k < 40; k++) r = (k % 3 == 0 ? 2.0 : k % 3 == 1 ? 2.5 : 2.0) * r;
    return r;
}

sss_result view_error_map(const sss_image *dssim_map, sss_image *out, double *range, sss_error *err)
{
    int w = dssim_map->width, h = dssim_map->height;
    sss_result res = ensure_size(out, w, h, err);
    if (res != SSS_OK) return res;
    size_t n = (size_t)w * (size_t)h;
    double top = 0.0;
    for (size_t i = 0; i < n; i++) {
        const float *p = dssim_map->pixels + 3 * i;
        double e = (p[0] + p[1] + p[2]) / 3.0;
        if (e > top) top = e;
    }
    *range = nice_range(top);
    for (size_t i = 0; i < n; i++) {
        const float *p = dssim_map->pixels + 3 * i;
        view_error_colour((p[0] + p[1] + p[2]) / 3.0 / *range, out->pixels + 3 * i);
    }
    int bar = h > 4 * VIEW_COLOUR_BAR_HEIGHT ? VIEW_COLOUR_BAR_HEIGHT : 0; /* no bar on tiny images */
    for (int y = h - bar - 1; bar && y < h; y++)
        for (int x = 0; x < w; x++) {
            float *q = out->pixels + 3 * ((size_t)y * (size_t)w + (size_t)x);
            if (y == h - bar - 1) q[0] = q[1] = q[2] = 0.0f;
            else view_error_colour(w > 1 ? (double)x / (w - 1) : 0.0, q);
        }
    return SSS_OK;
}
