/* eval/eval_sheet.c — the comparison sheet of one scene, after Maisch & Ropinski 2020, Fig. 7: the reference
 * with the legend on top; then one row per technique: its image, its per-pixel DSSIM map (R, G, B = the
 * DSSIM of each channel, black = no difference) and FLIP map (magma), each with a colour bar, a caption
 * with label, DSSIM, FLIP and milliseconds, and zoomed crops (reference beside technique) of its
 * worst-FLIP window and of the scene's silhouette window (eval_crops.c). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "eval/eval_internal.h"

/* DSSIM maps are shown with this gain: a per-pixel DSSIM of 1 / MAP_GAIN or more is white. */
#define MAP_GAIN 5.0
#define MARGIN 16.0
#define HEADER 58.0
#define GAP 6.0
#define CAPTION 38.0
#define BAR 24.0 /* colour bar and its labels under a map */
#define WORST_RGB 1.0, 0.55, 0.0
#define SILHOUETTE_RGB 0.0, 0.75, 0.95

/* Shortens text with "..." until it fits width. */
static void fit_text(cairo_t *cr, double size, int bold, const char *text, double width, char *out, size_t cap)
{
    snprintf(out, cap, "%s", text);
    size_t n = strlen(out);
    while (n > 3 && eval_text_width(cr, size, bold, out) > width) {
        n--;
        out[n - 3] = '.';
        out[n - 2] = '.';
        out[n - 1] = '.';
        out[n] = '\0';
    }
}

static const char *source_name(const sss_eval_reference *r)
{
    switch (r->source) {
    case SSS_EVAL_REF_CACHED: return "cached";
    case SSS_EVAL_REF_RENDERED: return "rendered";
    default: return "unavailable";
    }
}

/* The outline of window win (in image pixels) on an image drawn at (x, y) with scale sc. */
static void outline_window(cairo_t *cr, eval_window win, double x, double y, double sc, double r, double g, double b)
{
    if (!win.valid) return;
    cairo_set_source_rgb(cr, r, g, b);
    cairo_set_line_width(cr, 2);
    cairo_rectangle(cr, x + win.x * sc, y + win.y * sc, win.size * sc, win.size * sc);
    cairo_stroke(cr);
}

/* Reference crop and technique crop of win side by side in boxes of side box, framed in the window's
 * colour, with a caption under them. */
static void crop_pair(cairo_t *cr, cairo_surface_t *ref, cairo_surface_t *img, eval_window win, double x, double y,
                      double box, const char *what, double r, double g, double b)
{
    char buf[160];
    if (!win.valid) {
        eval_draw_surface(cr, NULL, x, y, 2 * box + GAP, box);
        cairo_set_source_rgb(cr, 0.3, 0.3, 0.3);
        snprintf(buf, sizeof buf, "%s: no window", what);
        char fit[160];
        fit_text(cr, 11, 0, buf, 2 * box + GAP, fit, sizeof fit);
        eval_text(cr, x, y + box + 14, 11, 0, 0, fit);
        return;
    }
    eval_draw_crop(cr, ref, win.x, win.y, win.size, x, y, box);
    eval_draw_crop(cr, img, win.x, win.y, win.size, x + box + GAP, y, box);
    cairo_set_source_rgb(cr, r, g, b);
    cairo_set_line_width(cr, 3);
    cairo_rectangle(cr, x - 1.5, y - 1.5, 2 * box + GAP + 3, box + 3);
    cairo_stroke(cr);
    /* two short lines within the pair's width: side by side, pairs' captions must not run into each other */
    char fit[160];
    cairo_set_source_rgb(cr, 0, 0, 0);
    snprintf(buf, sizeof buf, "%s at (%d, %d), %d px", what, win.x, win.y, win.size);
    fit_text(cr, 11, 0, buf, 2 * box + GAP, fit, sizeof fit);
    eval_text(cr, x, y + box + 14, 11, 0, 0, fit);
    eval_text(cr, x + box / 2, y + box + 28, 11, 0, 0.5, "reference");
    eval_text(cr, x + box + GAP + box / 2, y + box + 28, 11, 0, 0.5, "technique");
}

static void caption(cairo_t *cr, const sss_eval_results *res, const sss_eval_entry *e, const char *label, double x,
                    double y, double width)
{
    char buf[600], fit[600];
    cairo_set_source_rgb(cr, 0, 0, 0);
    fit_text(cr, 13, 1, label, width, fit, sizeof fit);
    eval_text(cr, x, y + 14, 13, 1, 0, fit);
    if (!e || !e->ok) {
        cairo_set_source_rgb(cr, 0.8, 0, 0);
        snprintf(buf, sizeof buf, "FAILED: %s", e ? e->error : "not run");
    } else if (e->has_metrics) {
        char psnr[32];
        if (isfinite(e->metrics.psnr)) snprintf(psnr, sizeof psnr, "%.1f dB", e->metrics.psnr);
        else snprintf(psnr, sizeof psnr, "inf");
        char ms[96], note[64];
        eval_frames_note(res, e, note, sizeof note);
        if (e->external) snprintf(ms, sizeof ms, "external");
        else snprintf(ms, sizeof ms, "%.1f ms%s", e->total_ms, note);
        snprintf(buf, sizeof buf, "DSSIM %.4f   FLIP %.4f   PSNR %s   %s", e->metrics.dssim, e->metrics.flip, psnr, ms);
    } else {
        snprintf(buf, sizeof buf, "no reference   %.1f ms", e->total_ms);
    }
    fit_text(cr, 11.5, 0, buf, width, fit, sizeof fit);
    eval_text(cr, x, y + 30, 11.5, 0, 0, fit);
}

sss_result sss_eval_write_sheet(const sss_eval_results *res, int scene, const char *path, sss_error *err)
{
    if (!res || scene < 0 || scene >= res->scene_count)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sheet: no scene %d", scene);
    const sss_eval_scene *es = &res->scenes[scene];
    int w, h;
    eval_primary_size(res, scene, &w, &h);
    double st = fmin(220.0 / w, 170.0 / h), sr = fmin(440.0 / w, 330.0 / h);
    double tw = floor(w * st), th = floor(h * st), rw = floor(w * sr), rh = floor(h * sr);
    double box = fmin(th, 150.0); /* crop boxes */
    int n = res->label_count, crop = eval_crop_size(w, h);
    eval_window sil = eval_silhouette_window(&es->object_ids, w, h, crop);
    double row_w = 3 * tw + 2 * GAP + 24 + 2 * (2 * box + GAP) + 24, row_h = th + BAR + CAPTION + 18;
    int W = (int)(2 * MARGIN + fmax(row_w, rw + 24 + 560));
    int H = (int)(HEADER + rh + 30 + n * row_h + MARGIN);
    cairo_surface_t *s;
    cairo_t *cr;
    if (!eval_canvas(W, H, &s, &cr)) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: cannot draw", path);

    char buf[600], fit[600];
    const sss_eval_reference *ref = es->reference_count > 0 ? &es->references[0] : NULL;
    cairo_set_source_rgb(cr, 0, 0, 0);
    snprintf(buf, sizeof buf, "%s  (%dx%d%s)", es->name, w, h, es->has_time ? ", animated" : "");
    eval_text(cr, MARGIN, 26, 18, 1, 0, buf);
    if (ref) {
        char tbuf[48] = "";
        if (es->has_time) snprintf(tbuf, sizeof tbuf, ", time %g s", es->time);
        if (ref->source == SSS_EVAL_REF_NONE) snprintf(buf, sizeof buf, "reference unavailable: %s", ref->error);
        else
            snprintf(buf, sizeof buf, "reference: sss reference, %s quality, %s (%.1f s)%s", ref->quality,
                     source_name(ref), ref->seconds, tbuf);
        fit_text(cr, 12, 0, buf, W - 2 * MARGIN, fit, sizeof fit);
        eval_text(cr, MARGIN, 46, 12, 0, 0, fit);
    }

    /* the reference with the silhouette window, and the legend beside it */
    double y0 = HEADER;
    cairo_surface_t *rs = eval_surface_from_image(&es->reference, es->exposure);
    eval_draw_surface(cr, rs, MARGIN, y0, rw, rh);
    outline_window(cr, sil, MARGIN, y0, sr, SILHOUETTE_RGB);
    double lx = MARGIN + rw + 24, ly = y0 + 14;
    cairo_set_source_rgb(cr, 0, 0, 0);
    eval_text(cr, lx, ly, 14, 1, 0, "Reference (CPU ground truth)");
    const char *legend[] = {
        "Each row: the technique; its DSSIM map (R, G, B = DSSIM of each channel; the bar is",
        "the scale of one channel, white >= 0.2); its FLIP map (LDR-FLIP, Andersson et al. 2020,",
        "at 67 pixels per degree; magma, 0 = no visible difference, 1 = largest); zoomed crops.",
        "Crops (nearest-neighbour zoom, reference left, technique right):",
        "  orange: the window with the largest mean FLIP of that technique (its worst error);",
        "  cyan: the window with the most silhouette pixels of the subsurface objects (where the",
        "  G-buffer object id changes, against background, ground or each other), same in every row.",
    };
    cairo_set_source_rgb(cr, 0.25, 0.25, 0.25);
    for (size_t i = 0; i < sizeof legend / sizeof legend[0]; i++) eval_text(cr, lx, ly + 22 + 16 * i, 11.5, 0, 0, legend[i]);
    snprintf(buf, sizeof buf, "Windows are %dx%d pixels (an eighth of the shorter side)%s.", crop, crop,
             sil.valid ? "" : "; no silhouette window: no G-buffer object ids or no subsurface edges");
    eval_text(cr, lx, ly + 22 + 16 * 7, 11.5, 0, 0, buf);
    snprintf(buf, sizeof buf, "ms: median total frame time of %d frame%s after %d warm-up%s; %s", res->frames,
             res->frames == 1 ? "" : "s", res->warmup_frames,
             res->frame_budget_s > 0 ? " (fewer where marked: --frame-budget)" : "",
             res->timing_method[0] ? res->timing_method : "");
    eval_text(cr, lx, ly + 22 + 16 * 8, 11.5, 0, 0, buf);

    /* one row per technique */
    for (int k = 0; k < n; k++) {
        double x = MARGIN, y = y0 + rh + 30 + k * row_h;
        const sss_eval_entry *e = eval_find(res, scene, SSS_EVAL_QUALITY, res->labels[k], w, h);
        cairo_surface_t *is = e && e->ok ? eval_surface_from_image(&e->image, es->exposure) : NULL;
        cairo_surface_t *ms = e && e->has_metrics ? eval_surface_from_map(&e->dssim_map, MAP_GAIN) : NULL;
        cairo_surface_t *fs = e && e->has_metrics ? eval_surface_from_flip(&e->flip_map) : NULL;
        eval_window worst = e && e->has_metrics ? eval_worst_window(&e->flip_map, crop) : (eval_window){0};
        eval_draw_surface(cr, is, x, y, tw, th);
        if (is) {
            outline_window(cr, worst, x, y, st, WORST_RGB);
            outline_window(cr, sil, x, y, st, SILHOUETTE_RGB);
        }
        eval_draw_surface(cr, ms, x + tw + GAP, y, tw, th);
        eval_draw_surface(cr, fs, x + 2 * (tw + GAP), y, tw, th);
        if (ms) eval_draw_colour_bar(cr, x + tw + GAP, y + th + 3, tw, 8, 0, 1.0 / MAP_GAIN, "DSSIM");
        if (fs) eval_draw_colour_bar(cr, x + 2 * (tw + GAP), y + th + 3, tw, 8, 1, 1.0, "FLIP");
        caption(cr, res, e, res->labels[k], x, y + th + BAR, 3 * tw + 2 * GAP);
        if (is && e->has_metrics) {
            double cx = x + 3 * tw + 2 * GAP + 24;
            crop_pair(cr, rs, is, worst, cx, y, box, "worst FLIP", WORST_RGB);
            crop_pair(cr, rs, is, sil, cx + 2 * box + GAP + 24, y, box, "silhouette", SILHOUETTE_RGB);
        }
        if (is) cairo_surface_destroy(is);
        if (ms) cairo_surface_destroy(ms);
        if (fs) cairo_surface_destroy(fs);
    }
    if (rs) cairo_surface_destroy(rs);
    return eval_finish_canvas(s, cr, path, err);
}

sss_result eval_write_crops(const sss_eval_results *res, int scene, int k, const char *path, sss_error *err)
{
    if (!res || scene < 0 || scene >= res->scene_count || k < 0 || k >= res->label_count)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "%s: no such technique", path);
    const sss_eval_scene *es = &res->scenes[scene];
    int w, h;
    eval_primary_size(res, scene, &w, &h);
    const sss_eval_entry *e = eval_find(res, scene, SSS_EVAL_QUALITY, res->labels[k], w, h);
    if (!e || !e->has_metrics || !e->image.pixels)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "%s: %s was not compared", path, res->labels[k]);
    const double box = 192;
    int crop = eval_crop_size(w, h);
    eval_window worst = eval_worst_window(&e->flip_map, crop), sil = eval_silhouette_window(&es->object_ids, w, h, crop);
    int W = (int)(2 * MARGIN + 2 * (2 * box + GAP) + 24), H = (int)(MARGIN + box + 40);
    cairo_surface_t *s;
    cairo_t *cr;
    if (!eval_canvas(W, H, &s, &cr)) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: cannot draw", path);
    cairo_surface_t *rs = eval_surface_from_image(&es->reference, es->exposure);
    cairo_surface_t *is = eval_surface_from_image(&e->image, es->exposure);
    crop_pair(cr, rs, is, worst, MARGIN, MARGIN / 2, box, "worst FLIP", WORST_RGB);
    crop_pair(cr, rs, is, sil, MARGIN + 2 * box + GAP + 24, MARGIN / 2, box, "silhouette", SILHOUETTE_RGB);
    if (rs) cairo_surface_destroy(rs);
    if (is) cairo_surface_destroy(is);
    return eval_finish_canvas(s, cr, path, err);
}
