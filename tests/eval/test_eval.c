/* tests/eval/test_eval.c — the evaluation module without the CLI: technique specs and size lists,
 * axis ticks, the outputs of a synthetic result set (JSON and CSV contents and escaping, bar heights
 * proportional to the plotted values, report images that decode to the PNG files), input errors of
 * sss_eval_run, and one small real run (GL + reference) in which a failing technique is kept. */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "core/file_util.h"
#include "eval/eval_internal.h"
#include "sss/eval.h"

static char tmpdir[256];

/* fontconfig (loaded by cairo for the labels) keeps process-wide caches that only FcFini frees; they
 * are not ours. LeakSanitizer reads this hook when the test runs under ASan. */
const char *__lsan_default_suppressions(void);
const char *__lsan_default_suppressions(void) { return "leak:libfontconfig.so\n"; }

static void test_specs(void)
{
    eval_spec s;
    CHECK(eval_parse_spec("maisch2020", &s, NULL) == SSS_OK && strcmp(s.name, "maisch2020") == 0 && s.param_count == 0);
    CHECK(eval_parse_spec("ssss-svd:rank=3:shadow_bias=0.5", &s, NULL) == SSS_OK);
    CHECK(strcmp(s.name, "ssss-svd") == 0 && s.param_count == 2);
    CHECK(strcmp(s.params[0].name, "rank") == 0 && s.params[0].value == 3.0);
    CHECK(strcmp(s.params[1].name, "shadow_bias") == 0 && s.params[1].value == 0.5);
    const char *bad[] = {"", ":x=1", "a:", "a:b", "a:=1", "a:b=", "a:b=x", "a:b=inf", "a:b=nan", "a b", "a:b=1:"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        sss_error err = {0};
        CHECK_MSG(sss_eval_check_spec(bad[i], &err) != SSS_OK && err.message[0], "'%s' accepted", bad[i]);
    }
}

static void test_sizes(void)
{
    sss_eval_size *v = NULL;
    int n = 0;
    CHECK(sss_eval_parse_sizes("960x540,1920x1080", &v, &n, NULL) == SSS_OK && n == 2);
    if (n == 2) CHECK(v[0].width == 960 && v[0].height == 540 && v[1].width == 1920 && v[1].height == 1080);
    free(v);
    const char *bad[] = {"", "960", "960x", "x540", "960x540,", "10x100", "100x10", "960x540x2", "20000x20", "-64x64"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        v = NULL;
        CHECK_MSG(sss_eval_parse_sizes(bad[i], &v, &n, NULL) != SSS_OK && v == NULL, "'%s' accepted", bad[i]);
    }
    char p[256];
    CHECK(sss_eval_reference_path("scenes/references", "eval_dragon", 480, 270, 0, 0, p, sizeof p) &&
          strcmp(p, "scenes/references/eval_dragon_480x270.exr") == 0);
    CHECK(sss_eval_reference_path("r", "twist", 64, 48, 1, 1.5, p, sizeof p) && strcmp(p, "r/twist_64x48_t1.5.exr") == 0);
    CHECK(!sss_eval_reference_path("r", "twist", 64, 48, 1, 1.5, p, 8));
}

/* Ticks: a 1, 2, 2.5 or 5 times a power of ten step, inside [lo, hi], covering it to within a step. */
static void test_ticks(void)
{
    uint64_t s = 12345;
    for (int it = 0; it < 2000; it++) {
        s = s * 6364136223846793005ull + 1442695040888963407ull;
        double lo = ((s >> 11) % 1000) / 10.0 - 50.0;
        double span = pow(10.0, ((s >> 30) % 1000) / 100.0 - 6.0);
        double hi = lo + span, first, step;
        int count;
        eval_ticks(lo, hi, 6, &first, &step, &count);
        double m = step / pow(10.0, floor(log10(step) + 1e-12));
        int nice = fabs(m - 1) < 1e-9 || fabs(m - 2) < 1e-9 || fabs(m - 2.5) < 1e-9 || fabs(m - 5) < 1e-9;
        int ok = nice && first >= lo - 1e-9 * span && first - lo < step * (1 + 1e-9) &&
                 first + (count - 1) * step <= hi + 1e-9 * span && hi - (first + (count - 1) * step) < step * (1 + 1e-9) &&
                 count >= 2 && count <= 13;
        CHECK_MSG(ok, "ticks of [%g, %g]: first %g step %g count %d", lo, hi, first, step, count);
        if (!ok) break;
    }
    char buf[32];
    eval_format_number(0.25, 0.25, buf, sizeof buf);
    CHECK(strcmp(buf, "0.25") == 0);
    eval_format_number(1500, 500, buf, sizeof buf);
    CHECK(strcmp(buf, "1500") == 0);
    eval_format_number(-1e-17, 0.1, buf, sizeof buf);
    CHECK(strcmp(buf, "0.0") == 0);
}

/* ---- A synthetic result set ----------------------------------------------------------------- */

static void fill_image(sss_image *img, int w, int h, double bias)
{
    sss_image_create(img, w, h, NULL);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            for (int c = 0; c < 3; c++)
                img->pixels[3 * (y * w + x) + c] = (float)(0.05 + 0.8 * x / w * (c + 1) / 3.0 + bias * ((x / 4 + y / 4) % 2));
}

static char *label_dup(const char *s)
{
    char *d = malloc(strlen(s) + 1);
    strcpy(d, s);
    return d;
}

/* 2 scenes x 3 labels; label 2 failed with an error holding a comma and a quote. DSSIM values are
 * set to 0.1 and 0.2 in scene 0 (the tallest bars) and 0.05, 0.06 in scene 1; totals to 100 and
 * 300 ms in both (stacked bars; each scene's panel has its own scale). */
static void make_results(sss_eval_results *res)
{
    memset(res, 0, sizeof *res);
    res->scene_count = 2;
    res->scenes = calloc(2, sizeof *res->scenes);
    res->label_count = 3;
    res->labels = calloc(3, sizeof *res->labels);
    res->labels[0] = label_dup("alpha");
    res->labels[1] = label_dup("beta:layers=4");
    res->labels[2] = label_dup("broken");
    res->frames = 3;
    res->gl_ok = 1;
    snprintf(res->gl_renderer, sizeof res->gl_renderer, "test <renderer> & co");
    snprintf(res->timing_method, sizeof res->timing_method, "glFinish + monotonic clock");
    snprintf(res->created, sizeof res->created, "2024-01-01T00:00:00Z");
    snprintf(res->sam_note, sizeof res->sam_note, "no technique 'sam' in this build");
    for (int s = 0; s < 2; s++) {
        sss_eval_scene *es = &res->scenes[s];
        es->path = label_dup(s ? "scenes/two.json" : "scenes/one.json");
        snprintf(es->stem, sizeof es->stem, s ? "two" : "one");
        snprintf(es->name, sizeof es->name, s ? "two@1" : "one");
        es->has_time = s;
        es->time = s;
        es->width = 40;
        es->height = 30;
        es->triangles = 1000;
        es->reference_count = 1;
        es->references[0].width = 40;
        es->references[0].height = 30;
        es->references[0].source = SSS_EVAL_REF_CACHED;
        snprintf(es->references[0].quality, 8, "final");
        fill_image(&es->reference, 40, 30, 0.0);
        for (int k = 0; k < 3; k++) {
            sss_eval_entry *e = eval_add_entry(res);
            e->scene = s;
            e->kind = SSS_EVAL_QUALITY;
            snprintf(e->label, sizeof e->label, "%s", res->labels[k]);
            snprintf(e->technique, sizeof e->technique, "%.*s", (int)strcspn(res->labels[k], ":"), res->labels[k]);
            e->width = 40;
            e->height = 30;
            if (k == 2) {
                snprintf(e->error, sizeof e->error, "unknown technique 'broken', \"really\"");
                continue;
            }
            e->ok = 1;
            e->frames = 3;
            fill_image(&e->image, 40, 30, 0.1 * (k + 1));
            sss_image_compare(&es->reference, &e->image, 0, &e->metrics, &e->dssim_map, NULL);
            double flip;
            sss_image_flip(&es->reference, &e->image, 0, SSS_FLIP_DEFAULT_PPD, &flip, &e->flip_map, NULL);
            e->has_metrics = 1;
            e->metrics.dssim = s == 0 ? (k == 0 ? 0.1 : 0.2) : (k == 0 ? 0.05 : 0.06);
            if (s == 1 && k == 0) e->metrics.psnr = INFINITY;
            /* over a black truth there is no ratio (NaN, which must reach no file); the entry's own image as
             * the single-event truth: identical, ratio 1, PSNR infinite */
            sss_image black;
            sss_image_create(&black, 40, 30, NULL); /* zero-filled */
            eval_mean_ratio(&e->image, &black, e->mean_ratio);
            sss_image_free(&black);
            if (s == 1 && k == 0) {
                e->has_single_event = 1;
                sss_image_compare(&e->image, &e->image, 0, &e->single_event, NULL, NULL);
                eval_mean_ratio(&e->image, &e->image, e->single_event_ratio);
            }
            e->pass_count = 2;
            snprintf(e->passes[0].name, 32, "gbuffer");
            snprintf(e->passes[1].name, 32, k ? "blur" : "combine");
            double total = k == 0 ? 100.0 : 300.0;
            e->passes[0].ms = 0.25 * total;
            e->passes[1].ms = 0.75 * total;
            e->total_ms = total;
            e->precompute_ms = 12.5;
            e->has_stats = 1;
            e->stats.texture_bytes = 1000;
            e->stats.buffer_bytes = 24;
            if (s == 0 && k == 0) snprintf(e->warning, sizeof e->warning, "object 0 (medium X): cut");
        }
    }
    /* the reference's seed-to-seed noise: scene 0's DSSIM lead (0.1) is beyond twice 0.02, scene 1's
     * (0.01) is not beyond twice 0.006; no FLIP lead is beyond 1 */
    res->both_truths = 1;
    res->scenes[0].has_noise = res->scenes[1].has_noise = 1;
    res->scenes[0].noise_dssim = 0.02;
    res->scenes[1].noise_dssim = 0.006;
    res->scenes[0].noise_flip = res->scenes[1].noise_flip = 1.0;
}

/* Occurrences of needle in text. */
static int occurrences(const char *text, const char *needle)
{
    int n = 0;
    for (const char *p = strstr(text, needle); p; p = strstr(p + 1, needle)) n++;
    return n;
}

/* Tallest run of pixels of exactly one colour in any column: a bar's height in pixels. */
static int bar_height(const uint8_t *rgb, int w, int h, unsigned colour)
{
    int best = 0;
    for (int x = 0; x < w; x++) {
        int n = 0;
        for (int y = 0; y < h; y++) {
            const uint8_t *p = rgb + 3 * ((size_t)y * w + x);
            n += ((unsigned)p[0] << 16 | (unsigned)p[1] << 8 | p[2]) == colour;
        }
        if (n > best) best = n;
    }
    return best;
}

/* Connected regions (4-neighbours) of pixels of exactly one colour: markers of a line plot. */
static int colour_regions(const uint8_t *rgb, int w, int h, unsigned colour)
{
    unsigned char *seen = calloc((size_t)w * h, 1);
    int *stack = malloc(sizeof(int) * (size_t)w * h), regions = 0;
#define AT(i) ((unsigned)rgb[3 * (i)] << 16 | (unsigned)rgb[3 * (i) + 1] << 8 | rgb[3 * (i) + 2])
    for (int i = 0; i < w * h; i++) {
        if (seen[i] || AT(i) != colour) continue;
        regions++;
        int top = 0;
        stack[top++] = i;
        seen[i] = 1;
        while (top > 0) {
            int p = stack[--top], x = p % w, y = p / w;
            int nb[4] = {x > 0 ? p - 1 : -1, x + 1 < w ? p + 1 : -1, y > 0 ? p - w : -1, y + 1 < h ? p + w : -1};
            for (int k = 0; k < 4; k++)
                if (nb[k] >= 0 && !seen[nb[k]] && AT(nb[k]) == colour) seen[nb[k]] = 1, stack[top++] = nb[k];
        }
    }
#undef AT
    free(seen);
    free(stack);
    return regions;
}

/* Pixels within tol of colour in every channel. */
static int colour_count(const uint8_t *rgb, int w, int h, int r, int g, int b, int tol)
{
    int n = 0;
    for (int i = 0; i < w * h; i++)
        n += abs(rgb[3 * i] - r) <= tol && abs(rgb[3 * i + 1] - g) <= tol && abs(rgb[3 * i + 2] - b) <= tol;
    return n;
}

static uint8_t *read_png8(const char *path, int *w, int *h)
{
    sss_image img = {0};
    if (sss_image_read(path, &img, NULL) != SSS_OK) return NULL;
    uint8_t *rgb = malloc((size_t)img.width * img.height * 3);
    sss_image_to_srgb8(&img, 0.0, rgb); /* the exact inverse of the PNG decoding */
    *w = img.width;
    *h = img.height;
    sss_image_free(&img);
    return rgb;
}

static int b64_value(char c)
{
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    return -1;
}

/* Decodes base64 up to the closing quote; returns the byte count. */
static size_t b64_decode(const char *s, unsigned char *out)
{
    size_t n = 0;
    unsigned v = 0;
    int bits = 0;
    for (; *s && *s != '"'; s++) {
        if (*s == '=') break;
        int d = b64_value(*s);
        if (d < 0) return 0;
        v = (v << 6) | (unsigned)d;
        bits += 6;
        if (bits >= 8) {
            bits -= 8;
            out[n++] = (unsigned char)(v >> bits);
        }
    }
    return n;
}

static void test_outputs(void)
{
    sss_eval_results res;
    make_results(&res);
    char dir[300];
    snprintf(dir, sizeof dir, "%s/out", tmpdir);
    sss_error err = {0};
    CHECK_MSG(sss_eval_write_all(&res, dir, &err) == SSS_OK, "%s", err.message);
    char path[600];

    /* JSON: every entry, the failure kept with its message, infinite PSNR as null + flag, no NaN */
    snprintf(path, sizeof path, "%s/results.json", dir);
    char *text = NULL;
    size_t size = 0;
    CHECK(sss_read_file(path, 1 << 24, &text, &size, NULL) == SSS_OK);
    cJSON *root = text ? cJSON_Parse(text) : NULL;
    CHECK(root != NULL);
    if (root) {
        const cJSON *results = cJSON_GetObjectItem(root, "results");
        CHECK(cJSON_GetArraySize(results) == 6);
        int failed = 0, inf_flag = 0, singles = 0;
        const cJSON *e;
        cJSON_ArrayForEach(e, results)
        {
            const char *status = cJSON_GetObjectItem(e, "status")->valuestring;
            if (strcmp(status, "failed") == 0) {
                failed++;
                CHECK(strcmp(cJSON_GetObjectItem(e, "error")->valuestring, "unknown technique 'broken', \"really\"") == 0);
                CHECK(cJSON_IsNull(cJSON_GetObjectItem(e, "dssim")));
            }
            if (cJSON_IsTrue(cJSON_GetObjectItem(e, "psnr_infinite"))) {
                inf_flag++;
                CHECK(cJSON_IsNull(cJSON_GetObjectItem(e, "psnr")));
            }
            const cJSON *ratio = cJSON_GetObjectItem(e, "mean_ratio"), *single = cJSON_GetObjectItem(e, "single_event");
            if (strcmp(status, "ok") == 0) /* over a black truth: no ratio */
                CHECK(cJSON_GetArraySize(ratio) == 3 && cJSON_IsNull(cJSON_GetArrayItem(ratio, 1)));
            if (cJSON_IsObject(single)) {
                singles++;
                const cJSON *r1 = cJSON_GetObjectItem(single, "mean_ratio");
                CHECK(cJSON_GetArrayItem(r1, 0)->valuedouble == 1.0 && cJSON_GetArrayItem(r1, 2)->valuedouble == 1.0);
                CHECK(cJSON_IsNull(cJSON_GetObjectItem(single, "psnr")) &&
                      cJSON_IsTrue(cJSON_GetObjectItem(single, "psnr_infinite")) &&
                      cJSON_GetObjectItem(single, "dssim")->valuedouble == 0.0);
            } else {
                CHECK(cJSON_IsNull(single));
            }
            if (strcmp(cJSON_GetObjectItem(e, "label")->valuestring, "beta:layers=4") == 0)
                CHECK(cJSON_GetObjectItem(cJSON_GetObjectItem(e, "params"), "layers")->valuedouble == 4.0);
        }
        CHECK(failed == 2 && inf_flag == 1 && singles == 1);
        CHECK(strstr(text, "nan") == NULL && strstr(text, "NaN") == NULL && strstr(text, "Infinity") == NULL);
        cJSON_Delete(root);
    }
    free(text);

    /* CSV: header + 6 rows of 34 fields; the error field quoted with doubled quotes */
    snprintf(path, sizeof path, "%s/results.csv", dir);
    CHECK(sss_read_file(path, 1 << 24, &text, &size, NULL) == SSS_OK);
    if (text) {
        int rows = 0, fields = 1, bad_rows = 0, in_quotes = 0;
        for (const char *c = text; *c; c++) {
            if (*c == '"') in_quotes = !in_quotes;
            else if (!in_quotes && *c == ',') fields++;
            else if (!in_quotes && *c == '\n') {
                bad_rows += fields != 34;
                rows++;
                fields = 1;
            }
        }
        CHECK(rows == 7 && bad_rows == 0 && !in_quotes);
        CHECK(strstr(text, "\"unknown technique 'broken', \"\"really\"\"\"") != NULL);
        free(text);
    }

    /* bars: DSSIM 0.1 and 0.2 give heights 1 : 2 (to a pixel) */
    int w, h;
    snprintf(path, sizeof path, "%s/plot_dssim.png", dir);
    uint8_t *rgb = read_png8(path, &w, &h);
    CHECK(rgb != NULL);
    if (rgb) {
        /* palette 0 and 1 (Tableau 10 blue, orange): scene 0's bars are the tallest of their colour */
        int h0 = bar_height(rgb, w, h, 0x4e79a7), h1 = bar_height(rgb, w, h, 0xf28e2b);
        CHECK_MSG(h0 > 20 && abs(h1 - 2 * h0) <= 2, "bar heights %d and %d", h0, h1);
        free(rgb);
    }
    /* stacked passes: 100 and 300 ms in ratio 1 : 3; the first pass (gbuffer, palette 0) is a quarter */
    snprintf(path, sizeof path, "%s/plot_passes.png", dir);
    rgb = read_png8(path, &w, &h);
    CHECK(rgb != NULL);
    if (rgb) {
        int g = bar_height(rgb, w, h, 0x4e79a7);  /* gbuffer of the 300 ms bar: 75 ms */
        int c = bar_height(rgb, w, h, 0xf28e2b);  /* combine of the 100 ms bar: 75 ms */
        int b = bar_height(rgb, w, h, 0xe15759);  /* blur of the 300 ms bar: 225 ms */
        CHECK_MSG(g > 20 && abs(c - g) <= 2 && abs(b - 3 * g) <= 3, "stack heights %d %d %d", g, c, b);
        free(rgb);
    }

    /* the sheet shows the reference at least at its own size, and the FLIP maps' colour bars end in
     * magma's last colour (252, 253, 191), which no FLIP map of these images reaches */
    snprintf(path, sizeof path, "%s/sheet_two_t1.png", dir);
    rgb = read_png8(path, &w, &h);
    CHECK(rgb != NULL && w > 2 * 40 && h > 30);
    if (rgb) {
        int top = colour_count(rgb, w, h, 252, 253, 191, 3);
        CHECK_MSG(top >= 2 * 8, "%d pixels of the end of the FLIP colour bars (2 bars, 8 pixels tall)", top);
    }
    free(rgb);
    /* one size per scene: no frame-time-against-resolution plot (it would be one dot per technique) */
    snprintf(path, sizeof path, "%s/plot_resolution.png", dir);
    FILE *resolution = fopen(path, "rb");
    CHECK_MSG(resolution == NULL, "%s was written with one size per scene", path);
    if (resolution) fclose(resolution);
    /* no sweep ran: no empty SAM plot */
    snprintf(path, sizeof path, "%s/plot_sam_rmse.png", dir);
    FILE *sam = fopen(path, "rb");
    CHECK_MSG(sam == NULL, "%s was written without a SAM sweep", path);
    if (sam) fclose(sam);

    /* report: each embedded image decodes to the bytes of a PNG file written next to it */
    snprintf(path, sizeof path, "%s/report.html", dir);
    CHECK(sss_read_file(path, 1 << 26, &text, &size, NULL) == SSS_OK);
    if (text) {
        /* the crops are on the sheets only (not a second time in a table) */
        const char *files[] = {"plot_dssim.png", "plot_flip.png", "plot_passes.png", "sheet_one.png", "sheet_two_t1.png"};
        int found = 0, images = 0;
        for (const char *p = strstr(text, "base64,"); p; p = strstr(p + 1, "base64,")) {
            images++;
            size_t len = strcspn(p + 7, "\"");
            unsigned char *bytes = malloc(len);
            size_t n = b64_decode(p + 7, bytes);
            for (size_t f = 0; f < sizeof files / sizeof files[0]; f++) {
                char fp[700];
                snprintf(fp, sizeof fp, "%s/%s", dir, files[f]);
                char *data = NULL;
                size_t ds = 0;
                int same = sss_read_file(fp, 1 << 26, &data, &ds, NULL) == SSS_OK && ds == n && memcmp(data, bytes, n) == 0;
                free(data);
                if (same) { /* counted once: the two scenes' crops may be the same bytes */
                    found++;
                    break;
                }
            }
            free(bytes);
        }
        CHECK_MSG(images == 5 && found == 5, "%d images, %d match files", images, found);
        /* both truths side by side in each scene's table, explained once */
        CHECK_MSG(occurrences(text, ">vs single event</th>") == 2 && occurrences(text, ">vs full transport</th>") == 2 &&
                      occurrences(text, "<b>Two truths.</b>") == 1 &&
                      occurrences(text, "<h2>Summary: DSSIM against the single event") == 1,
                  "two truths' columns: %d", occurrences(text, ">vs single event</th>"));
        /* notes once each: SAM's, how to read, light between surfaces, the frame time's definition, the
         * truncated kernel (scene 0, alpha), why there is no resolution plot */
        CHECK_MSG(occurrences(text, "no technique 'sam' in this build") == 1, "SAM note %d times",
                  occurrences(text, "no technique 'sam' in this build"));
        CHECK(occurrences(text, "id=\"how-to-read\"") == 1 && occurrences(text, "id=\"between-surfaces\"") == 1);
        CHECK(strstr(text, "every technique's error is light") != NULL && strstr(text, "both truths") != NULL);
        CHECK(occurrences(text, "id=\"frame-time\"") == 1 && strstr(text, "median of the 3 timed frames") != NULL);
        CHECK(occurrences(text, "Truncated kernels") == 1 && strstr(text, "alpha: object 0 (medium X): cut") != NULL);
        CHECK(occurrences(text, "No resolution plot") == 1);
        /* best: only scene 0's DSSIM (summary and scene table); the other leads are within the noise */
        CHECK_MSG(occurrences(text, "class=\"best\"") == 2 && occurrences(text, " best\"") == 0,
                  "%d DSSIM and %d FLIP cells marked best", occurrences(text, "class=\"best\""),
                  occurrences(text, " best\""));
        CHECK(strstr(text, "one DSSIM 0.02, FLIP 1; two@1 DSSIM 0.006") != NULL);
        CHECK(strstr(text, "test &lt;renderer&gt; &amp; co") != NULL); /* escaped */
        CHECK(strstr(text, "<script") == NULL && strstr(text, "http://") == NULL && strstr(text, "https://") == NULL);
        free(text);
    }
    sss_eval_results_free(&res);
    CHECK(res.entries == NULL && res.scene_count == 0);
    sss_eval_results_free(&res); /* twice is fine */
}

/* Frame time against resolution with two sizes per technique: one panel per scene, so technique alpha
 * (palette 0) has its line in each of the two panels, plus its legend entry. Without noise estimates
 * no best is marked, and the page says why. */
static void test_resolution_plot(void)
{
    sss_eval_results res;
    make_results(&res);
    res.scenes[0].has_noise = res.scenes[1].has_noise = 0;
    for (int s = 0; s < 2; s++)
        for (int k = 0; k < 2; k++) {
            sss_eval_entry *e = eval_add_entry(&res);
            e->scene = s;
            e->kind = SSS_EVAL_TIMING;
            snprintf(e->label, sizeof e->label, "%s", res.labels[k]);
            e->width = 80;
            e->height = 60;
            e->ok = 1;
            e->total_ms = k == 0 ? 100.0 : 300.0; /* as at 40x30: flat lines, one region each */
        }
    char dir[300], path[600];
    snprintf(dir, sizeof dir, "%s/res", tmpdir);
    sss_error err = {0};
    CHECK_MSG(sss_eval_write_all(&res, dir, &err) == SSS_OK, "%s", err.message);
    snprintf(path, sizeof path, "%s/plot_resolution.png", dir);
    int w, h;
    uint8_t *rgb = read_png8(path, &w, &h);
    CHECK(rgb != NULL);
    if (rgb) {
        int regions = colour_regions(rgb, w, h, 0x4e79a7);
        CHECK_MSG(regions == 3, "alpha's lines: %d regions (2 panels + legend expected)", regions);
        free(rgb);
    }
    snprintf(path, sizeof path, "%s/report.html", dir);
    char *text = NULL;
    size_t size = 0;
    CHECK(sss_read_file(path, 1 << 26, &text, &size, NULL) == SSS_OK);
    if (text) {
        CHECK(occurrences(text, "class=\"best\"") == 0 && strstr(text, "No best technique is marked") != NULL);
        CHECK(strstr(text, "No resolution plot") == NULL);
        free(text);
    }
    sss_eval_results_free(&res);
}

static void test_run_errors(void)
{
    sss_eval_results res;
    sss_error err = {0};
    const char *missing[] = {"/nonexistent/scene.json"};
    CHECK(sss_eval_run(missing, 1, NULL, NULL, &res, &err) != SSS_OK && strstr(err.message, "/nonexistent/scene.json"));
    CHECK(res.entries == NULL && res.scenes == NULL);
    CHECK(sss_eval_run(missing, 0, NULL, NULL, &res, &err) != SSS_OK);
    sss_eval_desc d;
    memset(&d, 0, sizeof d);
    d.frames = -1;
    CHECK(sss_eval_run(missing, 1, &d, NULL, &res, &err) == SSS_ERROR_INVALID_ARGUMENT);
    d.frames = 1;
    const char *specs[] = {"local:oops"};
    d.techniques = specs;
    d.technique_count = 1;
    CHECK(sss_eval_run(missing, 1, &d, NULL, &res, &err) == SSS_ERROR_INVALID_ARGUMENT && strstr(err.message, "local:oops"));
}

typedef struct cb_log {
    int progress_calls, bad_fraction, notes;
    double last;
} cb_log;

static void on_progress(void *user, double f, const char *stage)
{
    cb_log *l = user;
    l->progress_calls++;
    if (!(f >= 0 && f <= 1) || !stage) l->bad_fraction++;
    l->last = f;
}

static void on_note(void *user, const char *msg)
{
    cb_log *l = user;
    l->notes += msg && msg[0];
}

/* A real run: a small procedural scene, draft reference, "local" plus a technique that does not
 * exist and one whose parameter is out of range; a timing-only size; the cached path with a missing
 * cache (a note) and the reference saved for the next run, which then reads it. */
static void test_run(void)
{
    char scene[400];
    snprintf(scene, sizeof scene, "%s/ball.json", tmpdir);
    FILE *f = fopen(scene, "w");
    fputs("{\"camera\": {\"position\": [0, 1.2, 4], \"look_at\": [0, 0.4, 0], \"fov\": 35, \"width\": 32, \"height\": 24},\n"
          " \"objects\": [{\"procedural\": {\"shape\": \"sphere\", \"radius\": 0.6, \"subdivisions\": 2},\n"
          "   \"transform\": {\"translate\": [0, 0.6, 0]},\n"
          "   \"material\": {\"type\": \"subsurface\", \"medium\": \"Marble\", \"scale\": 20.0}}],\n"
          " \"lights\": [{\"type\": \"point\", \"position\": [1.5, 3, 1.5], \"intensity\": [6, 6, 6]}]}\n",
          f);
    fclose(f);
    char scene_t[420];
    snprintf(scene_t, sizeof scene_t, "%s@0.25", scene);
    const char *scenes[] = {scene_t};
    const char *specs[] = {"local", "nosuch", "local:shadow_size=1"};
    sss_eval_size timing = {40, 40};
    char refs[400];
    snprintf(refs, sizeof refs, "%s/refs", tmpdir);
    sss_eval_desc d;
    memset(&d, 0, sizeof d);
    d.techniques = specs;
    d.technique_count = 3;
    d.frames = 2;
    d.timing_resolutions = &timing;
    d.timing_resolution_count = 1;
    d.reference_quality = SSS_REFERENCE_DRAFT;
    d.cached_reference = 1;
    d.reference_dir = refs;
    d.save_references_dir = refs;
    cb_log log = {0};
    sss_eval_callbacks cb = {on_progress, on_note, &log};
    sss_eval_results res;
    sss_error err = {0};
    CHECK_MSG(sss_eval_run(scenes, 1, &d, &cb, &res, &err) == SSS_OK, "%s", err.message);
    if (res.scene_count != 1) return;
    CHECK(res.scenes[0].has_time && res.scenes[0].time == 0.25 && strcmp(res.scenes[0].name, "ball@0.25") == 0);
    CHECK(res.entry_count == 6); /* 3 quality + 3 timing: nothing dropped */
    CHECK(res.frames == 2 && res.warmup_frames == SSS_GL_WARMUP_FRAMES); /* warm-up on by default */
    CHECK(log.progress_calls > 3 && log.bad_fraction == 0 && fabs(log.last - 1.0) < 1e-12);
    CHECK(log.notes >= 1); /* "no cached reference ..." */
    CHECK(res.scenes[0].references[0].source == SSS_EVAL_REF_RENDERED);
    if (res.gl_ok) {
        for (int i = 0; i < res.entry_count; i++) {
            const sss_eval_entry *e = &res.entries[i];
            int should = strcmp(e->label, "local") == 0;
            CHECK_MSG(e->ok == should, "%s: ok %d (%s)", e->label, e->ok, e->error);
            if (!e->ok) CHECK(e->error[0] != '\0');
            if (e->ok && e->kind == SSS_EVAL_QUALITY) {
                CHECK(e->has_metrics && e->metrics.dssim > 0 && e->metrics.dssim < 1 && isfinite(e->metrics.rmse));
                CHECK(e->image.width == 32 && e->dssim_map.height == 24 && e->frames == 2 && e->total_ms > 0);
            }
            if (e->ok && e->kind == SSS_EVAL_TIMING) CHECK(e->width == 40 && !e->has_metrics && !e->image.pixels);
        }
    } else {
        fprintf(stderr, "note: no GL context (%s): technique checks limited\n", res.gl_error);
        for (int i = 0; i < res.entry_count; i++) CHECK(!res.entries[i].ok && res.entries[i].error[0]);
    }
    double dssim0 = res.entry_count ? res.entries[0].metrics.dssim : 0;
    sss_eval_results_free(&res);
    char saved[600];
    snprintf(saved, sizeof saved, "%s/ball_32x24_t0.25.exr", refs);
    CHECK(access(saved, R_OK) == 0);

    /* again: the saved reference is read, and the numbers stay (half-float rounding aside) */
    d.technique_count = 1;
    d.timing_resolution_count = 0;
    d.save_references_dir = NULL;
    memset(&log, 0, sizeof log);
    CHECK(sss_eval_run(scenes, 1, &d, &cb, &res, &err) == SSS_OK);
    if (res.scene_count == 1) {
        CHECK(res.scenes[0].references[0].source == SSS_EVAL_REF_CACHED && strcmp(res.scenes[0].references[0].quality, "draft") == 0);
        CHECK(log.notes == 0);
        if (res.gl_ok && res.entry_count == 1) CHECK_NEAR(res.entries[0].metrics.dssim, dssim0, 2e-3);
    }
    sss_eval_results_free(&res);
}

/* The zoomed crops' windows on maps built here: the worst window is the one holding a hot square
 * (placed off the grid of any window step), the silhouette window the one holding the most edges of
 * a disc's outline; both are brute-force checked against every other window position. */
static void test_crop_windows(void)
{
    enum { W = 40, H = 30, SIZE = 8 };
    CHECK(eval_crop_size(384, 384) == 48 && eval_crop_size(64, 40) == 12 && eval_crop_size(10, 30) == 10);
    float flip[W * H * 3] = {0};
    sss_image map = {.width = W, .height = H, .pixels = flip};
    for (int y = 13; y < 13 + SIZE; y++) /* a square of FLIP 0.9 at (27, 13), faint noise elsewhere */
        for (int x = 27; x < 27 + SIZE; x++) flip[3 * (y * W + x)] = 0.9f;
    for (int i = 0; i < W * H; i += 7) flip[3 * i] += 0.01f;
    eval_window worst = eval_worst_window(&map, SIZE);
    CHECK_MSG(worst.valid && worst.x == 27 && worst.y == 13 && worst.size == SIZE, "worst window (%d, %d) valid %d",
              worst.x, worst.y, worst.valid);
    float zero[W * H * 3] = {0};
    sss_image flat = {.width = W, .height = H, .pixels = zero};
    CHECK(!eval_worst_window(&flat, SIZE).valid); /* no error anywhere: no worst window */

    /* object ids at 2x the 40 x 30 output: a disc of id 1 (radius 10 output pixels) centred at (28, 15) */
    float ids[2 * W * 2 * H * 3] = {0};
    sss_image id_image = {.width = 2 * W, .height = 2 * H, .pixels = ids};
    for (int Y = 0; Y < 2 * H; Y++)
        for (int X = 0; X < 2 * W; X++) {
            double dx = (X + 0.5) / 2 - 28, dy = (Y + 0.5) / 2 - 15;
            ids[3 * (Y * 2 * W + X)] = dx * dx + dy * dy < 100 ? 1.0f : 0.0f;
        }
    eval_window sil = eval_silhouette_window(&id_image, W, H, SIZE);
    CHECK(sil.valid);
    /* brute force: the edge count of every window; the chosen one has the largest */
    int best = -1, chosen = -1;
    for (int y = 0; y + SIZE <= H; y++)
        for (int x = 0; x + SIZE <= W; x++) {
            int edges = 0;
            for (int Y = 2 * y; Y < 2 * (y + SIZE); Y++)
                for (int X = 2 * x; X < 2 * (x + SIZE); X++) {
                    float c = ids[3 * (Y * 2 * W + X)];
                    edges += (X + 1 < 2 * W && ids[3 * (Y * 2 * W + X + 1)] != c) +
                             (Y + 1 < 2 * H && ids[3 * ((Y + 1) * 2 * W + X)] != c);
                }
            if (edges > best) best = edges;
            if (x == sil.x && y == sil.y) chosen = edges;
        }
    CHECK_MSG(best > 0 && chosen == best, "silhouette window (%d, %d): %d edges, the most is %d", sil.x, sil.y, chosen,
              best);
    memset(ids, 0, sizeof ids); /* one object everywhere: no silhouette */
    CHECK(!eval_silhouette_window(&id_image, W, H, SIZE).valid);
    CHECK(!eval_silhouette_window(&id_image, W + 1, H, SIZE).valid); /* ids not a multiple of the output */
}

/* --frame-budget: under a budget no frame can meet, a technique renders one frame, timed, without
 * warm-up (its entry says so); under one every frame meets, it renders all it was asked for. Runs on
 * the reference test_run saved. */
static void test_frame_budget(void)
{
    char scene_t[420], refs[400];
    snprintf(scene_t, sizeof scene_t, "%s/ball.json@0.25", tmpdir);
    snprintf(refs, sizeof refs, "%s/refs", tmpdir);
    const char *scenes[] = {scene_t};
    const char *specs[] = {"local"};
    static const double budgets[] = {1e-9, 1e5};
    for (int k = 0; k < 2; k++) {
        sss_eval_desc d;
        memset(&d, 0, sizeof d);
        d.techniques = specs;
        d.technique_count = 1;
        d.frames = 3;
        d.warmup_frames = 2;
        d.frame_budget_s = budgets[k];
        d.reference_quality = SSS_REFERENCE_DRAFT;
        d.cached_reference = 1;
        d.reference_dir = refs;
        sss_eval_results res;
        sss_error err = {0};
        CHECK_MSG(sss_eval_run(scenes, 1, &d, NULL, &res, &err) == SSS_OK, "%s", err.message);
        CHECK(res.frame_budget_s == budgets[k] && res.frames == 3 && res.warmup_frames == 2);
        if (res.gl_ok && res.entry_count == 1) {
            const sss_eval_entry *e = &res.entries[0];
            CHECK_MSG(e->ok, "%s", e->error);
            if (k == 0) CHECK_MSG(e->frames == 1 && e->warmup_frames == 0, "frames %d, warm-up %d", e->frames, e->warmup_frames);
            else CHECK_MSG(e->frames == 3 && e->warmup_frames == 2, "frames %d, warm-up %d", e->frames, e->warmup_frames);
            CHECK(e->total_ms > 0 && e->has_metrics);
        }
        sss_eval_results_free(&res);
    }
    sss_eval_desc bad;
    memset(&bad, 0, sizeof bad);
    bad.frame_budget_s = -1;
    sss_eval_results res;
    sss_error err = {0};
    CHECK(sss_eval_run(scenes, 1, &bad, NULL, &res, &err) == SSS_ERROR_INVALID_ARGUMENT && strstr(err.message, "frame_budget"));
}

int main(void)
{
    snprintf(tmpdir, sizeof tmpdir, "/tmp/sss_test_eval_XXXXXX");
    if (!mkdtemp(tmpdir)) return 1;
    test_specs();
    test_sizes();
    test_ticks();
    test_outputs();
    test_resolution_plot();
    test_crop_windows();
    test_run_errors();
    test_run();
    test_frame_budget();
    char cmd[400];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmpdir);
    if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", tmpdir);
    return CHECK_DONE();
}
