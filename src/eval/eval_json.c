/* eval/eval_json.c — results.json (schema docs/results.schema.json, "sss-eval-results/1") and
 * results.csv (one row per entry). Non-finite numbers never reach a file: they become null (JSON) or
 * an empty field (CSV); an infinite PSNR (identical images) is null, in JSON with "psnr_infinite": true. */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/file_util.h"
#include "core/text.h"
#include "eval/eval_internal.h"
#include "sss/version.h"

static void add_num(cJSON *o, const char *key, double v)
{
    if (isfinite(v)) cJSON_AddNumberToObject(o, key, v);
    else cJSON_AddNullToObject(o, key);
}

/* A string from data (a path, a technique name): escaped (eval_escaped), since JSON text must be UTF-8. */
static void add_text(cJSON *o, const char *key, const char *text)
{
    char *escaped = eval_escaped(text);
    if (escaped) cJSON_AddStringToObject(o, key, escaped);
    free(escaped);
}

static const char *ref_source(sss_eval_ref_source s)
{
    return s == SSS_EVAL_REF_CACHED ? "cached" : s == SSS_EVAL_REF_RENDERED ? "rendered" : "unavailable";
}

/* metrics: dssim, flip, psnr, psnr_infinite, rmse, max_abs and mean_ratio [R, G, B] (null where unknown) */
static void add_metrics(cJSON *o, const sss_image_metrics *m, const double ratio[3], int has)
{
    const char *keys[] = {"dssim", "flip", "psnr", "rmse", "max_abs"};
    double v[] = {m->dssim, m->flip, m->psnr, m->rmse, m->max_abs};
    for (int i = 0; i < 5; i++) {
        if (has) add_num(o, keys[i], v[i]);
        else cJSON_AddNullToObject(o, keys[i]);
    }
    cJSON_AddBoolToObject(o, "psnr_infinite", has && isinf(m->psnr));
    cJSON *r = has ? cJSON_AddArrayToObject(o, "mean_ratio") : cJSON_AddNullToObject(o, "mean_ratio");
    for (int c = 0; has && r && c < 3; c++)
        cJSON_AddItemToArray(r, isfinite(ratio[c]) ? cJSON_CreateNumber(ratio[c]) : cJSON_CreateNull());
}

static cJSON *entry_json(const sss_eval_results *res, const sss_eval_entry *e)
{
    cJSON *o = cJSON_CreateObject();
    if (!o) return NULL;
    cJSON_AddStringToObject(o, "scene", res->scenes[e->scene].name);
    cJSON_AddNumberToObject(o, "scene_index", e->scene);
    cJSON_AddStringToObject(o, "kind", sss_eval_kind_name(e->kind));
    add_text(o, "technique", e->technique);
    cJSON_AddStringToObject(o, "label", e->label);
    cJSON *params = cJSON_AddObjectToObject(o, "params");
    eval_spec spec;
    if (params && !e->external && eval_parse_spec(e->label, &spec, NULL) == SSS_OK)
        for (int i = 0; i < spec.param_count; i++) add_num(params, spec.names[i], spec.params[i].value);
    cJSON_AddNumberToObject(o, "width", e->width);
    cJSON_AddNumberToObject(o, "height", e->height);
    if (e->kind == SSS_EVAL_SAM_SWEEP) cJSON_AddNumberToObject(o, "sam_n", e->sam_n);
    else cJSON_AddNullToObject(o, "sam_n");
    cJSON_AddStringToObject(o, "status", e->ok ? "ok" : "failed");
    if (e->ok) cJSON_AddNullToObject(o, "error");
    else add_text(o, "error", e->error);
    if (e->warning[0]) add_text(o, "warning", e->warning);
    else cJSON_AddNullToObject(o, "warning");
    add_metrics(o, &e->metrics, e->mean_ratio, e->has_metrics);
    cJSON *single = e->has_single_event ? cJSON_AddObjectToObject(o, "single_event")
                                        : cJSON_AddNullToObject(o, "single_event");
    if (e->has_single_event && single) add_metrics(single, &e->single_event, e->single_event_ratio, 1);
    cJSON_AddNumberToObject(o, "frames", e->frames);
    cJSON_AddNumberToObject(o, "warmup_frames", e->warmup_frames);
    cJSON_AddNumberToObject(o, "supersample", e->supersample > 0 ? e->supersample : 1);
    if (e->ok && !e->external) add_num(o, "ms_total", e->total_ms);
    else cJSON_AddNullToObject(o, "ms_total");
    cJSON_AddBoolToObject(o, "external", e->external);
    if (e->external) add_text(o, "file", e->file);
    else cJSON_AddNullToObject(o, "file");
    cJSON *passes = cJSON_AddArrayToObject(o, "passes");
    for (int p = 0; passes && e->ok && p < e->pass_count; p++) {
        cJSON *po = cJSON_CreateObject();
        if (!po) continue;
        cJSON_AddStringToObject(po, "name", e->passes[p].name);
        add_num(po, "ms", e->passes[p].ms);
        cJSON_AddItemToArray(passes, po);
    }
    /* set-up time exists whenever the renderer was created, even if a frame failed later */
    if (e->precompute_ms > 0) add_num(o, "precompute_ms", e->precompute_ms);
    else cJSON_AddNullToObject(o, "precompute_ms");
    if (e->has_stats) {
        cJSON *m = cJSON_AddObjectToObject(o, "memory");
        if (m) {
            cJSON_AddNumberToObject(m, "gpu_bytes", (double)(e->stats.texture_bytes + e->stats.buffer_bytes));
            cJSON_AddNumberToObject(m, "texture_bytes", (double)e->stats.texture_bytes);
            cJSON_AddNumberToObject(m, "buffer_bytes", (double)e->stats.buffer_bytes);
            cJSON_AddNumberToObject(m, "lut_bytes", (double)e->stats.lut_bytes);
            cJSON_AddNumberToObject(m, "per_pixel_bytes", (double)e->stats.per_pixel_bytes);
            cJSON_AddNumberToObject(m, "splat_total", e->stats.splat_total);
            cJSON_AddNumberToObject(m, "splat_drawn", e->stats.splat_drawn);
        }
    } else {
        cJSON_AddNullToObject(o, "memory");
    }
    return o;
}

static cJSON *reference_json(const sss_eval_reference *r)
{
    cJSON *ro = cJSON_CreateObject();
    if (!ro) return NULL;
    cJSON_AddNumberToObject(ro, "width", r->width);
    cJSON_AddNumberToObject(ro, "height", r->height);
    cJSON_AddStringToObject(ro, "source", ref_source(r->source));
    cJSON_AddStringToObject(ro, "quality", r->quality[0] ? r->quality : "unknown");
    cJSON_AddNumberToObject(ro, "bounces", r->bounces);
    if (r->path[0]) add_text(ro, "path", r->path);
    else cJSON_AddNullToObject(ro, "path");
    add_num(ro, "seconds", r->seconds);
    if (r->source == SSS_EVAL_REF_NONE) add_text(ro, "error", r->error);
    else cJSON_AddNullToObject(ro, "error");
    return ro;
}

static cJSON *results_json(const sss_eval_results *res)
{
    cJSON *root = cJSON_CreateObject();
    if (!root) return NULL;
    cJSON_AddStringToObject(root, "schema", "sss-eval-results/1");
    cJSON_AddStringToObject(root, "generator", "sss eval " SSS_VERSION_STRING);
    cJSON_AddStringToObject(root, "created", res->created);
    add_num(root, "seconds", res->seconds);
    cJSON *gl = cJSON_AddObjectToObject(root, "gl");
    if (gl) {
        cJSON_AddBoolToObject(gl, "available", res->gl_ok);
        if (res->gl_ok) cJSON_AddNullToObject(gl, "error");
        else cJSON_AddStringToObject(gl, "error", res->gl_error[0] ? res->gl_error : "no techniques were run");
        cJSON_AddStringToObject(gl, "platform", res->gl_platform);
        cJSON_AddStringToObject(gl, "renderer", res->gl_renderer);
        cJSON_AddStringToObject(gl, "version", res->gl_version);
        cJSON_AddBoolToObject(gl, "software", res->gl_software);
        cJSON_AddStringToObject(gl, "timing_method", res->timing_method);
    }
    cJSON *set = cJSON_AddObjectToObject(root, "settings");
    if (set) {
        cJSON_AddNumberToObject(set, "frames", res->frames);
        cJSON_AddNumberToObject(set, "warmup_frames", res->warmup_frames);
        if (res->frame_budget_s > 0) cJSON_AddNumberToObject(set, "frame_budget_s", res->frame_budget_s);
        else cJSON_AddNullToObject(set, "frame_budget_s");
        cJSON_AddNumberToObject(set, "supersample", res->supersample > 0 ? res->supersample : 1);
        cJSON_AddStringToObject(set, "reference_quality", res->reference_quality == SSS_REFERENCE_DRAFT ? "draft" : "final");
        cJSON_AddBoolToObject(set, "cached_reference", res->cached_reference);
        cJSON_AddNumberToObject(set, "reference_bounces", res->reference_bounces);
        cJSON_AddBoolToObject(set, "both_truths", res->both_truths);
        int nt = res->label_count - res->external_count;
        cJSON *t = cJSON_AddArrayToObject(set, "techniques");
        for (int i = 0; t && i < nt; i++) cJSON_AddItemToArray(t, cJSON_CreateString(res->labels[i]));
        cJSON *im = cJSON_AddArrayToObject(set, "images");
        for (int j = 0; im && j < res->external_count; j++) {
            cJSON *io = cJSON_CreateObject();
            if (!io) continue;
            cJSON_AddStringToObject(io, "name", res->labels[nt + j]);
            cJSON_AddStringToObject(io, "pattern", res->external_patterns[j]);
            cJSON_AddItemToArray(im, io);
        }
    }
    cJSON *scenes = cJSON_AddArrayToObject(root, "scenes");
    for (int i = 0; scenes && i < res->scene_count; i++) {
        const sss_eval_scene *s = &res->scenes[i];
        cJSON *o = cJSON_CreateObject();
        if (!o) continue;
        cJSON_AddStringToObject(o, "name", s->name);
        add_text(o, "path", s->path);
        cJSON_AddNumberToObject(o, "time", s->time);
        cJSON_AddNumberToObject(o, "width", s->width);
        cJSON_AddNumberToObject(o, "height", s->height);
        cJSON_AddNumberToObject(o, "exposure", s->exposure);
        cJSON_AddNumberToObject(o, "triangles", (double)s->triangles);
        cJSON *noise = s->has_noise ? cJSON_AddObjectToObject(o, "noise") : cJSON_AddNullToObject(o, "noise");
        if (s->has_noise && noise) {
            add_num(noise, "dssim", s->noise_dssim);
            add_num(noise, "flip", s->noise_flip);
        }
        cJSON *refs = cJSON_AddArrayToObject(o, "references");
        for (int k = 0; refs && k < s->reference_count; k++) {
            cJSON *ro = reference_json(&s->references[k]);
            if (ro) cJSON_AddItemToArray(refs, ro);
        }
        if (res->both_truths) cJSON_AddItemToObject(o, "single_event_reference", reference_json(&s->single_event_reference));
        else cJSON_AddNullToObject(o, "single_event_reference");
        cJSON_AddItemToArray(scenes, o);
    }
    cJSON *results = cJSON_AddArrayToObject(root, "results");
    for (int i = 0; results && i < res->entry_count; i++) {
        if (res->entries[i].kind == SSS_EVAL_SAM_SWEEP) continue;
        cJSON *o = entry_json(res, &res->entries[i]);
        if (o) cJSON_AddItemToArray(results, o);
    }
    cJSON *sam = cJSON_AddObjectToObject(root, "sam_sweep");
    if (sam) {
        cJSON_AddBoolToObject(sam, "available", res->sam_available);
        cJSON_AddBoolToObject(sam, "ran", res->sam_swept);
        if (res->sam_param[0]) cJSON_AddStringToObject(sam, "param", res->sam_param);
        else cJSON_AddNullToObject(sam, "param");
        cJSON_AddStringToObject(sam, "note", res->sam_note);
        cJSON *pts = cJSON_AddArrayToObject(sam, "points");
        for (int i = 0; pts && i < res->entry_count; i++) {
            if (res->entries[i].kind != SSS_EVAL_SAM_SWEEP) continue;
            cJSON *o = entry_json(res, &res->entries[i]);
            if (o) cJSON_AddItemToArray(pts, o);
        }
    }
    return root;
}

sss_result sss_eval_write_json(const sss_eval_results *res, const char *path, sss_error *err)
{
    cJSON *root = results_json(res);
    char *text = root ? cJSON_Print(root) : NULL;
    cJSON_Delete(root);
    if (!text) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (%s)", path);
    char tmp[4096];
    FILE *f = sss_atomic_open(path, tmp, sizeof tmp, err);
    if (!f) {
        free(text);
        return err ? err->code : SSS_ERROR_IO;
    }
    fputs(text, f);
    fputc('\n', f);
    free(text);
    return sss_atomic_close(f, tmp, path, err);
}

/* RFC 4180 field: quoted when it holds a comma, quote or line break. */
/* A CSV field, quoted when it must be; control characters and bytes that are not UTF-8 as visible
 * escapes (core/text.h: scene names come from file names). */
static void csv_field(FILE *f, const char *text)
{
    char escaped[SSS_TEXT_ESCAPE_MAX * 512 + 1];
    sss_text_escape(text, strnlen(text, 512), escaped);
    if (!strpbrk(escaped, ",\"")) { /* no line breaks are left to quote */
        fputs(escaped, f);
        return;
    }
    fputc('"', f);
    for (const char *s = escaped; *s; s++) {
        if (*s == '"') fputc('"', f);
        fputc(*s, f);
    }
    fputc('"', f);
}

static void csv_num(FILE *f, double v, int ok)
{
    if (ok && isfinite(v)) fprintf(f, ",%.6g", v);
    else fputc(',', f);
}

/* dssim, flip, psnr (empty when infinite: identical images, rmse 0), rmse, max_abs */
static void csv_metrics(FILE *f, const sss_image_metrics *m, int ok)
{
    csv_num(f, m->dssim, ok);
    csv_num(f, m->flip, ok);
    csv_num(f, m->psnr, ok);
    csv_num(f, m->rmse, ok);
    csv_num(f, m->max_abs, ok);
}

sss_result sss_eval_write_csv(const sss_eval_results *res, const char *path, sss_error *err)
{
    char tmp[4096];
    FILE *f = sss_atomic_open(path, tmp, sizeof tmp, err);
    if (!f) return err ? err->code : SSS_ERROR_IO;
    fputs("scene,time,kind,technique,label,width,height,sam_n,status,dssim,flip,psnr,rmse,max_abs,frames,ms_total,"
          "precompute_ms,gpu_bytes,passes,error,external,file,warmup_frames,mean_ratio_r,mean_ratio_g,mean_ratio_b,"
          "single_event_dssim,single_event_flip,single_event_psnr,single_event_rmse,single_event_max_abs,"
          "single_event_ratio_r,single_event_ratio_g,single_event_ratio_b\n", f);
    for (int i = 0; i < res->entry_count; i++) {
        const sss_eval_entry *e = &res->entries[i];
        const sss_eval_scene *s = &res->scenes[e->scene];
        csv_field(f, s->name);
        fprintf(f, ",%g,%s,", s->time, sss_eval_kind_name(e->kind));
        csv_field(f, e->technique);
        fputc(',', f);
        csv_field(f, e->label);
        fprintf(f, ",%d,%d,", e->width, e->height);
        if (e->kind == SSS_EVAL_SAM_SWEEP) fprintf(f, "%d", e->sam_n);
        fprintf(f, ",%s", e->ok ? "ok" : "failed");
        csv_metrics(f, &e->metrics, e->has_metrics);
        fprintf(f, ",%d", e->frames);
        csv_num(f, e->total_ms, e->ok && !e->external);
        csv_num(f, e->precompute_ms, e->precompute_ms > 0);
        if (e->has_stats) fprintf(f, ",%zu,", e->stats.texture_bytes + e->stats.buffer_bytes);
        else fputs(",,", f);
        char passes[2048] = "";
        size_t at = 0;
        for (int p = 0; e->ok && p < e->pass_count && at < sizeof passes; p++)
            at += (size_t)snprintf(passes + at, sizeof passes - at, "%s%s=%.3f", p ? ";" : "", e->passes[p].name,
                                   e->passes[p].ms);
        csv_field(f, passes);
        fputc(',', f);
        csv_field(f, e->ok ? "" : e->error);
        fprintf(f, ",%d,", e->external);
        csv_field(f, e->external ? e->file : "");
        fprintf(f, ",%d", e->warmup_frames);
        for (int c = 0; c < 3; c++) csv_num(f, e->mean_ratio[c], e->has_metrics);
        csv_metrics(f, &e->single_event, e->has_single_event);
        for (int c = 0; c < 3; c++) csv_num(f, e->single_event_ratio[c], e->has_single_event);
        fputc('\n', f);
    }
    return sss_atomic_close(f, tmp, path, err);
}
