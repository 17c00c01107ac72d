/* eval/eval_draw.c — cairo helpers of the sheets and plots: canvases, images as surfaces, text,
 * colours, axis ticks, and writing a surface as PNG atomically through sss_image_write_png8. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "eval/eval_internal.h"

eval_rgb eval_palette(int i)
{
    /* Tableau 10: distinguishable, also in grey print */
    static const unsigned hex[10] = {0x4e79a7, 0xf28e2b, 0xe15759, 0x76b7b2, 0x59a14f,
                                     0xedc948, 0xb07aa1, 0xff9da7, 0x9c755f, 0xbab0ac};
    if (i < 0) i = -i;
    unsigned c = hex[i % 10];
    double dim = i >= 10 ? 0.65 : 1.0; /* a second round is darker */
    eval_rgb out = {dim * ((c >> 16) & 255) / 255.0, dim * ((c >> 8) & 255) / 255.0, dim * (c & 255) / 255.0};
    return out;
}

int eval_canvas(int width, int height, cairo_surface_t **s, cairo_t **cr)
{
    *s = NULL;
    *cr = NULL;
    if (width < 1 || height < 1 || width > 32767 || height > 32767) return 0;
    *s = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height);
    if (cairo_surface_status(*s) != CAIRO_STATUS_SUCCESS) {
        cairo_surface_destroy(*s);
        *s = NULL;
        return 0;
    }
    *cr = cairo_create(*s);
    if (cairo_status(*cr) != CAIRO_STATUS_SUCCESS) {
        cairo_destroy(*cr);
        cairo_surface_destroy(*s);
        *s = NULL;
        *cr = NULL;
        return 0;
    }
    cairo_set_source_rgb(*cr, 1, 1, 1);
    cairo_paint(*cr);
    return 1;
}

static cairo_surface_t *surface_from_rgb8(const uint8_t *rgb, int w, int h)
{
    cairo_surface_t *s = cairo_image_surface_create(CAIRO_FORMAT_RGB24, w, h);
    if (cairo_surface_status(s) != CAIRO_STATUS_SUCCESS) {
        cairo_surface_destroy(s);
        return NULL;
    }
    cairo_surface_flush(s);
    unsigned char *data = cairo_image_surface_get_data(s);
    int stride = cairo_image_surface_get_stride(s);
    for (int y = 0; y < h; y++) {
        uint32_t *row = (uint32_t *)(void *)(data + (size_t)y * (size_t)stride);
        const uint8_t *src = rgb + (size_t)y * (size_t)w * 3;
        for (int x = 0; x < w; x++)
            row[x] = ((uint32_t)src[3 * x] << 16) | ((uint32_t)src[3 * x + 1] << 8) | src[3 * x + 2];
    }
    cairo_surface_mark_dirty(s);
    return s;
}

cairo_surface_t *eval_surface_from_image(const sss_image *img, double exposure)
{
    if (!img || !img->pixels || img->width < 1 || img->height < 1) return NULL;
    size_t n = (size_t)img->width * (size_t)img->height * 3;
    uint8_t *rgb = malloc(n);
    if (!rgb) return NULL;
    sss_image_to_srgb8(img, exposure, rgb);
    cairo_surface_t *s = surface_from_rgb8(rgb, img->width, img->height);
    free(rgb);
    return s;
}

cairo_surface_t *eval_surface_from_map(const sss_image *map, double gain)
{
    if (!map || !map->pixels || map->width < 1 || map->height < 1) return NULL;
    size_t n = (size_t)map->width * (size_t)map->height * 3;
    uint8_t *rgb = malloc(n);
    if (!rgb) return NULL;
    for (size_t i = 0; i < n; i++) {
        double v = map->pixels[i] * gain;
        if (!(v > 0)) v = 0; /* also NaN */
        if (v > 1) v = 1;
        rgb[i] = (uint8_t)lround(255.0 * v);
    }
    cairo_surface_t *s = surface_from_rgb8(rgb, map->width, map->height);
    free(rgb);
    return s;
}

double eval_draw_surface(cairo_t *cr, cairo_surface_t *s, double x, double y, double w, double h)
{
    if (!s) {
        /* a grey box with a cross: no image */
        cairo_set_source_rgb(cr, 0.9, 0.9, 0.9);
        cairo_rectangle(cr, x, y, w, h);
        cairo_fill(cr);
        cairo_set_source_rgb(cr, 0.6, 0.6, 0.6);
        cairo_set_line_width(cr, 1);
        cairo_move_to(cr, x, y);
        cairo_line_to(cr, x + w, y + h);
        cairo_move_to(cr, x + w, y);
        cairo_line_to(cr, x, y + h);
        cairo_stroke(cr);
        return h;
    }
    int iw = cairo_image_surface_get_width(s), ih = cairo_image_surface_get_height(s);
    double sc = fmin(w / iw, h / ih);
    cairo_save(cr);
    cairo_translate(cr, x, y);
    cairo_scale(cr, sc, sc);
    cairo_set_source_surface(cr, s, 0, 0);
    cairo_pattern_set_filter(cairo_get_source(cr), sc >= 1 ? CAIRO_FILTER_NEAREST : CAIRO_FILTER_GOOD);
    cairo_rectangle(cr, 0, 0, iw, ih);
    cairo_fill(cr);
    cairo_restore(cr);
    return ih * sc;
}

static void set_font(cairo_t *cr, double size, int bold)
{
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL,
                           bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, size);
}

double eval_text_width(cairo_t *cr, double size, int bold, const char *text)
{
    set_font(cr, size, bold);
    cairo_text_extents_t ext;
    cairo_text_extents(cr, text, &ext);
    return ext.x_advance;
}

void eval_text(cairo_t *cr, double x, double y, double size, int bold, double align, const char *text)
{
    double w = eval_text_width(cr, size, bold, text);
    cairo_move_to(cr, x - align * w, y);
    cairo_show_text(cr, text);
}

sss_result eval_finish_canvas(cairo_surface_t *s, cairo_t *cr, const char *path, sss_error *err)
{
    sss_result r = cairo_status(cr) == CAIRO_STATUS_SUCCESS ? eval_write_surface(s, path, err)
                                                            : sss_error_set(err, SSS_ERROR_UNSUPPORTED, "%s: cairo: %s",
                                                                            path, cairo_status_to_string(cairo_status(cr)));
    cairo_destroy(cr);
    cairo_surface_destroy(s);
    return r;
}

sss_result eval_write_surface(cairo_surface_t *s, const char *path, sss_error *err)
{
    cairo_surface_flush(s);
    int w = cairo_image_surface_get_width(s), h = cairo_image_surface_get_height(s);
    int stride = cairo_image_surface_get_stride(s);
    const unsigned char *data = cairo_image_surface_get_data(s);
    if (!data) return sss_error_set(err, SSS_ERROR_UNSUPPORTED, "%s: drawing failed", path);
    uint8_t *rgb = malloc((size_t)w * (size_t)h * 3);
    if (!rgb) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (%s)", path);
    for (int y = 0; y < h; y++) {
        const uint32_t *row = (const uint32_t *)(const void *)(data + (size_t)y * (size_t)stride);
        uint8_t *dst = rgb + (size_t)y * (size_t)w * 3;
        for (int x = 0; x < w; x++) {
            dst[3 * x] = (uint8_t)(row[x] >> 16);
            dst[3 * x + 1] = (uint8_t)(row[x] >> 8);
            dst[3 * x + 2] = (uint8_t)row[x];
        }
    }
    sss_result r = sss_image_write_png8(path, w, h, rgb, err);
    free(rgb);
    return r;
}

void eval_ticks(double lo, double hi, int target, double *first, double *step, int *count)
{
    if (!(hi > lo)) hi = lo + 1;
    double raw = (hi - lo) / (target > 1 ? target : 1);
    double mag = pow(10.0, floor(log10(raw)));
    double f = raw / mag;
    double s = f <= 1 ? 1 : f <= 2 ? 2 : f <= 2.5 ? 2.5 : f <= 5 ? 5 : 10;
    *step = s * mag;
    *first = ceil(lo / *step - 1e-9) * *step;
    *count = (int)floor((hi - *first) / *step + 1e-9) + 1;
    if (*count < 1) *count = 1;
    if (*count > 100) *count = 100;
}

void eval_format_number(double v, double step, char *out, size_t cap)
{
    if (fabs(v) < 1e-12 * (step > 0 ? step : 1)) v = 0;
    int decimals = 0;
    if (step > 0 && step < 1) decimals = (int)ceil(-log10(step) - 1e-9);
    if (step > 0 && fmod(step * pow(10, decimals), 1.0) > 1e-6) decimals++; /* 2.5, 0.25 */
    if (decimals > 8) decimals = 8;
    if (fabs(v) >= 1e6) snprintf(out, cap, "%.3g", v);
    else snprintf(out, cap, "%.*f", decimals, v);
}

eval_rgb eval_magma(double t)
{
    /* matplotlib's magma (van der Walt & Smith 2015, CC0) at entries 0, 16, ..., 240 and 255 of its 256;
     * linear in between (the largest deviation from the full table is under 1/255) */
    static const double stops[17][3] = {
        {0.001462, 0.000466, 0.013866}, {0.039608, 0.031090, 0.133515}, {0.113094, 0.065492, 0.276784},
        {0.211718, 0.061992, 0.418647}, {0.316654, 0.071690, 0.485380}, {0.414709, 0.110431, 0.504662},
        {0.512831, 0.148179, 0.507648}, {0.613617, 0.181811, 0.498536}, {0.716387, 0.214982, 0.475290},
        {0.816914, 0.255895, 0.436461}, {0.904281, 0.319610, 0.388137}, {0.960949, 0.418323, 0.359630},
        {0.986700, 0.535582, 0.382210}, {0.996096, 0.653659, 0.446213}, {0.996898, 0.769591, 0.534892},
        {0.992440, 0.884330, 0.640099}, {0.987053, 0.991438, 0.749504}};
    if (!(t > 0)) t = 0; /* also NaN */
    if (t > 1) t = 1;
    double i = t * 255.0;
    int k = i >= 240.0 ? 15 : (int)(i / 16.0);
    double k0 = 16.0 * k, k1 = k == 15 ? 255.0 : 16.0 * (k + 1), f = (i - k0) / (k1 - k0);
    eval_rgb c = {stops[k][0] + f * (stops[k + 1][0] - stops[k][0]), stops[k][1] + f * (stops[k + 1][1] - stops[k][1]),
                  stops[k][2] + f * (stops[k + 1][2] - stops[k][2])};
    return c;
}

cairo_surface_t *eval_surface_from_flip(const sss_image *map)
{
    if (!map || !map->pixels || map->width < 1 || map->height < 1) return NULL;
    size_t n = (size_t)map->width * (size_t)map->height;
    uint8_t *rgb = malloc(n * 3);
    if (!rgb) return NULL;
    for (size_t i = 0; i < n; i++) {
        eval_rgb c = eval_magma(map->pixels[3 * i]);
        rgb[3 * i] = (uint8_t)lround(255.0 * c.r);
        rgb[3 * i + 1] = (uint8_t)lround(255.0 * c.g);
        rgb[3 * i + 2] = (uint8_t)lround(255.0 * c.b);
    }
    cairo_surface_t *s = surface_from_rgb8(rgb, map->width, map->height);
    free(rgb);
    return s;
}

void eval_draw_colour_bar(cairo_t *cr, double x, double y, double w, double h, int magma, double vmax,
                          const char *label)
{
    double lw = label ? eval_text_width(cr, 10, 1, label) + 6 : 0;
    w -= lw; /* the name goes right of the bar */
    if (label) {
        cairo_set_source_rgb(cr, 0, 0, 0);
        eval_text(cr, x + w + 6, y + h, 10, 1, 0, label);
    }
    cairo_pattern_t *p = cairo_pattern_create_linear(x, 0, x + w, 0);
    for (int i = 0; i <= 16; i++) {
        eval_rgb c = magma ? eval_magma(i / 16.0) : (eval_rgb){i / 16.0, i / 16.0, i / 16.0};
        cairo_pattern_add_color_stop_rgb(p, i / 16.0, c.r, c.g, c.b);
    }
    cairo_set_source(cr, p);
    cairo_rectangle(cr, x, y, w, h);
    cairo_fill(cr);
    cairo_pattern_destroy(p);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 1);
    cairo_rectangle(cr, x + 0.5, y + 0.5, w - 1, h);
    cairo_stroke(cr);
    char buf[32];
    int ticks = w >= 160 ? 4 : 2; /* labels of 4 ticks need the room */
    for (int i = 0; i <= ticks; i++) {
        double tx = x + w * i / ticks;
        cairo_move_to(cr, round(tx) + 0.5, y + h);
        cairo_line_to(cr, round(tx) + 0.5, y + h + 3);
        cairo_stroke(cr);
        eval_format_number(vmax * i / ticks, vmax / 4.0, buf, sizeof buf);
        eval_text(cr, tx, y + h + 13, 10, 0, i == 0 ? 0.0 : i == ticks ? 1.0 : 0.5, buf);
    }
}

void eval_draw_crop(cairo_t *cr, cairo_surface_t *s, int x, int y, int size, double bx, double by, double box)
{
    if (!s || size < 1) {
        eval_draw_surface(cr, NULL, bx, by, box, box);
        return;
    }
    double sc = box / size;
    cairo_save(cr);
    cairo_rectangle(cr, bx, by, box, box);
    cairo_clip(cr);
    cairo_translate(cr, bx, by);
    cairo_scale(cr, sc, sc);
    cairo_set_source_surface(cr, s, -x, -y);
    cairo_pattern_set_filter(cairo_get_source(cr), CAIRO_FILTER_NEAREST);
    cairo_paint(cr);
    cairo_restore(cr);
}
