/* eval/eval_sheet.c — the comparison sheet of one scene, after Maisch & Ropinski 2020, Fig. 7: the reference large
 * on the left; for every technique its image, its per-pixel DSSIM map (R, G, B = the DSSIM of each
 * channel, black = no perceptible difference) and a caption with label, DSSIM and milliseconds. */
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

sss_result sss_eval_write_sheet(const sss_eval_results *res, int scene, const char *path, sss_error *err)
{
    if (!res || scene < 0 || scene >= res->scene_count)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sheet: no scene %d", scene);
    const sss_eval_scene *es = &res->scenes[scene];
    int w, h;
    eval_primary_size(res, scene, &w, &h);
    double st = fmin(300.0 / w, 220.0 / h), sr = fmin(640.0 / w, 560.0 / h);
    double tw = floor(w * st), th = floor(h * st), rw = floor(w * sr), rh = floor(h * sr);
    int n = res->label_count;
    int ncol = n <= 3 ? 1 : 2;
    int rows = (n + ncol - 1) / ncol;
    double cell_w = 2 * tw + GAP, cell_h = th + CAPTION + 12;
    double left_h = rh + 80;
    int W = (int)(MARGIN + rw + 24 + ncol * (cell_w + 16) + MARGIN);
    int H = (int)(HEADER + fmax(left_h, rows * cell_h) + MARGIN);
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

    /* the reference, large */
    double y0 = HEADER;
    cairo_surface_t *rs = eval_surface_from_image(&es->reference, es->exposure);
    eval_draw_surface(cr, rs, MARGIN, y0, rw, rh);
    if (rs) cairo_surface_destroy(rs);
    cairo_set_source_rgb(cr, 0, 0, 0);
    eval_text(cr, MARGIN, y0 + rh + 20, 14, 1, 0, "Reference (CPU ground truth)");
    cairo_set_source_rgb(cr, 0.3, 0.3, 0.3);
    snprintf(buf, sizeof buf, "DSSIM maps: R, G, B = per-channel DSSIM x %g (white >= %g); black = no difference",
             MAP_GAIN, 1.0 / MAP_GAIN);
    fit_text(cr, 11, 0, buf, rw, fit, sizeof fit);
    eval_text(cr, MARGIN, y0 + rh + 40, 11, 0, 0, fit);
    snprintf(buf, sizeof buf, "ms: median total frame time of %d frame%s after %d warm-up; %s", res->frames,
             res->frames == 1 ? "" : "s", res->warmup_frames,
             res->timing_method[0] ? res->timing_method : "");
    fit_text(cr, 11, 0, buf, rw, fit, sizeof fit);
    eval_text(cr, MARGIN, y0 + rh + 56, 11, 0, 0, fit);

    /* the techniques */
    for (int k = 0; k < n; k++) {
        int col = k % ncol, row = k / ncol;
        double x = MARGIN + rw + 24 + col * (cell_w + 16), y = y0 + row * cell_h;
        const sss_eval_entry *e = eval_find(res, scene, SSS_EVAL_QUALITY, res->labels[k], w, h);
        cairo_surface_t *is = e && e->ok ? eval_surface_from_image(&e->image, es->exposure) : NULL;
        cairo_surface_t *ms = e && e->has_metrics ? eval_surface_from_map(&e->dssim_map, MAP_GAIN) : NULL;
        eval_draw_surface(cr, is, x, y, tw, th);
        eval_draw_surface(cr, ms, x + tw + GAP, y, tw, th);
        if (is) cairo_surface_destroy(is);
        if (ms) cairo_surface_destroy(ms);
        cairo_set_source_rgb(cr, 0, 0, 0);
        fit_text(cr, 13, 1, res->labels[k], cell_w, fit, sizeof fit);
        eval_text(cr, x, y + th + 17, 13, 1, 0, fit);
        if (!e || !e->ok) {
            cairo_set_source_rgb(cr, 0.8, 0, 0);
            snprintf(buf, sizeof buf, "FAILED: %s", e ? e->error : "not run");
        } else if (e->has_metrics) {
            snprintf(buf, sizeof buf, "DSSIM %.4f   PSNR %.1f dB   %.1f ms", e->metrics.dssim,
                     isfinite(e->metrics.psnr) ? e->metrics.psnr : 99.0, e->total_ms);
            if (!isfinite(e->metrics.psnr))
                snprintf(buf, sizeof buf, "DSSIM %.4f   PSNR inf   %.1f ms", e->metrics.dssim, e->total_ms);
        } else {
            snprintf(buf, sizeof buf, "no reference   %.1f ms", e->total_ms);
        }
        fit_text(cr, 11.5, 0, buf, cell_w, fit, sizeof fit);
        eval_text(cr, x, y + th + 33, 11.5, 0, 0, fit);
    }
    sss_result r = cairo_status(cr) == CAIRO_STATUS_SUCCESS ? eval_write_surface(s, path, err)
                                                            : sss_error_set(err, SSS_ERROR_UNSUPPORTED, "%s: cairo: %s",
                                                                            path, cairo_status_to_string(cairo_status(cr)));
    cairo_destroy(cr);
    cairo_surface_destroy(s);
    return r;
}
