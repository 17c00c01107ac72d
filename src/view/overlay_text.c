/* view/overlay_text.c — the overlay's text as quads on the CPU with stb_easy_font (a bitmap font made
 * of rectangles: no texture, 6 x 12 pixels per character), behind them one darkened rectangle so the
 * text stays readable on any image. Drawn by view_gl.c with a tiny shader, or painted into an image
 * (the split view's labels and divider, the error map's ticks: compose.c). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wconversion"
#endif
#include <stb/stb_easy_font.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

#include "view/view_internal.h"

#define LINE_HEIGHT 12.0f
#define PAD 4.0f

static sss_result reserve(view_text *t, int quads, sss_error *err)
{
    if (t->quads + quads <= t->capacity) return SSS_OK;
    int cap = t->capacity ? t->capacity : 256;
    while (cap < t->quads + quads) cap *= 2;
    view_text_vertex *v = realloc(t->vertices, sizeof *v * 4 * (size_t)cap);
    if (!v) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (overlay text)");
    t->vertices = v;
    t->capacity = cap;
    return SSS_OK;
}

static void put_quad(view_text *t, float x0, float y0, float x1, float y1, const unsigned char rgba[4])
{
    view_text_vertex *v = &t->vertices[4 * t->quads++];
    float xs[4] = {x0, x1, x1, x0}, ys[4] = {y0, y0, y1, y1};
    for (int j = 0; j < 4; j++) {
        v[j].x = xs[j];
        v[j].y = ys[j];
        memcpy(v[j].rgba, rgba, 4);
    }
}

sss_result view_text_build(view_text *t, const char *text, float x, float y, float scale, sss_error *err)
{
    if (!text) text = "";
    size_t n = strlen(text);
    /* stb_easy_font indexes its tables with (c - 32) and (c - 31): keep to printable ASCII. */
    char *clean = malloc(n + 1);
    if (!clean) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (overlay text)");
    for (size_t i = 0; i < n; i++) {
        unsigned char c = (unsigned char)text[i];
        clean[i] = c == '\n' || (c >= 32 && c <= 126) ? (char)c : '?';
    }
    clean[n] = '\0';
    int lines = 1;
    for (size_t i = 0; i < n; i++) lines += clean[i] == '\n';
    float w = (float)stb_easy_font_width(clean), h = LINE_HEIGHT * (float)lines;
    /* At most 64 bytes per quad and far fewer than 16 quads per character. */
    int buf_size = (int)(n + 1) * 16 * 64;
    char *buf = malloc((size_t)buf_size);
    sss_result res = buf ? SSS_OK : sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (overlay text)");
    int quads = 0;
    if (res == SSS_OK) quads = stb_easy_font_print(0.0f, 0.0f, clean, NULL, buf, buf_size);
    if (res == SSS_OK) res = reserve(t, quads + 1, err);
    if (res == SSS_OK) {
        static const unsigned char shade[4] = {0, 0, 0, 160}, ink[4] = {255, 255, 255, 255};
        put_quad(t, x, y, x + (w + 2.0f * PAD) * scale, y + (h + 2.0f * PAD) * scale, shade);
        for (int q = 0; q < quads; q++) {
            const char *v = buf + 64 * q;
            float p[4][2];
            for (int j = 0; j < 4; j++) memcpy(p[j], v + 16 * j, 2 * sizeof(float));
            /* stb's vertices run (x0,y0) (x1,y0) (x1,y1) (x0,y1) */
            put_quad(t, x + (p[0][0] + PAD) * scale, y + (p[0][1] + PAD) * scale, x + (p[2][0] + PAD) * scale,
                     y + (p[2][1] + PAD) * scale, ink);
        }
        if (w + 2.0f * PAD > t->width) t->width = w + 2.0f * PAD;
        t->height += h + 2.0f * PAD;
    }
    free(buf);
    free(clean);
    return res;
}

float view_text_block_width(const char *text)
{
    char *clean = view_dup_str(text);
    if (!clean) return 0.0f;
    for (char *c = clean; *c; c++)
        if ((unsigned char)*c < 32 || (unsigned char)*c > 126) *c = '?';
    float w = (float)stb_easy_font_width(clean) + 2.0f * PAD;
    free(clean);
    return w;
}

sss_result view_text_rect(view_text *t, float x0, float y0, float x1, float y1, const unsigned char rgba[4],
                          sss_error *err)
{
    sss_result res = reserve(t, 1, err);
    if (res == SSS_OK) put_quad(t, x0, y0, x1, y1, rgba);
    return res;
}

/* The pixels whose centres lie in [a, b), clipped to [0, n). */
static void covered(float a, float b, int n, int *first, int *end)
{
    double f = ceil((double)a - 0.5), e = ceil((double)b - 0.5);
    *first = f < 0.0 ? 0 : f > n ? n : (int)f;
    *end = e < 0.0 ? 0 : e > n ? n : (int)e;
}

void view_text_paint(const view_text *t, sss_image *img, double exposure)
{
    double unit = exp2(-exposure); /* linear value that the tone map shows as 1 */
    for (int q = 0; q < t->quads; q++) {
        const view_text_vertex *v = &t->vertices[4 * q];
        int x0, x1, y0, y1;
        covered(fminf(v[0].x, v[2].x), fmaxf(v[0].x, v[2].x), img->width, &x0, &x1);
        covered(fminf(v[0].y, v[2].y), fmaxf(v[0].y, v[2].y), img->height, &y0, &y1);
        float a = v[0].rgba[3] / 255.0f, c[3];
        for (int k = 0; k < 3; k++) c[k] = (float)(sss_srgb_decode(v[0].rgba[k] / 255.0) * unit);
        for (int y = y0; y < y1; y++)
            for (int x = x0; x < x1; x++) {
                float *p = img->pixels + 3 * ((size_t)y * (size_t)img->width + (size_t)x);
                for (int k = 0; k < 3; k++) p[k] = (1.0f - a) * p[k] + a * c[k];
            }
    }
}

void view_text_free(view_text *t)
{
    free(t->vertices);
    memset(t, 0, sizeof *t);
}
