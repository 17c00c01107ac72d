/* eval/eval_ref.c — the ground truth of a scene at one size: a cached EXR next to the scene (checked
 * against the scene file's hash in its .json sidecar), or a fresh sss_reference_render that can be
 * saved for committing (half-float EXR + sidecar). */
#include <cjson/cJSON.h>
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "core/file_util.h"
#include "scene/json_reader.h"
#include "eval/eval_internal.h"

static const char *quality_name(sss_reference_quality q) { return q == SSS_REFERENCE_DRAFT ? "draft" : "final"; }

/* "<exr without .exr>.json" */
static int sidecar_path(const char *exr, char *out, size_t cap)
{
    size_t n = strlen(exr);
    if (n < 4 || n + 2 >= cap) return 0;
    memcpy(out, exr, n - 4);
    memcpy(out + n - 4, ".json", 6);
    return 1;
}

/* Reads the sidecar: 1 when it exists and parses; *hash 0 when absent in it; *bounces 1 when absent
 * (references from before interreflection are the single-event integral); *transport 1 when absent
 * (SSS_REFERENCE_TRANSPORT_VERSION). */
static int read_sidecar(const char *exr, uint64_t *hash, char quality[8], int *bounces, int *transport)
{
    *bounces = 1;
    *transport = 1;
    char path[1100];
    *hash = 0;
    snprintf(quality, 8, "unknown");
    if (!sidecar_path(exr, path, sizeof path)) return 0;
    char *text = NULL;
    size_t size = 0;
    if (sss_read_file(path, 1 << 20, &text, &size, NULL) != SSS_OK) return 0;
    /* a sidecar that is not JSON counts as absent (and one whose string is cut at a NUL could pass for
     * another scene's hash) */
    jr r;
    jr_init(&r, path, NULL);
    cJSON *root = NULL;
    sss_result parsed = jr_parse(&r, text, size, &root);
    free(text);
    if (parsed != SSS_OK) return 0;
    const cJSON *h = cJSON_GetObjectItemCaseSensitive(root, "scene_fnv1a64");
    if (cJSON_IsString(h)) *hash = strtoull(h->valuestring, NULL, 16);
    const cJSON *q = cJSON_GetObjectItemCaseSensitive(root, "quality");
    if (cJSON_IsString(q) && (strcmp(q->valuestring, "final") == 0 || strcmp(q->valuestring, "draft") == 0))
        snprintf(quality, 8, "%s", q->valuestring);
    const cJSON *b = cJSON_GetObjectItemCaseSensitive(root, "bounces");
    if (cJSON_IsNumber(b)) *bounces = b->valueint;
    const cJSON *t = cJSON_GetObjectItemCaseSensitive(root, "transport_version");
    if (cJSON_IsNumber(t)) *transport = t->valueint;
    cJSON_Delete(root);
    return 1;
}

/* What the render measured, for the sidecar: CPU seconds (all threads) and the bounces' times. */
typedef struct render_record {
    uint64_t seed;
    double seconds, cpu_seconds;
    sss_reference_stats stats;
} render_record;

/* The text of a file name inside a JSON string: escaped (eval_escaped: no control characters, UTF-8),
 * then quotes and backslashes escaped for JSON. */
static void json_text(FILE *f, const char *text)
{
    char *escaped = eval_escaped(text);
    for (const char *c = escaped ? escaped : ""; *c; c++) {
        if (*c == '"' || *c == '\\') fputc('\\', f);
        fputc(*c, f);
    }
    free(escaped);
}

static sss_result write_sidecar(const char *exr, const sss_eval_scene *es, int w, int h, const char *quality,
                                int bounces, const render_record *rec, sss_error *err)
{
    char path[1100], tmp[4096];
    if (!sidecar_path(exr, path, sizeof path)) return sss_error_set(err, SSS_ERROR_LIMIT, "%s: path too long", exr);
    FILE *f = sss_atomic_open(path, tmp, sizeof tmp, err);
    if (!f) return err ? err->code : SSS_ERROR_IO;
    const char *slash = strrchr(es->path, '/'), *name = slash ? slash + 1 : es->path;
    char tflag[80] = "";
    int n = es->has_time ? snprintf(tflag, sizeof tflag, " --time %g", es->time) : 0;
    if (bounces > 0) n += snprintf(tflag + n, sizeof tflag - (size_t)n, " --bounces %d", bounces);
    if (rec->seed) snprintf(tflag + n, sizeof tflag - (size_t)n, " --seed %" PRIu64, rec->seed);
    fputs("{\n  \"scene\": \"", f);
    json_text(f, name);
    fprintf(f,
            "\",\n  \"scene_fnv1a64\": \"%016" PRIx64 "\",\n  \"width\": %d,\n  \"height\": %d,\n"
            "  \"time\": %.17g,\n  \"quality\": \"%s\",\n  \"bounces\": %d,\n  \"transport_version\": %d,\n"
            "  \"seconds\": %.3f,\n"
            "  \"cpu_seconds\": %.3f,\n  \"bounces_done\": %u,\n  \"seconds_per_bounce\": [",
            eval_file_hash(es->path), w, h, es->time, quality, bounces, SSS_REFERENCE_TRANSPORT_VERSION, rec->seconds,
            rec->cpu_seconds, rec->stats.bounces);
    for (uint32_t k = 0; k < rec->stats.bounces && k < SSS_REFERENCE_MAX_BOUNCES; k++)
        fprintf(f, "%s%.3f", k ? ", " : "", rec->stats.seconds_bounce[k]);
    fprintf(f, "],\n  \"seconds_pixels\": %.3f,\n  \"command\": \"sss reference ", rec->stats.seconds_pixels);
    json_text(f, name);
    fprintf(f, "%s -o OUT.exr --quality %s\"\n}\n", tflag, quality);
    return sss_atomic_close(f, tmp, path, err);
}

typedef struct ref_fwd {
    eval_progress *prog;
    char prefix[200];
} ref_fwd;

static void ref_progress(void *user, double fraction, const char *stage)
{
    ref_fwd *f = user;
    char s[256];
    snprintf(s, sizeof s, "%s (%s)", f->prefix, stage ? stage : "");
    eval_progress_update(f->prog, fraction, s);
}

sss_result eval_reference(const sss_scene *view, const sss_eval_scene *es, const sss_eval_desc *desc,
                          eval_progress *prog, sss_eval_reference *ref, sss_image *img, sss_error *err)
{
    return eval_reference_variant(view, es, desc, 0, desc->reference_bounces, prog, ref, img, err);
}

sss_eval_scene eval_variant_scene(const sss_eval_scene *es, const sss_eval_desc *desc, uint64_t seed, int bounces)
{
    /* another seed or another truth is another file: the scene's outputs' name with "_seed<S>" and/or
     * "_bounces<B>" */
    sss_eval_scene named = *es;
    char suffix[64] = "", shown[64] = "";
    int n = 0, m = 0;
    if (seed) {
        n += snprintf(suffix + n, sizeof suffix - (size_t)n, "_seed%" PRIu64, seed);
        m += snprintf(shown + m, sizeof shown - (size_t)m, " (seed %" PRIu64 ")", seed);
    }
    if (bounces != desc->reference_bounces) {
        snprintf(suffix + n, sizeof suffix - (size_t)n, "_bounces%d", bounces);
        snprintf(shown + m, sizeof shown - (size_t)m, " (bounces %d)", bounces);
    }
    if (!suffix[0]) return named;
    snprintf(named.stem, sizeof named.stem, "%.90s%.37s", es->stem, suffix);
    snprintf(named.file_stem, sizeof named.file_stem, "%.90s%.37s", es->file_stem, suffix);
    snprintf(named.name, sizeof named.name, "%.90s%.37s", es->name, shown);
    return named;
}

sss_result eval_reference_variant(const sss_scene *view, const sss_eval_scene *es_given, const sss_eval_desc *desc,
                                  uint64_t seed, int bounces, eval_progress *prog, sss_eval_reference *ref,
                                  sss_image *img, sss_error *err)
{
    sss_eval_scene named = eval_variant_scene(es_given, desc, seed, bounces);
    const sss_eval_scene *es = &named;
    int w = view->camera.width, h = view->camera.height;
    memset(img, 0, sizeof *img);
    ref->width = w;
    ref->height = h;
    ref->source = SSS_EVAL_REF_NONE;
    ref->bounces = bounces;
    char cached[1024];
    int have_name = eval_cached_reference_path(desc, es, w, h, cached, sizeof cached);
    if (desc->cached_reference && have_name) {
        if (access(cached, R_OK) == 0) {
            uint64_t hash = 0;
            char quality[8];
            int cached_bounces, transport;
            int side = read_sidecar(cached, &hash, quality, &cached_bounces, &transport);
            uint64_t now = eval_file_hash(es->path);
            if (side && hash && hash != now) {
                eval_note(prog, "%s: cached reference %s is stale (the scene file changed since it was rendered); "
                                "rendering it", es->name, cached);
            } else if (side && cached_bounces != bounces) {
                eval_note(prog, "%s: cached reference %s has bounces %d (0: full transport), not %d; rendering it",
                          es->name, cached, cached_bounces, bounces);
            } else if (side && cached_bounces != 1 && transport != SSS_REFERENCE_TRANSPORT_VERSION) {
                eval_note(prog, "%s: cached reference %s is stale (rendered by interreflection version %d, now %d); "
                                "rendering it", es->name, cached, transport, SSS_REFERENCE_TRANSPORT_VERSION);
            } else {
                double t0 = sss_time_seconds();
                sss_error rerr = {0};
                if (sss_image_read(cached, img, &rerr) != SSS_OK) {
                    eval_note(prog, "%s: cannot read cached reference (%s); rendering it", es->name, rerr.message);
                } else if (img->width != w || img->height != h) {
                    eval_note(prog, "%s: cached reference %s is %dx%d, not %dx%d; rendering it", es->name, cached,
                              img->width, img->height, w, h);
                    sss_image_free(img);
                } else if (sss_image_count_nonfinite(img) != 0) {
                    eval_note(prog, "%s: cached reference %s holds NaN/Inf; rendering it", es->name, cached);
                    sss_image_free(img);
                } else {
                    ref->source = SSS_EVAL_REF_CACHED;
                    ref->seconds = sss_time_seconds() - t0;
                    snprintf(ref->path, sizeof ref->path, "%s", cached);
                    snprintf(ref->quality, sizeof ref->quality, "%s", quality);
                    if (!side)
                        eval_note(prog, "%s: using cached reference %s (no sidecar: not checked against the scene)",
                                  es->name, cached);
                    return SSS_OK;
                }
            }
        } else {
            eval_note(prog, "%s: no cached reference %s; rendering it (%s quality)", es->name, cached,
                      quality_name(desc->reference_quality));
        }
    }
    sss_reference_desc rd;
    memset(&rd, 0, sizeof rd);
    rd.quality = desc->reference_quality;
    rd.threads = desc->reference_threads;
    rd.time = es->time;
    rd.bounces = bounces;
    rd.seed = seed;
    ref_fwd fwd;
    fwd.prog = prog;
    snprintf(fwd.prefix, sizeof fwd.prefix, "%.120s %dx%d: reference", es->name, w, h);
    double t0 = sss_time_seconds();
    clock_t c0 = clock();
    sss_error rerr = {0};
    render_record rec;
    memset(&rec, 0, sizeof rec);
    rec.seed = seed;
    if (sss_reference_render(view, &rd, img, ref_progress, &fwd, &rec.stats, &rerr) != SSS_OK) {
        snprintf(ref->error, sizeof ref->error, "%s", rerr.message);
        eval_note(prog, "%s: reference failed: %s", es->name, rerr.message);
        sss_image_free(img);
        return SSS_OK;
    }
    ref->seconds = rec.seconds = sss_time_seconds() - t0;
    rec.cpu_seconds = (double)(clock() - c0) / CLOCKS_PER_SEC;
    ref->source = SSS_EVAL_REF_RENDERED;
    snprintf(ref->quality, sizeof ref->quality, "%s", quality_name(desc->reference_quality));
    if (desc->save_references_dir) {
        char path[1024];
        if (!sss_eval_reference_path(desc->save_references_dir, es->stem, w, h, es->has_time, es->time, path,
                                     sizeof path))
            return sss_error_set(err, SSS_ERROR_LIMIT, "%s: reference path too long", desc->save_references_dir);
        sss_result r = eval_make_dirs(desc->save_references_dir, err);
        if (r != SSS_OK) return r;
        /* Half floats keep the committed files small; a value beyond the half range falls back to float. */
        r = sss_image_write_exr(path, img, 1, err);
        if (r == SSS_ERROR_LIMIT) r = sss_image_write_exr(path, img, 0, err);
        if (r == SSS_OK) r = write_sidecar(path, es, w, h, ref->quality, ref->bounces, &rec, err);
        if (r != SSS_OK) return r;
        snprintf(ref->path, sizeof ref->path, "%s", path);
    }
    return SSS_OK;
}
