/* view/compose.c — the images the viewer builds on the CPU: the split view (a wipe between two
 * images, with a divider and each side's name) and the error map (per-pixel DSSIM in colours over a
 * fixed range, with a colour bar, its ticks and their values). The decorations are overlay_text.c's
 * quads painted into the image, so screenshots and tests see exactly what is shown. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "view/view_internal.h"

static sss_result ensure_size(sss_image *img, int width, int height, sss_error *err)
{
    if (img->pixels && img->width == width && img->height == height) return SSS_OK;
    sss_image_free(img);
    return sss_image_create(img, width, height, err);
}

static const unsigned char white[4] = {255, 255, 255, 255}, black[4] = {0, 0, 0, 255};

/* label shortened (from its end) until its box fits in width pixels; 0 when fewer than 3 characters do */
static int fit_label(const char *label, float width, char *out, size_t cap)
{
    snprintf(out, cap, "%s", label ? label : "");
    for (size_t n = strlen(out); n >= 3; out[--n] = '\0')
        if (view_text_block_width(out) <= width) return 1;
    return 0;
}

/* The divider at column cut and the two labels in their top corners (VIEW_TEXT_BLOCK_HEIGHT rows). */
static sss_result split_decoration(view_text *t, int w, int h, int cut, const char *left_label,
                                   const char *right_label, sss_error *err)
{
    const float margin = 4.0f, half = VIEW_DIVIDER_WIDTH / 2.0f;
    sss_result res = view_text_rect(t, cut - half, 0.0f, cut + half, (float)h, black, err);
    if (res == SSS_OK) res = view_text_rect(t, cut - half + 1.0f, 0.0f, cut + half - 1.0f, (float)h, white, err);
    if (h < 32) return res;
    char text[64];
    if (res == SSS_OK && fit_label(left_label, cut - half - 2.0f * margin, text, sizeof text))
        res = view_text_build(t, text, margin, margin, 1.0f, err);
    if (res == SSS_OK && fit_label(right_label, w - cut - half - 2.0f * margin, text, sizeof text))
        res = view_text_build(t, text, w - margin - view_text_block_width(text), margin, 1.0f, err);
    return res;
}

sss_result view_compose_split(const sss_image *left, const sss_image *right, double position, const char *left_label,
                              const char *right_label, double exposure, sss_image *out, sss_error *err)
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
    view_text t = {0};
    res = split_decoration(&t, w, left->height, cut, left_label, right_label, err);
    if (res == SSS_OK) view_text_paint(&t, out, exposure);
    view_text_free(&t);
    return res;
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

static void tick_labels(int width, double range, int count, int unit, view_ticks *t)
{
    t->count = count;
    for (int k = 0; k < count; k++) {
        double f = (double)k / (count - 1);
        t->x[k] = (int)lround(f * (width - 1));
        snprintf(t->label[k], sizeof t->label[k], "%g%s", f * range, unit && k == count - 1 ? " DSSIM" : "");
        float lw = view_text_block_width(t->label[k]);
        t->label_x[k] = k == 0 ? 0.0f : k == count - 1 ? (float)width - lw : (float)t->x[k] - lw / 2.0f;
    }
}

static int ticks_fit(const view_ticks *t)
{
    for (int k = 1; k < t->count; k++)
        if (t->label_x[k - 1] + view_text_block_width(t->label[k - 1]) > t->label_x[k]) return 0;
    return t->label_x[0] >= 0.0f;
}

void view_colour_bar_ticks(int width, double range, int unit, view_ticks *out)
{
    static const int counts[3] = {5, 3, 2};
    memset(out, 0, sizeof *out);
    for (int u = unit ? 1 : 0; u >= 0; u--)
        for (int i = 0; i < 3; i++) {
            tick_labels(width, range, counts[i], u, out);
            if (ticks_fit(out)) return;
        }
    tick_labels(width, range, 2, 0, out); /* too narrow for any: the ends, overlapping */
}

/* The bar's ticks over the rule and, on images tall enough, their values above them. */
static sss_result bar_ticks(view_text *t, int w, int h, double range, sss_error *err)
{
    view_ticks ticks;
    view_colour_bar_ticks(w, range, 1, &ticks);
    float rule = (float)(h - VIEW_COLOUR_BAR_HEIGHT - 1), top = rule - VIEW_TICK_HEIGHT;
    sss_result res = SSS_OK;
    int labels = h >= VIEW_TICK_LABEL_MIN_HEIGHT;
    for (int k = 0; k < ticks.count && res == SSS_OK; k++) {
        if (labels) res = view_text_build(t, ticks.label[k], ticks.label_x[k], top - VIEW_TEXT_BLOCK_HEIGHT, 1.0f, err);
        if (res == SSS_OK) res = view_text_rect(t, (float)ticks.x[k], top, ticks.x[k] + 1.0f, rule + 1.0f, white, err);
    }
    return res;
}

sss_result view_error_map(const sss_image *dssim_map, double range, sss_image *out, sss_error *err)
{
    if (!(range > 0.0) || !isfinite(range))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "error map: range %g is not > 0", range);
    int w = dssim_map->width, h = dssim_map->height;
    sss_result res = ensure_size(out, w, h, err);
    if (res != SSS_OK) return res;
    size_t n = (size_t)w * (size_t)h;
    for (size_t i = 0; i < n; i++) {
        const float *p = dssim_map->pixels + 3 * i;
        view_error_colour((p[0] + p[1] + p[2]) / 3.0 / range, out->pixels + 3 * i);
    }
    int bar = h > 4 * VIEW_COLOUR_BAR_HEIGHT ? VIEW_COLOUR_BAR_HEIGHT : 0; /* no bar on tiny images */
    if (!bar) return SSS_OK;
    for (int y = h - bar - 1; y < h; y++)
        for (int x = 0; x < w; x++) {
            float *q = out->pixels + 3 * ((size_t)y * (size_t)w + (size_t)x);
            if (y == h - bar - 1) q[0] = q[1] = q[2] = 0.0f;
            else view_error_colour(w > 1 ? (double)x / (w - 1) : 0.0, q);
        }
    view_text t = {0};
    res = bar_ticks(&t, w, h, range, err);
    if (res == SSS_OK) view_text_paint(&t, out, 0.0);
    view_text_free(&t);
    return res;
}
