/* eval/eval_plot.c — the plots of the report, drawn with cairo: DSSIM per technique per scene as
 * grouped bars (Maisch & Ropinski 2020, Fig. 10), stacked milliseconds per pass (Maisch & Ropinski 2020, Fig. 11), SAM RMSE against
 * the number of back-side samples (Maisch & Ropinski 2017, Fig. 10) and frame time against resolution. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "eval/eval_internal.h"

#define FONT 13.0
#define TITLE_FONT 17.0

typedef struct frame {
    double x0, y0, x1, y1;   /* plot area in pixels (y0 top) */
    double xlo, xhi, ylo, yhi; /* data ranges */
} frame;

static double fx(const frame *f, double v) { return f->x0 + (v - f->xlo) / (f->xhi - f->xlo) * (f->x1 - f->x0); }
static double fy(const frame *f, double v) { return f->y1 - (v - f->ylo) / (f->yhi - f->ylo) * (f->y1 - f->y0); }

static double nice_max(double v)
{
    if (!(v > 0) || !isfinite(v)) return 1.0;
    double first, step;
    int count;
    eval_ticks(0, v * 1.08, 5, &first, &step, &count);
    return ceil(v * 1.08 / step - 1e-9) * step;
}

/* Title, y axis with ticks, grid lines and label; x axis line; about xticks x ticks (numeric x; 0: none). */
static void draw_axes(cairo_t *cr, const frame *f, const char *xlabel, const char *ylabel, int xticks)
{
    double first, step;
    int count;
    char buf[64];
    eval_ticks(f->ylo, f->yhi, 6, &first, &step, &count);
    cairo_set_line_width(cr, 1);
    for (int i = 0; i < count; i++) {
        double v = first + i * step;
        if (v > f->yhi + 1e-9 * step) break;
        double y = round(fy(f, v)) + 0.5;
        cairo_set_source_rgb(cr, 0.88, 0.88, 0.88);
        cairo_move_to(cr, f->x0, y);
        cairo_line_to(cr, f->x1, y);
        cairo_stroke(cr);
        cairo_set_source_rgb(cr, 0, 0, 0);
        cairo_move_to(cr, f->x0 - 5, y);
        cairo_line_to(cr, f->x0, y);
        cairo_stroke(cr);
        eval_format_number(v, step, buf, sizeof buf);
        eval_text(cr, f->x0 - 8, y + 4, FONT - 1, 0, 1.0, buf);
    }
    if (xticks) {
        eval_ticks(f->xlo, f->xhi, xticks, &first, &step, &count);
        for (int i = 0; i < count; i++) {
            double v = first + i * step;
            if (v > f->xhi + 1e-9 * step) break;
            double x = round(fx(f, v)) + 0.5;
            cairo_set_source_rgb(cr, 0.92, 0.92, 0.92);
            cairo_move_to(cr, x, f->y0);
            cairo_line_to(cr, x, f->y1);
            cairo_stroke(cr);
            cairo_set_source_rgb(cr, 0, 0, 0);
            cairo_move_to(cr, x, f->y1);
            cairo_line_to(cr, x, f->y1 + 5);
            cairo_stroke(cr);
            eval_format_number(v, step, buf, sizeof buf);
            eval_text(cr, x, f->y1 + 19, FONT - 1, 0, 0.5, buf);
        }
    }
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 1.2);
    cairo_move_to(cr, f->x0 + 0.5, f->y0);
    cairo_line_to(cr, f->x0 + 0.5, f->y1 + 0.5);
    cairo_line_to(cr, f->x1, f->y1 + 0.5);
    cairo_stroke(cr);
    if (xlabel) eval_text(cr, (f->x0 + f->x1) / 2, f->y1 + (xticks ? 42 : 38), FONT, 0, 0.5, xlabel);
    if (ylabel) {
        cairo_save(cr);
        cairo_translate(cr, f->x0 - 58, (f->y0 + f->y1) / 2);
        cairo_rotate(cr, -M_PI / 2);
        eval_text(cr, 0, 0, FONT, 0, 0.5, ylabel);
        cairo_restore(cr);
    }
}

/* The title, centred on the canvas (whose width fits it: see canvas_width). */
static void draw_title(cairo_t *cr, int W, const char *title)
{
    cairo_set_source_rgb(cr, 0, 0, 0);
    eval_text(cr, W / 2.0, 34, TITLE_FONT, 1, 0.5, title);
}

/* Widens W so that the title fits with margins. */
static int canvas_width(cairo_t *measure, int W, const char *title)
{
    int tw = (int)ceil(eval_text_width(measure, TITLE_FONT, 1, title)) + 60;
    return W > tw ? W : tw;
}

/* Legend: colour swatches (markers when lines) with labels, top-down from (x, y). */
static void draw_legend(cairo_t *cr, double x, double y, const char *heading, char **labels, int n, int lines)
{
    cairo_set_source_rgb(cr, 0, 0, 0);
    if (heading) {
        eval_text(cr, x, y, FONT, 1, 0, heading);
        y += 20;
    }
    for (int i = 0; i < n; i++) {
        eval_rgb c = eval_palette(i);
        cairo_set_source_rgb(cr, c.r, c.g, c.b);
        if (lines) {
            cairo_set_line_width(cr, 2.5);
            cairo_move_to(cr, x, y - 5);
            cairo_line_to(cr, x + 22, y - 5);
            cairo_stroke(cr);
            cairo_arc(cr, x + 11, y - 5, 4, 0, 2 * M_PI);
            cairo_fill(cr);
        } else {
            cairo_rectangle(cr, x, y - 11, 22, 12);
            cairo_fill(cr);
        }
        cairo_set_source_rgb(cr, 0, 0, 0);
        eval_text(cr, x + 30, y, FONT - 1, 0, 0, labels[i]);
        y += 19;
    }
}

static double legend_width(cairo_t *cr, const char *heading, char **labels, int n)
{
    double w = heading ? eval_text_width(cr, FONT, 1, heading) : 0;
    for (int i = 0; i < n; i++) w = fmax(w, 30 + eval_text_width(cr, FONT - 1, 0, labels[i]));
    return w + 30;
}

static void draw_fail_mark(cairo_t *cr, double x, double y)
{
    cairo_set_source_rgb(cr, 0.8, 0, 0);
    cairo_set_line_width(cr, 2);
    cairo_move_to(cr, x - 4, y - 12);
    cairo_line_to(cr, x + 4, y - 4);
    cairo_move_to(cr, x + 4, y - 12);
    cairo_line_to(cr, x - 4, y - 4);
    cairo_stroke(cr);
}

/* An external image's place in a timing plot: it has no timings (sss_eval_entry.external). */
static void draw_external_mark(cairo_t *cr, double x, double y)
{
    cairo_set_source_rgb(cr, 0.45, 0.45, 0.45);
    eval_text(cr, x, y - 4, FONT - 4, 0, 0.5, "ext");
}

static void center_message(cairo_t *cr, const frame *f, const char *msg, const char *detail)
{
    cairo_set_source_rgb(cr, 0.4, 0.4, 0.4);
    eval_text(cr, (f->x0 + f->x1) / 2, (f->y0 + f->y1) / 2, 20, 1, 0.5, msg);
    if (detail && detail[0]) eval_text(cr, (f->x0 + f->x1) / 2, (f->y0 + f->y1) / 2 + 26, FONT, 0, 0.5, detail);
}

/* Measuring context for text widths before the canvas size is known. */
static cairo_t *measure_ctx(cairo_surface_t **s)
{
    *s = cairo_image_surface_create(CAIRO_FORMAT_RGB24, 4, 4);
    return cairo_create(*s);
}

/* ---- DSSIM and FLIP bars (Maisch & Ropinski 2020, Fig. 10) ------------------------------------------------ */

static double metric_of(const sss_eval_entry *e, int flip) { return flip ? e->metrics.flip : e->metrics.dssim; }

static sss_result plot_metric_bars(const sss_eval_results *res, const char *path, int flip, sss_error *err)
{
    int ns = res->label_count, ng = res->scene_count;
    double bw = ns > 8 ? 14 : 20, gap = 28;
    cairo_surface_t *ms;
    cairo_t *mc = measure_ctx(&ms);
    double lw = legend_width(mc, "techniques", res->labels, ns);
    double glw = 0;
    for (int g = 0; g < ng; g++) glw = fmax(glw, eval_text_width(mc, FONT, 0, res->scenes[g].name));
    const char *title = flip ? "FLIP against the reference (mean LDR-FLIP at 67 ppd, lower is better)"
                             : "DSSIM against the reference (lower is better)";
    double group_w = fmax(ns * bw, glw) + gap;
    int W = canvas_width(mc, (int)(100 + ng * group_w + 30 + lw), title), H = 460;
    cairo_destroy(mc);
    cairo_surface_destroy(ms);
    cairo_surface_t *s;
    cairo_t *cr;
    if (!eval_canvas(W, H, &s, &cr)) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: cannot draw", path);
    double vmax = 0;
    for (int i = 0; i < res->entry_count; i++) {
        const sss_eval_entry *e = &res->entries[i];
        int pw, ph;
        eval_primary_size(res, e->scene, &pw, &ph);
        if (e->kind == SSS_EVAL_QUALITY && e->has_metrics && e->width == pw && e->height == ph)
            vmax = fmax(vmax, metric_of(e, flip));
    }
    frame f = {90, 60, W - lw - 20, H - 70, 0, 1, 0, nice_max(vmax)};
    draw_title(cr, W, title);
    draw_axes(cr, &f, NULL, flip ? "FLIP" : "DSSIM", 0);
    for (int g = 0; g < ng; g++) {
        double gx = f.x0 + gap / 2 + g * group_w + (group_w - gap - ns * bw) / 2;
        int pw, ph;
        eval_primary_size(res, g, &pw, &ph);
        for (int k = 0; k < ns; k++) {
            const sss_eval_entry *e = eval_find(res, g, SSS_EVAL_QUALITY, res->labels[k], pw, ph);
            double x = gx + k * bw;
            if (!e || !e->ok) {
                draw_fail_mark(cr, x + bw / 2, f.y1);
                continue;
            }
            if (!e->has_metrics) continue;
            eval_rgb c = eval_palette(k);
            cairo_set_source_rgb(cr, c.r, c.g, c.b);
            double y = fy(&f, metric_of(e, flip));
            cairo_rectangle(cr, x + 1, y, bw - 2, f.y1 - y);
            cairo_fill(cr);
        }
        cairo_set_source_rgb(cr, 0, 0, 0);
        eval_text(cr, f.x0 + gap / 2 + g * group_w + (group_w - gap) / 2, f.y1 + 20, FONT, 0, 0.5, res->scenes[g].name);
    }
    cairo_set_source_rgb(cr, 0.8, 0, 0);
    eval_text(cr, f.x0, H - 16, FONT - 2, 0, 0, "x = failed (see results.json); no bar = no reference");
    draw_legend(cr, f.x1 + 24, f.y0 + 10, "techniques", res->labels, ns, 0);
    return eval_finish_canvas(s, cr, path, err);
}

sss_result sss_eval_plot_dssim(const sss_eval_results *res, const char *path, sss_error *err)
{
    return plot_metric_bars(res, path, 0, err);
}

sss_result sss_eval_plot_flip(const sss_eval_results *res, const char *path, sss_error *err)
{
    return plot_metric_bars(res, path, 1, err);
}

/* ---- Stacked milliseconds per pass (Maisch & Ropinski 2020, Fig. 11) ----------------------------------------- */

static int cmp_dbl(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* One panel per scene, each with its own scale (software GL makes some techniques 100x slower than
 * others). A bar taller than the cap (3x the scene's median total, when that hides the others) is cut
 * with a break mark and labelled with its total. */
sss_result sss_eval_plot_passes(const sss_eval_results *res, const char *path, sss_error *err)
{
    /* the union of pass names, in order of appearance */
    char *names[64];
    char store[64][32];
    int np = 0;
    for (int i = 0; i < res->entry_count; i++) {
        const sss_eval_entry *e = &res->entries[i];
        int pw, ph;
        eval_primary_size(res, e->scene, &pw, &ph);
        if (e->kind != SSS_EVAL_QUALITY || !e->ok || e->width != pw || e->height != ph) continue;
        for (int p = 0; p < e->pass_count; p++) {
            int j = 0;
            while (j < np && strcmp(names[j], e->passes[p].name) != 0) j++;
            if (j == np && np < 64) {
                snprintf(store[np], sizeof store[np], "%s", e->passes[p].name);
                names[np] = store[np];
                np++;
            }
        }
    }
    int ns = res->label_count, ng = res->scene_count;
    double bw = 22;
    cairo_surface_t *ms;
    cairo_t *mc = measure_ctx(&ms);
    double lw = legend_width(mc, "passes", names, np);
    double tl = 0;
    for (int k = 0; k < ns; k++) tl = fmin(160, fmax(tl, eval_text_width(mc, FONT - 2, 0, res->labels[k])));
    const char *title = "Milliseconds per frame by pass (median of the frames; each scene its own scale)";
    double pw_px = fmax(220, 80 + ns * bw + 20), ph_px = 300 + tl * 0.8 + 30;
    int cols = ng < 4 ? (ng > 0 ? ng : 1) : 4, rows = (ng + cols - 1) / cols;
    int W = canvas_width(mc, (int)(cols * pw_px + 30 + lw), title);
    int H = (int)(60 + rows * ph_px + fmax(0, np * 19 + 40 - rows * ph_px));
    cairo_destroy(mc);
    cairo_surface_destroy(ms);
    cairo_surface_t *s;
    cairo_t *cr;
    if (!eval_canvas(W, H, &s, &cr)) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: cannot draw", path);
    draw_title(cr, W, title);
    for (int g = 0; g < ng; g++) {
        int pw, ph;
        eval_primary_size(res, g, &pw, &ph);
        double totals[256];
        int nt = 0;
        double vmax = 0;
        for (int k = 0; k < ns; k++) {
            const sss_eval_entry *e = eval_find(res, g, SSS_EVAL_QUALITY, res->labels[k], pw, ph);
            if (e && e->ok && !e->external && nt < 256) totals[nt++] = e->total_ms;
            if (e && e->ok && !e->external) vmax = fmax(vmax, e->total_ms);
        }
        double cap = vmax;
        if (nt >= 3) {
            qsort(totals, (size_t)nt, sizeof *totals, cmp_dbl);
            double med = totals[nt / 2];
            if (vmax > 4 * med && med > 0) cap = 3 * med;
        }
        double px = 20 + (g % cols) * pw_px, py = 60 + (g / cols) * ph_px;
        frame f = {px + 62, py + 40, px + pw_px - 12, py + 250, 0, 1, 0, nice_max(cap)};
        char buf[200];
        cairo_set_source_rgb(cr, 0, 0, 0);
        eval_text(cr, (f.x0 + f.x1) / 2, py + 14, FONT, 1, 0.5, res->scenes[g].name);
        snprintf(buf, sizeof buf, "%llu triangles, %dx%d", res->scenes[g].triangles, pw, ph);
        eval_text(cr, (f.x0 + f.x1) / 2, py + 30, FONT - 3, 0, 0.5, buf);
        draw_axes(cr, &f, NULL, g % cols == 0 ? "ms" : NULL, 0);
        double gx = f.x0 + (f.x1 - f.x0 - ns * bw) / 2;
        for (int k = 0; k < ns; k++) {
            const sss_eval_entry *e = eval_find(res, g, SSS_EVAL_QUALITY, res->labels[k], pw, ph);
            double x = gx + k * bw;
            if (!e || !e->ok) draw_fail_mark(cr, x + bw / 2, f.y1);
            else if (e->external) draw_external_mark(cr, x + bw / 2, f.y1);
            else {
                double acc = 0;
                for (int p = 0; p < e->pass_count; p++) {
                    int j = 0;
                    while (j < np && strcmp(names[j], e->passes[p].name) != 0) j++;
                    eval_rgb c = eval_palette(j);
                    double a0 = fmin(acc, f.yhi), a1 = fmin(acc + e->passes[p].ms, f.yhi);
                    acc += e->passes[p].ms;
                    if (a1 <= a0) continue;
                    cairo_set_source_rgb(cr, c.r, c.g, c.b);
                    cairo_rectangle(cr, x + 2, fy(&f, a1), bw - 4, fy(&f, a0) - fy(&f, a1));
                    cairo_fill(cr);
                }
                if (acc > f.yhi) {
                    /* a break mark and the real total */
                    double y = fy(&f, f.yhi * 0.93);
                    cairo_set_source_rgb(cr, 1, 1, 1);
                    cairo_rectangle(cr, x + 1, y - 3, bw - 2, 6);
                    cairo_fill(cr);
                    cairo_set_source_rgb(cr, 0, 0, 0);
                    cairo_set_line_width(cr, 1);
                    cairo_move_to(cr, x + 1, y - 1);
                    cairo_line_to(cr, x + bw - 1, y - 5);
                    cairo_move_to(cr, x + 1, y + 5);
                    cairo_line_to(cr, x + bw - 1, y + 1);
                    cairo_stroke(cr);
                    /* the real total, written downwards inside the bar below the break */
                    snprintf(buf, sizeof buf, "%.0f ms", acc);
                    double tw = eval_text_width(cr, FONT - 3, 0, buf);
                    cairo_set_source_rgb(cr, 1, 1, 1);
                    cairo_rectangle(cr, x + 3, y + 6, bw - 6, tw + 6);
                    cairo_fill(cr);
                    cairo_save(cr);
                    cairo_set_source_rgb(cr, 0, 0, 0);
                    cairo_translate(cr, x + bw / 2 - 4, y + 9); /* glyphs extend to +x when rotated */
                    cairo_rotate(cr, M_PI / 2);
                    eval_text(cr, 0, 0, FONT - 3, 0, 0, buf);
                    cairo_restore(cr);
                }
            }
            cairo_save(cr);
            cairo_set_source_rgb(cr, 0, 0, 0);
            cairo_translate(cr, x + bw / 2 + 4, f.y1 + 8);
            cairo_rotate(cr, M_PI / 2.6);
            eval_text(cr, 0, 0, FONT - 2, 0, 0, res->labels[k]);
            cairo_restore(cr);
        }
    }
    draw_legend(cr, 20 + cols * pw_px + 10, 80, "passes", names, np, 0);
    return eval_finish_canvas(s, cr, path, err);
}

/* ---- Line plots ------------------------------------------------------------------------------- */

typedef struct series {
    double x[64], y[64];
    int n;
} series;

static void draw_series(cairo_t *cr, const frame *f, const series *sv, int count)
{
    for (int i = 0; i < count; i++) {
        eval_rgb c = eval_palette(i);
        cairo_set_source_rgb(cr, c.r, c.g, c.b);
        cairo_set_line_width(cr, 2.2);
        for (int k = 0; k < sv[i].n; k++) {
            double x = fx(f, sv[i].x[k]), y = fy(f, sv[i].y[k]);
            if (k == 0) cairo_move_to(cr, x, y);
            else cairo_line_to(cr, x, y);
        }
        cairo_stroke(cr);
        for (int k = 0; k < sv[i].n; k++) {
            cairo_arc(cr, fx(f, sv[i].x[k]), fy(f, sv[i].y[k]), 4, 0, 2 * M_PI);
            cairo_fill(cr);
        }
    }
}

static void sort_series(series *s)
{
    for (int i = 1; i < s->n; i++)
        for (int j = i; j > 0 && s->x[j] < s->x[j - 1]; j--) {
            double t = s->x[j];
            s->x[j] = s->x[j - 1];
            s->x[j - 1] = t;
            t = s->y[j];
            s->y[j] = s->y[j - 1];
            s->y[j - 1] = t;
        }
}

static sss_result line_plot(const char *path, const char *title, const char *xlabel, const char *ylabel,
                            const char *heading, char **labels, const series *sv, int count, const char *empty,
                            const char *empty_detail, sss_error *err)
{
    cairo_surface_t *ms;
    cairo_t *mc = measure_ctx(&ms);
    double lw = legend_width(mc, heading, labels, count);
    int W = canvas_width(mc, (int)(640 + lw), title), H = 440;
    cairo_destroy(mc);
    cairo_surface_destroy(ms);
    cairo_surface_t *s;
    cairo_t *cr;
    if (!eval_canvas(W, H, &s, &cr)) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: cannot draw", path);
    double xmax = 0, ymax = 0;
    int points = 0;
    for (int i = 0; i < count; i++)
        for (int k = 0; k < sv[i].n; k++) {
            xmax = fmax(xmax, sv[i].x[k]);
            ymax = fmax(ymax, sv[i].y[k]);
            points++;
        }
    frame f = {90, 60, W - lw - 20, H - 70, 0, nice_max(xmax), 0, nice_max(ymax)};
    draw_title(cr, W, title);
    draw_axes(cr, &f, xlabel, ylabel, 8);
    if (points == 0 || empty_detail) center_message(cr, &f, empty, empty_detail);
    else {
        draw_series(cr, &f, sv, count);
        draw_legend(cr, f.x1 + 24, f.y0 + 10, heading, labels, count, 1);
    }
    return eval_finish_canvas(s, cr, path, err);
}

sss_result sss_eval_plot_sam(const sss_eval_results *res, const char *path, sss_error *err)
{
    int ng = res->scene_count;
    series *sv = calloc((size_t)(ng ? ng : 1), sizeof *sv);
    char **labels = calloc((size_t)(ng ? ng : 1), sizeof *labels);
    if (!sv || !labels) {
        free(sv);
        free(labels);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory");
    }
    for (int g = 0; g < ng; g++) {
        labels[g] = (char *)res->scenes[g].name;
        for (int i = 0; i < res->entry_count; i++) {
            const sss_eval_entry *e = &res->entries[i];
            if (e->scene != g || e->kind != SSS_EVAL_SAM_SWEEP || !e->has_metrics || sv[g].n >= 64) continue;
            sv[g].x[sv[g].n] = e->sam_n;
            sv[g].y[sv[g].n] = e->metrics.rmse;
            sv[g].n++;
        }
        sort_series(&sv[g]);
    }
    char xlabel[96] = "back-side samples n";
    if (res->sam_param[0]) snprintf(xlabel, sizeof xlabel, "back-side samples n (sam parameter %s)", res->sam_param);
    const char *detail = NULL;
    const char *msg = "no SAM sweep results";
    if (!res->sam_available) {
        msg = "sam not available";
        detail = res->sam_note;
    } else if (!res->sam_swept) {
        msg = "SAM sweep not run";
        detail = "evaluate the sam technique (or pass --sam-sweep) to plot it";
    }
    sss_result r = line_plot(path, "SAM: RMSE against back-side samples (Maisch & Ropinski 2017, Fig. 10)", xlabel,
                             "RMSE (8-bit sRGB)", "scenes", labels, sv, ng, msg, detail, err);
    free(sv);
    free(labels);
    return r;
}

/* One panel per scene (its sizes differ from the others', and so do its costs): frame time against
 * megapixels, one line per technique, over the quality and timing sizes of that scene only. */
sss_result sss_eval_plot_resolution(const sss_eval_results *res, const char *path, sss_error *err)
{
    int nl = res->label_count, ng = res->scene_count;
    series *sv = calloc((size_t)(nl ? nl : 1) * (size_t)(ng ? ng : 1), sizeof *sv);
    if (!sv) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory");
    int points = 0;
    for (int g = 0; g < ng; g++)
        for (int k = 0; k < nl; k++) {
            series *se = &sv[(size_t)g * (size_t)nl + (size_t)k];
            for (int i = 0; i < res->entry_count && se->n < 64; i++) {
                const sss_eval_entry *e = &res->entries[i];
                if (e->scene != g || e->kind == SSS_EVAL_SAM_SWEEP || !e->ok || e->external ||
                    strcmp(e->label, res->labels[k]) != 0)
                    continue;
                se->x[se->n] = e->width * (double)e->height / 1e6;
                se->y[se->n] = e->total_ms;
                se->n++;
                points++;
            }
            sort_series(se);
        }
    const char *title = "Frame time against resolution, per scene (median ms per frame)";
    cairo_surface_t *ms;
    cairo_t *mc = measure_ctx(&ms);
    double lw = legend_width(mc, "techniques", res->labels, nl);
    double pw_px = 380, ph_px = 330;
    int cols = ng < 3 ? (ng > 0 ? ng : 1) : 3, rows = ng > 0 ? (ng + cols - 1) / cols : 1;
    int W = canvas_width(mc, (int)(20 + cols * pw_px + 30 + lw), title);
    int H = (int)(60 + fmax(rows * ph_px, nl * 19 + 60));
    cairo_destroy(mc);
    cairo_surface_destroy(ms);
    cairo_surface_t *s;
    cairo_t *cr;
    if (!eval_canvas(W, H, &s, &cr)) {
        free(sv);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "%s: cannot draw", path);
    }
    draw_title(cr, W, title);
    for (int g = 0; g < ng; g++) {
        const series *sg = &sv[(size_t)g * (size_t)nl];
        double xmax = 0, ymax = 0;
        for (int k = 0; k < nl; k++)
            for (int j = 0; j < sg[k].n; j++) xmax = fmax(xmax, sg[k].x[j]), ymax = fmax(ymax, sg[k].y[j]);
        double px = 20 + (g % cols) * pw_px, py = 60 + (g / cols) * ph_px;
        frame f = {px + 70, py + 30, px + pw_px - 20, py + ph_px - 60, 0, nice_max(xmax), 0, nice_max(ymax)};
        cairo_set_source_rgb(cr, 0, 0, 0);
        eval_text(cr, (f.x0 + f.x1) / 2, py + 14, FONT, 1, 0.5, res->scenes[g].name);
        draw_axes(cr, &f, "megapixels", g % cols == 0 ? "ms per frame" : NULL, 4);
        draw_series(cr, &f, sg, nl);
    }
    if (points == 0) {
        frame f = {90, 60, W - lw - 20, H - 70, 0, 1, 0, 1};
        center_message(cr, &f, "no successful renders", NULL);
    }
    draw_legend(cr, 20 + cols * pw_px + 10, 80, "techniques", res->labels, nl, 1);
    free(sv);
    return eval_finish_canvas(s, cr, path, err);
}
