/* eval/eval_report.c — report.html: one self-contained page (PNG images as base64 data URIs, inline
 * CSS, no scripts, no external references) with the summary, the comparison sheets, the plots and
 * the tables of results.json; and sss_eval_write_all, which writes every output of a run. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/file_util.h"
#include "core/text.h"
#include "eval/eval_internal.h"

/* ---- A growing string ------------------------------------------------------------------------- */

typedef struct sbuf {
    char *data;
    size_t len, cap;
    int oom;
} sbuf;

static void sb_grow(sbuf *b, size_t extra)
{
    if (b->oom || b->len + extra + 1 <= b->cap) return;
    size_t cap = b->cap ? b->cap : 65536;
    while (cap < b->len + extra + 1) cap *= 2;
    char *d = realloc(b->data, cap);
    if (!d) {
        b->oom = 1;
        return;
    }
    b->data = d;
    b->cap = cap;
}

static void sb_put(sbuf *b, const char *s, size_t n)
{
    sb_grow(b, n);
    if (b->oom) return;
    memcpy(b->data + b->len, s, n);
    b->len += n;
    b->data[b->len] = '\0';
}

static void sb_printf(sbuf *b, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
static void sb_printf(sbuf *b, const char *fmt, ...)
{
    char tmp[2048];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(tmp, sizeof tmp, fmt, ap);
    va_end(ap);
    if (n < 0) return;
    sb_put(b, tmp, (size_t)n < sizeof tmp ? (size_t)n : sizeof tmp - 1);
}

/* HTML text (also safe inside double-quoted attributes), control characters and bytes that are not
 * UTF-8 written as visible escapes first (core/text.h): scene names come from file names. */
static void sb_esc(sbuf *b, const char *text)
{
    size_t n = strlen(text);
    char *escaped = malloc(SSS_TEXT_ESCAPE_MAX * n + 1);
    if (!escaped) {
        b->oom = 1;
        return;
    }
    sss_text_escape(text, n, escaped);
    for (const char *s = escaped; *s; s++) {
        switch (*s) {
        case '&': sb_put(b, "&amp;", 5); break;
        case '<': sb_put(b, "&lt;", 4); break;
        case '>': sb_put(b, "&gt;", 4); break;
        case '"': sb_put(b, "&quot;", 6); break;
        default: sb_put(b, s, 1);
        }
    }
    free(escaped);
}

static void sb_base64(sbuf *b, const unsigned char *d, size_t n)
{
    static const char tab[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    sb_grow(b, (n + 2) / 3 * 4);
    if (b->oom) return;
    char *o = b->data + b->len;
    size_t i = 0;
    for (; i + 2 < n; i += 3) {
        unsigned v = (unsigned)d[i] << 16 | (unsigned)d[i + 1] << 8 | d[i + 2];
        *o++ = tab[v >> 18];
        *o++ = tab[(v >> 12) & 63];
        *o++ = tab[(v >> 6) & 63];
        *o++ = tab[v & 63];
    }
    if (i < n) {
        unsigned v = (unsigned)d[i] << 16 | (i + 1 < n ? (unsigned)d[i + 1] << 8 : 0);
        *o++ = tab[v >> 18];
        *o++ = tab[(v >> 12) & 63];
        *o++ = i + 1 < n ? tab[(v >> 6) & 63] : '=';
        *o++ = '=';
    }
    b->len = (size_t)(o - b->data);
    b->data[b->len] = '\0';
}

/* <img> with the PNG file embedded, or a note when it cannot be read. */
static void sb_image(sbuf *b, const char *dir, const char *file, const char *alt)
{
    char path[2048];
    snprintf(path, sizeof path, "%s/%s", dir, file);
    char *data = NULL;
    size_t size = 0;
    if (sss_read_file(sss_outputs_current_path(path), 256u << 20, &data, &size, NULL) != SSS_OK) {
        sb_printf(b, "<p class=\"fail\">image %s is missing</p>\n", file);
        return;
    }
    sb_put(b, "<img alt=\"", 10);
    sb_esc(b, alt);
    sb_put(b, "\" src=\"data:image/png;base64,", 29);
    sb_base64(b, (const unsigned char *)data, size);
    sb_put(b, "\">\n", 3);
    free(data);
}

/* ---- Tables ----------------------------------------------------------------------------------- */

static void fmt_num(char *out, size_t cap, double v, const char *fmt, int ok)
{
    if (!ok || !isfinite(v)) snprintf(out, cap, "&ndash;");
    else snprintf(out, cap, fmt, v);
}

static void sb_puts(sbuf *b, const char *s) { sb_put(b, s, strlen(s)); }

/* The mean linear R/G/B ratios as "r / g / b" ("&ndash;" when unknown). */
static void fmt_ratio(char *out, size_t cap, const double ratio[3], int ok)
{
    char c[3][24];
    for (int i = 0; i < 3; i++) fmt_num(c[i], sizeof c[i], ratio[i], "%.2f", ok);
    if (ok) snprintf(out, cap, "%s / %s / %s", c[0], c[1], c[2]);
    else snprintf(out, cap, "&ndash;");
}

/* The cells of the scores against the single-event truth (sss_eval_desc.both_truths): DSSIM, FLIP, mean R/G/B. */
static void single_event_cells(sbuf *b, const sss_eval_entry *e)
{
    char d[32], fl[32], ratio[96];
    fmt_num(d, sizeof d, e->single_event.dssim, "%.4f", e->has_single_event);
    fmt_num(fl, sizeof fl, e->single_event.flip, "%.4f", e->has_single_event);
    fmt_ratio(ratio, sizeof ratio, e->single_event_ratio, e->has_single_event);
    sb_printf(b, "<td class=\"se\">%s</td><td class=\"se\">%s</td><td class=\"se nw\">%s</td>", d, fl, ratio);
}

/* best: bit 0 the scene's lowest DSSIM, bit 1 its lowest FLIP; two: the single-event columns too. */
static void entry_row(sbuf *b, const sss_eval_results *res, const sss_eval_entry *e, int best, int two)
{
    char d[32], fl[32], p[32], r[32], ms[96], pre[32], mem[32];
    fmt_num(d, sizeof d, e->metrics.dssim, "%.4f", e->has_metrics);
    fmt_num(fl, sizeof fl, e->metrics.flip, "%.4f", e->has_metrics);
    if (e->has_metrics && isinf(e->metrics.psnr)) snprintf(p, sizeof p, "&infin;");
    else fmt_num(p, sizeof p, e->metrics.psnr, "%.2f", e->has_metrics);
    fmt_num(r, sizeof r, e->metrics.rmse, "%.3f", e->has_metrics);
    char ratio[96];
    fmt_ratio(ratio, sizeof ratio, e->mean_ratio, e->has_metrics);
    fmt_num(ms, sizeof ms, e->total_ms, "%.1f", e->ok && !e->external);
    char note[64];
    if (eval_frames_note(res, e, note, sizeof note))
        snprintf(ms + strlen(ms), sizeof ms - strlen(ms), " <span class=\"small\">%s</span>", note + 1);
    fmt_num(pre, sizeof pre, e->precompute_ms, "%.0f", e->precompute_ms > 0);
    fmt_num(mem, sizeof mem, e->has_stats ? (e->stats.texture_bytes + e->stats.buffer_bytes) / 1048576.0 : 0, "%.1f",
            e->has_stats);
    sb_put(b, "<tr><td class=\"l\">", 18);
    sb_esc(b, e->label);
    sb_printf(b, "</td><td>%dx%d</td>", e->width, e->height);
    if (e->ok) sb_put(b, "<td class=\"ok\">ok</td>", 22);
    else {
        sb_put(b, "<td class=\"fail\">failed</td>", 28);
    }
    sb_printf(b, "<td%s>%s</td><td class=\"flip%s\">%s</td><td>%s</td><td>%s</td><td class=\"nw\">%s</td>",
              best & 1 ? " class=\"best\"" : "", d, best & 2 ? " best" : "", fl, p, r, ratio);
    if (two) single_event_cells(b, e);
    sb_printf(b, "<td>%s</td><td>%s</td><td>%s</td><td class=\"l small\">", ms, pre, mem);
    if (e->external) {
        sb_puts(b, "external image: ");
        sb_esc(b, e->file);
    } else if (e->ok) {
        for (int k = 0; k < e->pass_count; k++) sb_printf(b, "%s%s&nbsp;%.1f", k ? ", " : "", e->passes[k].name, e->passes[k].ms);
    } else {
        sb_esc(b, e->error);
    }
    sb_put(b, "</td></tr>\n", 11);
}


/* The main truth's name in column groups: "full transport", "N bounces". */
static void truth_name(const sss_eval_results *res, char *out, size_t cap)
{
    if (res->reference_bounces == 0) snprintf(out, cap, "full transport");
    else snprintf(out, cap, "%d bounce%s", res->reference_bounces, res->reference_bounces == 1 ? "" : "s");
}

/* two: the scores against both truths side by side, under a row naming each truth. */
static void table_head(sbuf *b, const sss_eval_results *res, int two)
{
    static const char *main_cols = "<th>DSSIM</th><th class=\"flip\">FLIP</th><th>PSNR dB</th><th>RMSE</th>"
                                   "<th title=\"mean linear R, G, B over the truth's\">mean R/G/B</th>";
    static const char *tail = "<th class=\"l\">passes (ms) or error</th></tr>\n";
    if (!two) {
        sb_printf(b, "<table><tr><th class=\"l\">technique</th><th>size</th><th>status</th>%s<th>ms/frame</th>"
                     "<th>set-up ms</th><th>GPU MB</th>%s", main_cols, tail);
        return;
    }
    char name[32];
    truth_name(res, name, sizeof name);
    sb_printf(b, "<table class=\"two-truths\"><tr><th class=\"l\" rowspan=\"2\">technique</th><th rowspan=\"2\">size</th>"
                 "<th rowspan=\"2\">status</th><th class=\"grp\" colspan=\"5\">vs %s</th><th class=\"grp se\" colspan=\"3\">"
                 "vs single event</th>"
                 "<th rowspan=\"2\">ms/frame</th><th rowspan=\"2\">set-up ms</th><th rowspan=\"2\">GPU MB</th>"
                 "<th class=\"l\" rowspan=\"2\">passes (ms) or error</th></tr>\n<tr>%s<th class=\"se\">DSSIM</th>"
                 "<th class=\"se\">FLIP</th><th class=\"se\">mean R/G/B</th></tr>\n",
              name, main_cols);
}

static const char *CSS =
    "body{font-family:DejaVu Sans,Helvetica,Arial,sans-serif;margin:24px;color:#222;max-width:1800px}"
    "h1{font-size:24px}h2{font-size:20px;margin-top:36px;border-bottom:1px solid #ccc}h3{font-size:16px}"
    "table{border-collapse:collapse;margin:8px 0 16px 0;font-size:13px}"
    "td,th{border:1px solid #ccc;padding:3px 8px;text-align:right;vertical-align:top}"
    "th{background:#f0f0f0}.l{text-align:left}.small{font-size:11px;max-width:560px}"
    ".ok{color:#176e1a}.fail{color:#b00000;font-weight:bold}.best{font-weight:bold;background:#e6f4e6}"
    "img{max-width:100%;height:auto;border:1px solid #ddd;margin:6px 0}"
    ".se{background:#f4f7fb}.grp{text-align:center}.nw{white-space:nowrap}.meta td{text-align:left}.note{color:#555;font-size:13px}.warn{color:#8a5300;font-size:13px}";

static double metric(const sss_eval_entry *e, int flip) { return flip ? e->metrics.flip : e->metrics.dssim; }

/* The scene's best entry for the metric at its first size, when it leads the runner-up by more than the
 * noise: twice the largest change of any technique's value between references of two seeds (the two
 * values may move opposite ways). NULL without a noise estimate or a runner-up. */
static const sss_eval_entry *best_beyond_noise(const sss_eval_results *res, int s, int flip)
{
    const sss_eval_scene *es = &res->scenes[s];
    if (!es->has_noise) return NULL;
    int w, h;
    eval_primary_size(res, s, &w, &h);
    const sss_eval_entry *best = NULL;
    double second = INFINITY;
    for (int k = 0; k < res->label_count; k++) {
        const sss_eval_entry *e = eval_find(res, s, SSS_EVAL_QUALITY, res->labels[k], w, h);
        if (!e || !e->has_metrics) continue;
        if (!best || metric(e, flip) < metric(best, flip)) {
            if (best) second = metric(best, flip);
            best = e;
        } else if (metric(e, flip) < second) second = metric(e, flip);
    }
    double noise = flip ? es->noise_flip : es->noise_dssim;
    return best && second - metric(best, flip) > 2.0 * noise ? best : NULL;
}

/* How "best" is decided, under the summary tables. */
static void noise_note(sbuf *b, const sss_eval_results *res)
{
    int any = 0;
    for (int s = 0; s < res->scene_count; s++) any |= res->scenes[s].has_noise;
    if (!any) {
        sb_puts(b, "<p class=\"note\" id=\"noise\">No best technique is marked: the run made no noise estimate "
                   "(<code>sss eval --reference-noise</code> renders the reference with a second seed; a difference "
                   "smaller than the reference's own noise ranks nothing).</p>\n");
        return;
    }
    sb_puts(b, "<p class=\"note\" id=\"noise\">Marked: a scene's lowest value where it leads the next by more "
               "than twice the scene's noise. The noise is measured: the reference is rendered again with another "
               "seed, every technique compared with both, and the largest change of its DSSIM or FLIP is the "
               "noise (per scene: ");
    for (int s = 0; s < res->scene_count; s++) {
        const sss_eval_scene *es = &res->scenes[s];
        sb_puts(b, s ? "; " : "");
        sb_esc(b, es->name);
        if (es->has_noise) sb_printf(b, " DSSIM %.2g, FLIP %.2g", es->noise_dssim, es->noise_flip);
        else sb_puts(b, " not estimated");
    }
    sb_puts(b, ").</p>\n");
}

/* DSSIM or FLIP per scene and technique at the scene's first size, the best of each scene highlighted
 * when it leads by more than the noise (best_beyond_noise); single: against the single-event truth
 * instead (sss_eval_desc.both_truths; no best: the noise is the main truth's). */
static void summary_table(sbuf *b, const sss_eval_results *res, int flip, int single)
{
    char truth[64] = "", name[32];
    truth_name(res, name, sizeof name);
    if (single || res->both_truths) /* which truth, when there are two */
        snprintf(truth, sizeof truth, " against the %s", single ? "single event" : name);
    sb_printf(b, "<h2>Summary: %s%s (lower is better)</h2>\n<table class=\"summary-%s%s\"><tr><th class=\"l\">scene</th>",
              flip ? "FLIP" : "DSSIM", truth, flip ? "flip" : "dssim", single ? "-se" : "");
    for (int k = 0; k < res->label_count; k++) {
        sb_puts(b, "<th>");
        sb_esc(b, res->labels[k]);
        sb_puts(b, "</th>");
    }
    sb_puts(b, "</tr>\n");
    for (int s = 0; s < res->scene_count; s++) {
        int w, h;
        eval_primary_size(res, s, &w, &h);
        const sss_eval_entry *best = single ? NULL : best_beyond_noise(res, s, flip);
        sb_puts(b, "<tr><td class=\"l\">");
        sb_esc(b, res->scenes[s].name);
        sb_puts(b, "</td>");
        for (int k = 0; k < res->label_count; k++) {
            const sss_eval_entry *e = eval_find(res, s, SSS_EVAL_QUALITY, res->labels[k], w, h);
            if (!e || !e->ok) {
                sb_puts(b, "<td class=\"fail\" title=\"");
                sb_esc(b, e ? e->error : "not run");
                sb_puts(b, "\">failed</td>");
            } else if (single ? !e->has_single_event : !e->has_metrics) sb_puts(b, "<td>&ndash;</td>");
            else if (single) sb_printf(b, "<td>%.4f</td>", flip ? e->single_event.flip : e->single_event.dssim);
            else sb_printf(b, "<td%s>%.4f</td>", e == best ? " class=\"best\"" : "", metric(e, flip));
        }
        sb_puts(b, "</tr>\n");
    }
    sb_puts(b, "</table>\n");
}

/* The SAM sweep produced points to plot. */
static int sam_plotted(const sss_eval_results *res)
{
    for (int i = 0; res->sam_swept && i < res->entry_count; i++)
        if (res->entries[i].kind == SSS_EVAL_SAM_SWEEP && res->entries[i].has_metrics) return 1;
    return 0;
}

/* Light between surfaces: the full-transport reference carries it, the techniques' own models do not;
 * the shared interreflection stage adds an estimate (docs/eval.md, 'Two truths'; docs/interreflection.md). */
static void between_surfaces_note(sbuf *b, const sss_eval_results *res)
{
    sb_puts(b, "<p class=\"note\" id=\"between-surfaces\"><b>Light between surfaces.</b> Part of every "
               "technique's error is light that travels from one surface to another: the floor lit by the object's "
               "glow, the object lit by the floor, a shadow filled by light from the surfaces around it. The "
               "techniques' own models compute light from the lights only; the renderer's shared "
               "<code>interreflection</code> stage (on by default, off with <code>interreflection=0</code> and "
               "<code>preset=paper</code>) adds an estimate of this light to every technique's irradiance "
               "(docs/interreflection.md). Without it this error is the same for all techniques and sits in the "
               "same places (on <code>default</code> the floor's shadow was every technique's worst window). "
               "Score against both truths to tell it apart from a technique's own error: ");
    if (res->both_truths)
        sb_puts(b, "this report does: each scene's table gives the scores against the single-event truth (light "
                   "from the lights only, what the techniques model) beside the main ones.</p>\n");
    else if (res->reference_bounces == 1)
        sb_puts(b, "this report uses the single-event truth (<code>--reference-bounces 1</code>, light from the "
                   "lights only, what the techniques model); run without it for the full transport, what a viewer "
                   "sees.</p>\n");
    else
        sb_puts(b, "this report uses the full transport (what a viewer sees); <code>sss eval "
                   "--reference-bounces 1</code> scores against the single-event truth (light from the lights only, "
                   "what the techniques model), where what remains is each technique's own error.</p>\n");
}

/* The techniques that cut a material's kernel in scene s (at its first size), once each. */
static void kernel_cut_note(sbuf *b, const sss_eval_results *res, int s)
{
    int w, h, any = 0;
    eval_primary_size(res, s, &w, &h);
    for (int k = 0; k < res->label_count; k++) {
        const sss_eval_entry *e = eval_find(res, s, SSS_EVAL_QUALITY, res->labels[k], w, h);
        if (!e || !e->warning[0]) continue;
        if (!any++)
            sb_printf(b, "<p class=\"warn\" id=\"kernel-cut-%d\"><b>Truncated kernels.</b> These techniques carry "
                         "light over a shorter distance than the material spreads half of it (the colour of the long "
                         "distances is lost; sss_gl_kernel_cut, docs/eval.md):", s);
        char line[sizeof e->warning];
        for (const char *at = e->warning; *at;) { /* one line per object */
            size_t n = strcspn(at, "\n");
            snprintf(line, sizeof line, "%.*s", (int)n, at);
            sb_puts(b, "<br>");
            sb_esc(b, e->label);
            sb_puts(b, ": ");
            sb_esc(b, line);
            at += n + (at[n] == '\n');
        }
    }
    if (any) sb_puts(b, "</p>\n");
}

/* "<br>LABEL WxH: cached|rendered, quality, bounces, seconds (path)" or why it is unavailable. */
static void reference_line(sbuf *b, const char *label, const sss_eval_reference *r)
{
    sb_printf(b, "<br>%s %dx%d: ", label, r->width, r->height);
    if (r->source == SSS_EVAL_REF_NONE) {
        sb_puts(b, "<span class=\"fail\">unavailable: ");
        sb_esc(b, r->error);
        sb_puts(b, "</span>");
        return;
    }
    sb_printf(b, "%s, %s quality, bounces %d%s, %.1f s", r->source == SSS_EVAL_REF_CACHED ? "cached" : "rendered",
              r->quality, r->bounces, r->bounces == 0 ? " (full transport)" : "", r->seconds);
    if (r->path[0]) {
        sb_puts(b, " (");
        sb_esc(b, r->path);
        sb_puts(b, ")");
    }
}

static sss_result build_report(const sss_eval_results *res, const char *dir, sbuf *b)
{
    sb_puts(b, "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>sss eval report</title>\n<style>");
    sb_puts(b, CSS);
    sb_puts(b, "</style></head><body>\n<h1>sss eval: real-time techniques against the ground truth</h1>\n");
    sb_puts(b, "<table class=\"meta\">");
    sb_printf(b, "<tr><th class=\"l\">created</th><td>%s (run time %.1f s)</td></tr>", res->created, res->seconds);
    sb_puts(b, "<tr><th class=\"l\">OpenGL</th><td>");
    if (res->gl_ok) {
        sb_esc(b, res->gl_renderer);
        sb_puts(b, " &mdash; ");
        sb_esc(b, res->gl_version);
        sb_puts(b, " (");
        sb_esc(b, res->gl_platform);
        sb_puts(b, ")");
    } else {
        sb_puts(b, "<span class=\"fail\">");
        sb_esc(b, res->gl_error[0] ? res->gl_error : "not used");
        sb_puts(b, "</span>");
    }
    sb_puts(b, "</td></tr><tr><th class=\"l\">timing</th><td>");
    sb_printf(b, "median of %d frame%s per technique after %d warm-up frame%s (not timed); ", res->frames,
              res->frames == 1 ? "" : "s", res->warmup_frames, res->warmup_frames == 1 ? "" : "s");
    if (res->frame_budget_s > 0)
        sb_printf(b, "a technique's timed frames stop after %g s (at least one), and one whose first frame took longer "
                     "is timed on that frame alone, its one-off costs (shader compilation, first uploads) included: "
                     "ms/frame shows such entries' frames; ", res->frame_budget_s);
    if (res->supersample > 1)
        sb_printf(b, "supersampled %d&times;%d (SSAA, every pass at %d&times; the size); ", res->supersample,
                  res->supersample, res->supersample);
    sb_esc(b, res->timing_method[0] ? res->timing_method : "no frames timed");
    sb_printf(b, "</td></tr><tr><th class=\"l\">reference</th><td>sss reference (CPU), %s quality, ",
              res->reference_quality == SSS_REFERENCE_DRAFT ? "draft" : "final");
    if (res->reference_bounces == 0) sb_puts(b, "full transport (bounces until converged)");
    else if (res->reference_bounces == 1) sb_puts(b, "single-event integral (bounces 1)");
    else sb_printf(b, "%d bounces", res->reference_bounces);
    if (res->both_truths) sb_puts(b, "; and beside it the single-event integral (bounces 1), the second truth");
    sb_printf(b, "%s</td></tr>", res->cached_reference ? ", cached images used where present" : "");
    sb_puts(b, "<tr><th class=\"l\">metrics</th><td>DSSIM = (1 &minus; SSIM)/2 (11&times;11 Gaussian window, "
               "&sigma; 1.5), FLIP (mean LDR-FLIP, Andersson et al. 2020, at 67 pixels per degree), PSNR and RMSE "
               "on the tone-mapped 8-bit sRGB images (docs/physics.md §5, docs/eval.md)</td></tr></table>\n");
    sb_puts(b, "<p class=\"note\" id=\"how-to-read\"><b>How to read.</b> DSSIM measures the loss of local "
               "structure (0: identical). FLIP estimates what an observer sees when flipping between the reference "
               "and the image on a 0.7&nbsp;m wide 4K monitor at 0.7&nbsp;m: per pixel in [0, 1], 0 = no visible "
               "difference; the mean is the number in the tables. Lower is better for both. On each sheet the DSSIM "
               "map (R, G, B = per-channel DSSIM) and the FLIP map (magma) carry colour bars with their scale. The "
               "zoomed crops show the reference left and the technique right, nearest-neighbour: the "
               "<span style=\"color:#d97000\">worst window</span> of a technique is the square (an eighth of the "
               "shorter side) with the largest mean FLIP; the <span style=\"color:#0090c0\">silhouette window</span> "
               "of a scene is the square holding the most pixels where the G-buffer object id of a subsurface "
               "object changes (its outline against the background, the ground or another object).");
    if (res->both_truths) {
        char name[32];
        truth_name(res, name, sizeof name);
        sb_printf(b, " <b>Two truths.</b> Each scene's table scores every entry against both, side by side: "
                     "&ldquo;vs %s&rdquo; and &ldquo;vs single event&rdquo; (light from the lights only; mean R/G/B: "
                     "the entry's mean linear red, green, blue over the truth's, 1 = as much light). For an entry "
                     "without the <code>interreflection</code> stage (<code>interreflection=0</code>, "
                     "<code>preset=paper</code>) the difference between the two scores is the part of its error "
                     "that is light between surfaces (below): the floor lit by the object's glow, a shadow filled by "
                     "the surrounding surfaces; what remains against the single event is the technique's own "
                     "error. With the stage (the default) the entry carries an estimate of that light: its score "
                     "against the full transport says how well the two together do, and the same technique with "
                     "<code>:interreflection=0</code> beside it scores its own model against the single event.", name);
    }
    sb_puts(b, "</p>\n");
    between_surfaces_note(b, res);

    for (int single = 0; single <= res->both_truths; single++) {
        summary_table(b, res, 0, single);
        summary_table(b, res, 1, single);
    }
    noise_note(b, res);

    sb_puts(b, "<h2>Plots</h2>\n");
    sb_image(b, dir, "plot_dssim.png", "DSSIM per technique and scene");
    sb_image(b, dir, "plot_flip.png", "FLIP per technique and scene");
    sb_image(b, dir, "plot_passes.png", "milliseconds per pass");
    sb_printf(b, "<p class=\"note\" id=\"frame-time\">Frame time, everywhere in this report (tables, sheets, the "
                 "labels of cut bars): the median of the %d timed frames' totals. A bar's segments are each pass's "
                 "own median, so the stack can differ from the frame time by the frames' spread.</p>\n",
              res->frames);
    if (sam_plotted(res)) sb_image(b, dir, "plot_sam_rmse.png", "SAM RMSE against back-side samples");
    else {
        sb_puts(b, "<p class=\"note\">No SAM plot (plot_sam_rmse.png is not written): ");
        sb_esc(b, !res->sam_available ? (res->sam_note[0] ? res->sam_note : "sam is not available")
                  : res->sam_swept   ? "the sweep gave no compared points (no reference)"
                                     : "the SAM sweep did not run (evaluate the sam technique or pass --sam-sweep)");
        sb_puts(b, ".</p>\n");
    }
    if (eval_resolutions_plotted(res)) sb_image(b, dir, "plot_resolution.png", "frame time against resolution, per scene");
    else
        sb_puts(b, "<p class=\"note\">No resolution plot (plot_resolution.png is not written): every technique was "
                   "timed at one size per scene, which would draw one dot per technique and no trend "
                   "(--timing-resolutions adds sizes).</p>\n");

    for (int s = 0; s < res->scene_count; s++) {
        const sss_eval_scene *es = &res->scenes[s];
        sb_puts(b, "<h2>");
        sb_esc(b, es->name);
        sb_puts(b, "</h2>\n<p class=\"note\">");
        sb_esc(b, es->path);
        sb_printf(b, ": camera %dx%d, %llu triangles", es->width, es->height, es->triangles);
        if (es->has_time) sb_printf(b, ", time %g s", es->time);
        for (int k = 0; k < es->reference_count; k++) reference_line(b, "reference", &es->references[k]);
        if (res->both_truths) reference_line(b, "single-event truth", &es->single_event_reference);
        sb_puts(b, "</p>\n");
        char file[300];
        eval_sheet_file(es, file, sizeof file);
        sb_image(b, dir, file, es->name);
        kernel_cut_note(b, res, s);
        table_head(b, res, res->both_truths);
        const sss_eval_entry *best[2] = {best_beyond_noise(res, s, 0), best_beyond_noise(res, s, 1)};
        for (int i = 0; i < res->entry_count; i++) {
            const sss_eval_entry *e = &res->entries[i];
            if (e->scene == s && e->kind != SSS_EVAL_SAM_SWEEP)
                entry_row(b, res, e, (e == best[0]) | (e == best[1]) << 1, res->both_truths);
        }
        sb_puts(b, "</table>\n");
    }

    if (res->sam_swept) { /* otherwise the Plots section said why there is no sweep */
        sb_puts(b, "<h2>SAM: RMSE against back-side samples (Maisch & Ropinski 2017, Fig. 10)</h2>\n");
        table_head(b, res, 0);
        for (int i = 0; i < res->entry_count; i++)
            if (res->entries[i].kind == SSS_EVAL_SAM_SWEEP) {
                entry_row(b, res, &res->entries[i], 0, 0);
            }
        sb_puts(b, "</table>\n");
    }

    int failures = 0;
    for (int i = 0; i < res->entry_count; i++) failures += !res->entries[i].ok;
    sb_printf(b, "<h2>Failures (%d)</h2>\n", failures);
    if (failures) {
        sb_puts(b, "<table><tr><th class=\"l\">scene</th><th class=\"l\">technique</th><th>size</th><th class=\"l\">error</th></tr>\n");
        for (int i = 0; i < res->entry_count; i++) {
            const sss_eval_entry *e = &res->entries[i];
            if (e->ok) continue;
            sb_puts(b, "<tr><td class=\"l\">");
            sb_esc(b, res->scenes[e->scene].name);
            sb_puts(b, "</td><td class=\"l\">");
            sb_esc(b, e->label);
            sb_printf(b, "</td><td>%dx%d</td><td class=\"l\">", e->width, e->height);
            sb_esc(b, e->error);
            sb_puts(b, "</td></tr>\n");
        }
        sb_puts(b, "</table>\n");
    } else sb_puts(b, "<p class=\"note\">none</p>\n");
    sb_puts(b, "<p class=\"note\">Numbers: results.json (schema docs/results.schema.json) and results.csv next to "
               "this page.</p>\n</body></html>\n");
    return b->oom ? SSS_ERROR_OUT_OF_MEMORY : SSS_OK;
}

sss_result sss_eval_write_report(const sss_eval_results *res, const char *out_dir, sss_error *err)
{
    sbuf b = {0};
    if (build_report(res, out_dir, &b) != SSS_OK) {
        free(b.data);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (report.html)");
    }
    char path[2048], tmp[4096];
    snprintf(path, sizeof path, "%s/report.html", out_dir);
    FILE *f = sss_atomic_open(path, tmp, sizeof tmp, err);
    if (!f) {
        free(b.data);
        return err ? err->code : SSS_ERROR_IO;
    }
    fwrite(b.data, 1, b.len, f);
    free(b.data);
    return sss_atomic_close(f, tmp, path, err);
}

sss_result sss_eval_write_all(const sss_eval_results *res, const char *out_dir, sss_error *err)
{
    if (!res || !out_dir) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sss_eval_write_all: bad arguments");
    sss_result r = eval_make_dirs(out_dir, err);
    char path[2048];
    if (r == SSS_OK) {
        snprintf(path, sizeof path, "%s/results.json", out_dir);
        r = sss_eval_write_json(res, path, err);
    }
    if (r == SSS_OK) {
        snprintf(path, sizeof path, "%s/results.csv", out_dir);
        r = sss_eval_write_csv(res, path, err);
    }
    for (int s = 0; r == SSS_OK && s < res->scene_count; s++) {
        char file[300];
        eval_sheet_file(&res->scenes[s], file, sizeof file);
        snprintf(path, sizeof path, "%s/%s", out_dir, file);
        r = sss_eval_write_sheet(res, s, path, err);
    }
    for (int s = 0; r == SSS_OK && s < res->scene_count; s++) {
        int w, h;
        eval_primary_size(res, s, &w, &h);
        for (int k = 0; r == SSS_OK && k < res->label_count; k++) {
            const sss_eval_entry *e = eval_find(res, s, SSS_EVAL_QUALITY, res->labels[k], w, h);
            if (!e || !e->has_metrics || !e->image.pixels) continue;
            char file[300];
            eval_crops_file(&res->scenes[s], k, file, sizeof file);
            snprintf(path, sizeof path, "%s/%s", out_dir, file);
            r = eval_write_crops(res, s, k, path, err);
        }
    }
    if (r == SSS_OK) {
        snprintf(path, sizeof path, "%s/plot_dssim.png", out_dir);
        r = sss_eval_plot_dssim(res, path, err);
    }
    if (r == SSS_OK) {
        snprintf(path, sizeof path, "%s/plot_flip.png", out_dir);
        r = sss_eval_plot_flip(res, path, err);
    }
    if (r == SSS_OK) {
        snprintf(path, sizeof path, "%s/plot_passes.png", out_dir);
        r = sss_eval_plot_passes(res, path, err);
    }
    if (r == SSS_OK && sam_plotted(res)) {
        snprintf(path, sizeof path, "%s/plot_sam_rmse.png", out_dir);
        r = sss_eval_plot_sam(res, path, err);
    }
    if (r == SSS_OK && eval_resolutions_plotted(res)) {
        snprintf(path, sizeof path, "%s/plot_resolution.png", out_dir);
        r = sss_eval_plot_resolution(res, path, err);
    }
    if (r == SSS_OK) r = sss_eval_write_report(res, out_dir, err);
    return r;
}
