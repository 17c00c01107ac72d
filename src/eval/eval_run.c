/* eval/eval_run.c — the evaluation loop: scenes x quality sizes x techniques (+ reference, + the SAM
 * sweep of Maisch & Ropinski 2017, Fig. 10), then timing-only sizes. Failures of a technique become entries. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "eval/eval_internal.h"

/* Work units: one unit = one technique frame of one pixel (techniques cost about the same order on
 * llvmpipe); a final reference costs about ten such frames, a draft one a quarter of that. The
 * fractions only drive the progress bar's ETA. */
#define REF_FINAL_UNITS 10.0
#define REF_DRAFT_UNITS 2.5

static sss_result validate(const sss_eval_desc *d, int scene_count, sss_error *err)
{
    if (scene_count < 1) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "eval: no scenes");
    if (d->frames < 0 || d->frames > 10000)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "eval: frames must be in 1..10000, got %d", d->frames);
    if (d->warmup_frames < -1 || d->warmup_frames > 10000)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "eval: warmup_frames must be in -1..10000, got %d",
                             d->warmup_frames);
    if (!(d->frame_budget_s >= 0 && d->frame_budget_s <= 1e6))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "eval: frame_budget_s must be in 0..1e6 seconds, got %g",
                             d->frame_budget_s);
    if (d->resolution_count < 0 || d->resolution_count > EVAL_MAX_QUALITY_SIZES)
        return sss_error_set(err, SSS_ERROR_LIMIT, "eval: at most %d quality resolutions", EVAL_MAX_QUALITY_SIZES);
    if (d->supersample < 0 || d->supersample > SSS_GL_MAX_SUPERSAMPLE)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "eval: supersample must be in 1..%d (0: 1, off), got %d",
                             SSS_GL_MAX_SUPERSAMPLE, d->supersample);
    if (d->timing_resolution_count < 0 || d->technique_count < 0 || d->sam_count_count < 0)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "eval: negative count");
    const sss_eval_size *lists[2] = {d->resolutions, d->timing_resolutions};
    int counts[2] = {d->resolution_count, d->timing_resolution_count};
    for (int l = 0; l < 2; l++)
        for (int i = 0; i < counts[l]; i++)
            if (!lists[l] || lists[l][i].width < 11 || lists[l][i].height < 11 ||
                lists[l][i].width > SSS_SCENE_MAX_IMAGE_SIZE || lists[l][i].height > SSS_SCENE_MAX_IMAGE_SIZE)
                return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "eval: image sizes must be in 11..%d",
                                     SSS_SCENE_MAX_IMAGE_SIZE);
    for (int i = 0; i < d->technique_count; i++) {
        if (!d->techniques || !d->techniques[i])
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "eval: technique %d is NULL", i);
        sss_result r = sss_eval_check_spec(d->techniques[i], err);
        if (r != SSS_OK) return r;
    }
    for (int i = 0; i < d->sam_count_count; i++)
        if (!d->sam_counts || d->sam_counts[i] < 1)
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "eval: SAM sample counts must be >= 1");
    return eval_external_validate(d, scene_count, err);
}

/* "path.json@T" -> path and time (the suffix counts only when it is a finite number). */
static sss_result split_scene_arg(const char *arg, sss_eval_scene *s, sss_error *err)
{
    const char *at = strrchr(arg, '@');
    size_t len = strlen(arg);
    s->time = 0.0;
    s->has_time = 0;
    if (at && at[1]) {
        char *end = NULL;
        double t = strtod(at + 1, &end);
        if (end != at + 1 && *end == '\0' && isfinite(t)) {
            s->time = t;
            s->has_time = 1;
            len = (size_t)(at - arg);
        }
    }
    s->path = malloc(len + 1);
    if (!s->path) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory");
    memcpy(s->path, arg, len);
    s->path[len] = '\0';
    const char *slash = strrchr(s->path, '/');
    const char *base = slash ? slash + 1 : s->path;
    const char *dot = strrchr(base, '.');
    int stem_len = dot && dot != base ? (int)(dot - base) : (int)strlen(base);
    snprintf(s->file_stem, sizeof s->file_stem, "%.*s", stem_len, base);
    eval_escape(s->file_stem, s->stem, sizeof s->stem);
    return SSS_OK;
}

/* The part of the scene's output names after "sheet_" and before ".png" (and the same in crops_*),
 * for the scene with the given stem: the stem and the time. Two scenes with one key would write the
 * same files. */
static void output_key(const sss_eval_scene *s, const char *stem, char *out, size_t cap)
{
    if (s->has_time) snprintf(out, cap, "%s_t%g", stem, s->time);
    else snprintf(out, cap, "%s", stem);
}

static int same_key(const sss_eval_scene *a, const char *stem_a, const sss_eval_scene *b, const char *stem_b)
{
    char ka[200], kb[200];
    output_key(a, stem_a, ka, sizeof ka);
    output_key(b, stem_b, kb, sizeof kb);
    return strcmp(ka, kb) == 0;
}

/* "<file_stem>-<the last `depth` folder names of the scene file's folder, joined by '-'>" into out,
 * escaped (the folder resolved, so that "s.json" and "../d/s.json" show their folder's name; as given
 * when it cannot be resolved). Returns 0 when the folder has fewer than depth names. */
static int suffixed_stem(const sss_eval_scene *s, int depth, char *out, size_t cap)
{
    char *real = realpath(s->path, NULL);
    const char *dir = real ? real : s->path;
    const char *start = strrchr(dir, '/');
    int ok = start != NULL;
    for (int d = 0; ok && d < depth; d++) { /* start: at the '/' before the names taken so far */
        const char *end = start;
        while (start > dir && start[-1] != '/') start--;
        ok = start < end;
        if (ok && d + 1 < depth) ok = start-- > dir;
    }
    char *raw = ok ? malloc(strlen(s->file_stem) + strlen(start) + 2) : NULL;
    if (raw) {
        sprintf(raw, "%s-%.*s", s->file_stem, (int)(strrchr(dir, '/') - start), start);
        for (char *c = raw + strlen(s->file_stem); *c; c++)
            if (*c == '/') *c = '-';
        eval_escape(raw, out, cap);
    }
    free(raw);
    free(real);
    return raw != NULL;
}

/* A scene whose outputs would share their names with another's (the same file stem and time:
 * d1/s.json and d2/s.json) is told apart by its folders: stems "s-d1" and "s-d2", with as many folder
 * names as it takes. The same file given twice at one time, and names that stay equal, are refused
 * before any work. */
static sss_result distinct_names(sss_eval_scene *sc, int n, sss_error *err)
{
    for (int i = 0; i < n; i++) {
        int clash = 0;
        for (int j = 0; j < n && !clash; j++)
            clash = j != i && same_key(&sc[i], sc[i].file_stem, &sc[j], sc[j].file_stem);
        char mine[128], other[128];
        for (int depth = 1; clash && suffixed_stem(&sc[i], depth, mine, sizeof mine); depth++) {
            int unique = 1;
            for (int j = 0; j < n && unique; j++)
                unique = j == i || !same_key(&sc[i], sc[i].file_stem, &sc[j], sc[j].file_stem) ||
                         !suffixed_stem(&sc[j], depth, other, sizeof other) || !same_key(&sc[i], mine, &sc[j], other);
            if (unique) {
                snprintf(sc[i].stem, sizeof sc[i].stem, "%s", mine);
                clash = 0;
            }
        }
    }
    for (int i = 0; i < n; i++)
        for (int j = 0; j < i; j++)
            if (same_key(&sc[i], sc[i].stem, &sc[j], sc[j].stem))
                return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                                     "scenes %s and %s would write the same output files (sheet_%s.png, "
                                     "references/%s_*.exr): give a scene once per time, or rename one",
                                     sc[j].path, sc[i].path, sc[i].stem, sc[i].stem);
    for (int i = 0; i < n; i++) {
        if (sc[i].has_time) snprintf(sc[i].name, sizeof sc[i].name, "%.100s@%g", sc[i].stem, sc[i].time);
        else snprintf(sc[i].name, sizeof sc[i].name, "%s", sc[i].stem);
    }
    return SSS_OK;
}

static void utc_now(char out[32])
{
    time_t now = time(NULL);
    struct tm tmv;
    if (gmtime_r(&now, &tmv)) strftime(out, 32, "%Y-%m-%dT%H:%M:%SZ", &tmv);
    else snprintf(out, 32, "unknown");
}

/* A sized view of a loaded scene (shares its data; never freed). */
static sss_result sized_view(const sss_scene *scene, int w, int h, sss_scene *view, sss_error *err)
{
    *view = *scene;
    view->camera.width = w;
    view->camera.height = h;
    return sss_camera_basis_init(&view->camera, &view->basis, err);
}

typedef struct run_state {
    const sss_eval_desc *desc;
    sss_eval_results *res;
    sss_scene *scenes;
    eval_spec *specs;
    eval_gl rc;
    eval_progress prog;
    const int *sam_counts;
    int sam_count_n;
    const sss_gl_param_info *sam_param;
    int sam_spec; /* index of the spec the sweep starts from (the first "sam" spec), -1 for plain sam */
    int counts_buf[64];
    int nt;                 /* technique specs: the first nt labels (the external images follow) */
    sss_image *ext_images;  /* scene si's image of source j at [si * image_count + j], until moved to its entry */
    char (*ext_paths)[1024];
} run_state;

static sss_result add_result(run_state *st, const sss_eval_entry *e)
{
    sss_eval_entry *dst = eval_add_entry(st->res);
    if (!dst) return sss_error_set(NULL, SSS_ERROR_OUT_OF_MEMORY, "out of memory");
    *dst = *e;
    return SSS_OK;
}

/* Renders technique i on the view of scene si at one size into a fresh entry e of the given kind
 * (frames, timings, image; the progress advances by its work). */
static sss_result run_entry(run_state *st, const sss_scene *view, int si, int i, sss_eval_size size, sss_eval_kind kind,
                            sss_eval_entry *e)
{
    const sss_eval_scene *es = &st->res->scenes[si];
    memset(e, 0, sizeof *e);
    e->scene = si;
    e->kind = kind;
    snprintf(e->label, sizeof e->label, "%s", st->res->labels[i]);
    snprintf(e->technique, sizeof e->technique, "%s", st->specs[i].name);
    e->width = size.width;
    e->height = size.height;
    char stage[256];
    snprintf(stage, sizeof stage, "%.100s %dx%d%s: %.120s", es->name, size.width, size.height,
             kind == SSS_EVAL_TIMING ? " (timing)" : "", e->label);
    st->prog.step = (st->rc.frames + st->rc.warmup_frames + 1.0) * size.width * size.height;
    sss_result r = eval_run_technique(&st->rc, view, es->time, &st->specs[i], st->specs[i].param_count, st->rc.frames, e,
                                      stage);
    eval_progress_finish_step(&st->prog);
    return r;
}

/* Clears the ids of objects that are not subsurface: the silhouette crops look at the edges of the
 * translucent objects (against the background, the ground and each other), not at a horizon. */
static void keep_subsurface_ids(const sss_scene *scene, sss_image *ids)
{
    size_t n = ids->pixels ? (size_t)ids->width * (size_t)ids->height * 3 : 0;
    for (size_t i = 0; i < n; i++) {
        float id = ids->pixels[i];
        size_t obj = id >= 1.0f ? (size_t)id - 1 : scene->object_count;
        if (obj >= scene->object_count || scene->objects[obj].material.type != SSS_SCENE_MATERIAL_SUBSURFACE)
            ids->pixels[i] = 0.0f;
    }
}

/* The first quality size's other references: seed 1 (sss_eval_desc.reference_noise) and the single-event
 * truth (sss_eval_desc.both_truths); images empty when not asked or unavailable. */
typedef struct extra_refs {
    sss_image seed1, single_event;
} extra_refs;

/* Compares an entry's image with the reference: metrics, mean ratios, and the maps at the first size (k = 0). */
static void score_entry(const sss_eval_scene *es, const sss_image *ref, int k, sss_eval_entry *e)
{
    if (!e->ok || !ref->pixels) return;
    sss_error cerr = {0};
    sss_image map = {0}, flip_map = {0};
    if (sss_image_compare_maps(ref, &e->image, es->exposure, &e->metrics, k == 0 ? &map : NULL,
                               k == 0 ? &flip_map : NULL, &cerr) == SSS_OK) {
        e->has_metrics = 1;
        e->dssim_map = map;
        e->flip_map = flip_map;
        eval_mean_ratio(&e->image, ref, e->mean_ratio);
    } else {
        eval_fail_entry(e, cerr.message);
    }
}

/* The entry (scored against the main truth) against the other references: the seed-to-seed noise as
 * this technique sees it (how much its metrics move when the reference is rendered with another seed;
 * the scene's noise is the largest over the techniques), and its scores against the single-event truth. */
static void score_extra(sss_eval_scene *es, const extra_refs *x, sss_eval_entry *e)
{
    if (!e->has_metrics) return;
    sss_image_metrics m1;
    if (x->seed1.pixels) {
        if (sss_image_compare_maps(&x->seed1, &e->image, es->exposure, &m1, NULL, NULL, NULL) != SSS_OK) {
            es->has_noise = 0; /* unknown for this one: no claim for the scene */
        } else {
            es->noise_dssim = fmax(es->noise_dssim, fabs(m1.dssim - e->metrics.dssim));
            es->noise_flip = fmax(es->noise_flip, fabs(m1.flip - e->metrics.flip));
        }
    }
    if (x->single_event.pixels &&
        sss_image_compare_maps(&x->single_event, &e->image, es->exposure, &e->single_event, NULL, NULL, NULL) == SSS_OK) {
        e->has_single_event = 1;
        eval_mean_ratio(&e->image, &x->single_event, e->single_event_ratio);
    }
}

/* The external images of scene si (at its first quality size) as entries. */
static sss_result add_external_entries(run_state *st, int si, const sss_image *ref, const extra_refs *x)
{
    sss_eval_results *res = st->res;
    for (int j = 0; j < res->external_count; j++) {
        sss_eval_entry e;
        size_t at = (size_t)si * (size_t)res->external_count + (size_t)j;
        eval_external_entry(si, res->labels[st->nt + j], st->ext_paths[at], &st->ext_images[at], &e);
        score_entry(&res->scenes[si], ref, 0, &e);
        score_extra(&res->scenes[si], x, &e);
        if (!e.ok) sss_image_free(&e.image);
        if (add_result(st, &e) != SSS_OK) {
            sss_image_free(&e.image);
            sss_image_free(&e.dssim_map);
            sss_image_free(&e.flip_map);
            return SSS_ERROR_OUT_OF_MEMORY;
        }
    }
    return SSS_OK;
}

/* Work units of a reference: almost none when a cached file will be read (es named as the file). */
static double reference_units(const run_state *st, const sss_eval_scene *es, int w, int h)
{
    const sss_eval_desc *d = st->desc;
    double px = (double)w * h;
    if (d->cached_reference) {
        char path[1024];
        if (eval_cached_reference_path(d, es, w, h, path, sizeof path) && access(path, R_OK) == 0)
            return 0.01 * px;
    }
    return px * (d->reference_quality == SSS_REFERENCE_DRAFT ? REF_DRAFT_UNITS : REF_FINAL_UNITS);
}

/* The units of the first size's other references (extra_refs). */
static double extra_units(const run_state *st, const sss_eval_scene *es, int w, int h)
{
    const sss_eval_desc *d = st->desc;
    sss_eval_scene v[2] = {eval_variant_scene(es, d, 1, d->reference_bounces), eval_variant_scene(es, d, 0, 1)};
    return (d->reference_noise ? reference_units(st, &v[0], w, h) : 0.0) +
           (d->both_truths ? reference_units(st, &v[1], w, h) : 0.0);
}

/* Renders (or reads) the first size's other references into x; errors are the run's (saving, memory). */
static sss_result extra_references(run_state *st, const sss_scene *view, sss_eval_scene *es, extra_refs *x,
                                   sss_error *err)
{
    const sss_eval_desc *d = st->desc;
    memset(x, 0, sizeof *x);
    sss_result r = SSS_OK;
    if (d->reference_noise) {
        sss_eval_reference rf1;
        memset(&rf1, 0, sizeof rf1);
        sss_eval_scene v = eval_variant_scene(es, d, 1, d->reference_bounces);
        st->prog.step = reference_units(st, &v, view->camera.width, view->camera.height);
        r = eval_reference_variant(view, es, d, 1, d->reference_bounces, &st->prog, &rf1, &x->seed1, err);
        eval_progress_finish_step(&st->prog);
        es->has_noise = r == SSS_OK && x->seed1.pixels;
    }
    if (r == SSS_OK && d->both_truths) {
        sss_eval_scene v = eval_variant_scene(es, d, 0, 1);
        st->prog.step = reference_units(st, &v, view->camera.width, view->camera.height);
        r = eval_reference_variant(view, es, d, 0, 1, &st->prog, &es->single_event_reference, &x->single_event, err);
        eval_progress_finish_step(&st->prog);
    }
    return r;
}

static void free_extra(extra_refs *x)
{
    sss_image_free(&x->seed1);
    sss_image_free(&x->single_event);
}

static sss_result run_quality_size(run_state *st, int si, int k, sss_eval_size size, sss_error *err)
{
    sss_eval_results *res = st->res;
    sss_eval_scene *es = &res->scenes[si];
    sss_scene view;
    sss_result r = sized_view(&st->scenes[si], size.width, size.height, &view, err);
    if (r != SSS_OK) return r;
    sss_image ref = {0};
    /* reference */
    sss_eval_reference *rf = &es->references[k];
    r = eval_reference(&view, es, st->desc, &st->prog, rf, &ref, err);
    es->reference_count = k + 1;
    eval_progress_finish_step(&st->prog);
    if (r != SSS_OK) return r;
    extra_refs x;
    memset(&x, 0, sizeof x);
    if (k == 0 && (r = extra_references(st, &view, es, &x, err)) != SSS_OK) {
        free_extra(&x);
        sss_image_free(&ref);
        return r;
    }
    if (k == 0) es->has_noise = es->has_noise && ref.pixels;
    sss_eval_entry e;
    for (int i = 0; i < st->nt; i++) {
        st->rc.object_ids = k == 0 ? &es->object_ids : NULL;
        r = run_entry(st, &view, si, i, size, SSS_EVAL_QUALITY, &e);
        st->rc.object_ids = NULL;
        if (k == 0) keep_subsurface_ids(&st->scenes[si], &es->object_ids);
        if (r == SSS_OK) score_entry(es, &ref, k, &e);
        score_extra(es, &x, &e);
        if (k != 0 || !e.ok) sss_image_free(&e.image);
        if (r == SSS_OK) r = add_result(st, &e);
        if (r != SSS_OK) {
            sss_image_free(&e.image);
            sss_image_free(&e.dssim_map);
            sss_image_free(&e.flip_map);
            sss_image_free(&ref);
            free_extra(&x);
            return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory");
        }
    }
    if (k == 0 && add_external_entries(st, si, &ref, &x) != SSS_OK) {
        sss_image_free(&ref);
        free_extra(&x);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory");
    }
    free_extra(&x);
    /* the SAM sweep at the first quality size (Maisch & Ropinski 2017, Fig. 10: RMSE against back-side samples) */
    if (k == 0 && res->sam_swept) {
        eval_spec spec;
        if (st->sam_spec >= 0) spec = st->specs[st->sam_spec];
        else eval_parse_spec("sam", &spec, NULL);
        /* the count replaces a value the spec may give */
        int np = 0;
        for (int i = 0; i < spec.param_count; i++)
            if (strcmp(spec.names[i], st->sam_param->name) != 0) {
                memmove(spec.names[np], spec.names[i], sizeof spec.names[0]);
                spec.params[np].value = spec.params[i].value;
                np++;
            }
        for (int i = 0; i < np; i++) spec.params[i].name = spec.names[i];
        spec.param_count = np;
        for (int c = 0; c < st->sam_count_n; c++) {
            int n = st->sam_counts[c];
            memset(&e, 0, sizeof e);
            e.scene = si;
            e.kind = SSS_EVAL_SAM_SWEEP;
            e.sam_n = n;
            snprintf(e.technique, sizeof e.technique, "sam");
            snprintf(e.label, sizeof e.label, "sam:%s=%d", st->sam_param->name, n);
            e.width = size.width;
            e.height = size.height;
            spec.params[np].name = st->sam_param->name;
            spec.params[np].value = n;
            char stage[256];
            snprintf(stage, sizeof stage, "%s %dx%d: SAM sweep %s = %d", es->name, size.width, size.height,
                     st->sam_param->name, n);
            st->prog.step = 2.0 * size.width * size.height;
            r = eval_run_technique(&st->rc, &view, es->time, &spec, np + 1, 1, &e, stage);
            eval_progress_finish_step(&st->prog);
            if (r == SSS_OK && e.ok && ref.pixels) {
                sss_error cerr = {0};
                if (sss_image_compare(&ref, &e.image, es->exposure, &e.metrics, NULL, &cerr) == SSS_OK)
                    e.has_metrics = 1;
                else eval_fail_entry(&e, cerr.message);
            }
            sss_image_free(&e.image);
            if (r == SSS_OK) r = add_result(st, &e);
            if (r != SSS_OK) {
                sss_image_free(&ref);
                return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory");
            }
        }
    }
    if (k == 0) es->reference = ref;
    else sss_image_free(&ref);
    return SSS_OK;
}

static sss_result run_timing_size(run_state *st, int si, sss_eval_size size, sss_error *err)
{
    sss_scene view;
    sss_result r = sized_view(&st->scenes[si], size.width, size.height, &view, err);
    if (r != SSS_OK) return r;
    for (int i = 0; i < st->nt; i++) {
        sss_eval_entry e;
        r = run_entry(st, &view, si, i, size, SSS_EVAL_TIMING, &e);
        sss_image_free(&e.image);
        if (r == SSS_OK) r = add_result(st, &e);
        if (r != SSS_OK) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory");
    }
    return SSS_OK;
}

/* Plans the work units (for the progress fraction). */
static double plan_units(run_state *st)
{
    const sss_eval_desc *d = st->desc;
    double units = 0;
    for (int si = 0; si < st->res->scene_count; si++) {
        const sss_eval_scene *es = &st->res->scenes[si];
        int nq = d->resolution_count ? d->resolution_count : 1;
        for (int k = 0; k < nq; k++) {
            int w = d->resolution_count ? d->resolutions[k].width : es->width;
            int h = d->resolution_count ? d->resolutions[k].height : es->height;
            double px = (double)w * h;
            units += reference_units(st, es, w, h);
            units += st->nt * (st->rc.frames + st->rc.warmup_frames + 1.0) * px;
            if (k == 0) units += extra_units(st, es, w, h);
            if (k == 0 && st->res->sam_swept) units += st->sam_count_n * 2.0 * px;
        }
        for (int k = 0; k < d->timing_resolution_count; k++)
            units += st->nt * (st->rc.frames + st->rc.warmup_frames + 1.0) * d->timing_resolutions[k].width *
                     (double)d->timing_resolutions[k].height;
    }
    return units;
}

/* The external images not moved into entries (all of them after a failure). */
static void free_external(run_state *st, int scene_count)
{
    for (size_t i = 0; st->ext_images && i < (size_t)scene_count * (size_t)st->desc->image_count; i++)
        sss_image_free(&st->ext_images[i]);
    free(st->ext_images);
    free(st->ext_paths);
}

sss_result sss_eval_run(const char *const *scene_args, int scene_count, const sss_eval_desc *desc_in,
                        const sss_eval_callbacks *cb, sss_eval_results *out, sss_error *err)
{
    if (!out) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sss_eval_run: out is NULL");
    memset(out, 0, sizeof *out);
    sss_eval_desc desc;
    memset(&desc, 0, sizeof desc);
    if (desc_in) desc = *desc_in;
    sss_result r = validate(&desc, scene_count, err);
    if (r != SSS_OK) return r;
    if (!scene_args) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sss_eval_run: no scenes");
    if (desc.reference_bounces < 0 || desc.reference_bounces > SSS_REFERENCE_MAX_BOUNCES)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sss_eval_run: reference_bounces must be in 0..%d, got %d",
                             SSS_REFERENCE_MAX_BOUNCES, desc.reference_bounces);
    if (desc.both_truths && desc.reference_bounces == 1)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                             "sss_eval_run: both_truths adds the single-event truth (bounces 1) to the main one, "
                             "which is already bounces 1");
    double t_start = sss_time_seconds();
    run_state st;
    memset(&st, 0, sizeof st);
    st.desc = &desc;
    st.res = out;
    st.prog.cb = cb;
    st.rc.prog = &st.prog;
    st.rc.frames = desc.frames ? desc.frames : SSS_GL_TIMED_FRAMES;
    st.rc.warmup_frames = desc.warmup_frames == 0 ? SSS_GL_WARMUP_FRAMES : desc.warmup_frames < 0 ? 0 : desc.warmup_frames;
    out->frames = st.rc.frames;
    out->warmup_frames = st.rc.warmup_frames;
    st.rc.frame_budget_s = desc.frame_budget_s;
    out->frame_budget_s = desc.frame_budget_s;
    st.rc.supersample = desc.supersample ? desc.supersample : 1;
    out->supersample = st.rc.supersample;
    out->reference_quality = desc.reference_quality;
    out->cached_reference = desc.cached_reference;
    out->reference_bounces = desc.reference_bounces;
    out->both_truths = desc.both_truths;
    utc_now(out->created);

    /* techniques: the given specs, or every registered one */
    int nl = desc.technique_count ? desc.technique_count : sss_gl_technique_count();
    int ni = desc.image_count;
    st.nt = nl;
    out->labels = calloc((size_t)(nl + ni ? nl + ni : 1), sizeof *out->labels);
    out->external_patterns = calloc((size_t)(ni ? ni : 1), sizeof *out->external_patterns);
    st.ext_images = calloc((size_t)scene_count * (size_t)(ni ? ni : 1), sizeof *st.ext_images);
    st.ext_paths = calloc((size_t)scene_count * (size_t)(ni ? ni : 1), sizeof *st.ext_paths);
    st.specs = calloc((size_t)(nl ? nl : 1), sizeof *st.specs);
    out->scenes = calloc((size_t)scene_count, sizeof *out->scenes);
    st.scenes = calloc((size_t)scene_count, sizeof *st.scenes);
    if (!out->labels || !st.specs || !out->scenes || !st.scenes || !out->external_patterns || !st.ext_images ||
        !st.ext_paths) {
        r = sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory");
        goto fail;
    }
    for (int i = 0; i < nl; i++) {
        const char *spec = desc.technique_count ? desc.techniques[i] : sss_gl_technique_at(i)->name;
        out->labels[i] = eval_escaped(spec); /* shown in sheets and plots: cairo takes UTF-8 only */
        if (!out->labels[i]) {
            r = sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory");
            goto fail;
        }
        out->label_count = i + 1;
        if ((r = eval_parse_spec(spec, &st.specs[i], err)) != SSS_OK) goto fail;
    }
    out->external_count = ni;
    for (int j = 0; j < ni; j++) {
        out->labels[nl + j] = eval_escaped(desc.images[j].name);
        out->external_patterns[j] = eval_escaped(desc.images[j].pattern);
        if (!out->labels[nl + j] || !out->external_patterns[j]) {
            r = sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory");
            goto fail;
        }
        out->label_count = nl + j + 1;
    }

    /* scenes */
    for (int i = 0; i < scene_count; i++) {
        sss_eval_scene *es = &out->scenes[i];
        out->scene_count = i + 1;
        if (!scene_args[i]) {
            r = sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "eval: scene %d is NULL", i);
            goto fail;
        }
        if ((r = split_scene_arg(scene_args[i], es, err)) != SSS_OK) goto fail;
    }
    if ((r = distinct_names(out->scenes, scene_count, err)) != SSS_OK) goto fail;
    for (int i = 0; i < scene_count; i++) {
        sss_eval_scene *es = &out->scenes[i];
        if ((r = sss_scene_load(es->path, NULL, &st.scenes[i], err)) != SSS_OK) goto fail;
        es->width = st.scenes[i].camera.width;
        es->height = st.scenes[i].camera.height;
        es->exposure = st.scenes[i].render.exposure;
        for (size_t o = 0; o < st.scenes[i].object_count; o++) es->triangles += st.scenes[i].objects[o].mesh.triangle_count;
        /* the external images, at the first quality size: a missing or mis-sized one stops the run now */
        sss_eval_size first = desc.resolution_count ? desc.resolutions[0] : (sss_eval_size){es->width, es->height};
        if (ni && (r = eval_external_load(&desc, es, first.width, first.height, st.ext_images + (size_t)i * ni,
                                          st.ext_paths + (size_t)i * ni, err)) != SSS_OK)
            goto fail;
    }

    /* the SAM sweep: needs the technique and its sample-count parameter */
    const sss_gl_technique_info *sam = sss_gl_technique_find("sam");
    st.sam_spec = -1;
    for (int i = 0; i < nl; i++)
        if (strcmp(st.specs[i].name, "sam") == 0) {
            st.sam_spec = i;
            break;
        }
    if (!sam) {
        snprintf(out->sam_note, sizeof out->sam_note, "no technique 'sam' in this build");
    } else if (!(st.sam_param = eval_find_sam_param(sam))) {
        snprintf(out->sam_note, sizeof out->sam_note, "technique sam has no back-side sample count parameter");
    } else {
        out->sam_available = 1;
        snprintf(out->sam_param, sizeof out->sam_param, "%s", st.sam_param->name);
        out->sam_swept = desc.sam_sweep > 0 || (desc.sam_sweep == 0 && st.sam_spec >= 0);
        if (!out->sam_swept) snprintf(out->sam_note, sizeof out->sam_note, "SAM sweep not requested");
    }
    st.sam_counts = desc.sam_count_count ? desc.sam_counts : eval_default_sam_counts;
    int ncounts = desc.sam_count_count ? desc.sam_count_count : EVAL_DEFAULT_SAM_COUNTS;
    if (out->sam_swept) {
        /* counts outside the parameter's range are skipped with a note */
        int m = 0;
        for (int i = 0; i < ncounts && m < 64; i++) {
            if (st.sam_counts[i] < st.sam_param->min_value || st.sam_counts[i] > st.sam_param->max_value) {
                eval_note(&st.prog, "SAM sweep: %s = %d is outside the parameter's range [%g, %g]; skipped",
                          st.sam_param->name, st.sam_counts[i], st.sam_param->min_value, st.sam_param->max_value);
                continue;
            }
            st.counts_buf[m++] = st.sam_counts[i];
        }
        st.sam_counts = st.counts_buf;
        st.sam_count_n = m;
    }

    /* one GL context for the run; without it every technique entry fails with the reason */
    if (nl > 0) {
        sss_error gerr = {0};
        if (sss_gl_context_create(NULL, &st.rc.gl, &gerr) != SSS_OK) {
            snprintf(out->gl_error, sizeof out->gl_error, "no OpenGL context: %.480s", gerr.message);
            st.rc.gl_error = out->gl_error;
            eval_note(&st.prog, "%s (every technique is reported as failed)", out->gl_error);
        } else {
            sss_gl_context_info info;
            sss_gl_context_get_info(st.rc.gl, &info);
            out->gl_ok = 1;
            out->gl_software = info.software;
            snprintf(out->gl_platform, sizeof out->gl_platform, "%s", info.platform ? info.platform : "");
            snprintf(out->gl_renderer, sizeof out->gl_renderer, "%s", info.renderer ? info.renderer : "");
            snprintf(out->gl_version, sizeof out->gl_version, "%s", info.version ? info.version : "");
            snprintf(out->timing_method, sizeof out->timing_method, "%s",
                     info.software ? "glFinish + monotonic clock" : "GL_TIME_ELAPSED queries");
        }
    }

    st.prog.total = plan_units(&st);
    for (int si = 0; si < scene_count; si++) {
        sss_eval_scene *es = &out->scenes[si];
        int nq = desc.resolution_count ? desc.resolution_count : 1;
        for (int k = 0; k < nq; k++) {
            sss_eval_size size = desc.resolution_count ? desc.resolutions[k] : (sss_eval_size){es->width, es->height};
            st.prog.step = reference_units(&st, es, size.width, size.height);
            char stage[256];
            snprintf(stage, sizeof stage, "%s %dx%d: reference", es->name, size.width, size.height);
            eval_progress_update(&st.prog, 0.0, stage);
            if ((r = run_quality_size(&st, si, k, size, err)) != SSS_OK) goto fail;
        }
        for (int k = 0; k < desc.timing_resolution_count; k++)
            if ((r = run_timing_size(&st, si, desc.timing_resolutions[k], err)) != SSS_OK) goto fail;
    }
    /* the method the renderer reported (GL_TIME_ELAPSED on GPUs, glFinish on software GL) */
    if (st.rc.method) snprintf(out->timing_method, sizeof out->timing_method, "%s", st.rc.method);
    st.prog.done = st.prog.total;
    eval_progress_update(&st.prog, 0.0, "done");
    sss_gl_context_destroy(st.rc.gl);
    for (int i = 0; i < scene_count; i++) sss_scene_free(&st.scenes[i]);
    free(st.scenes);
    free(st.specs);
    free_external(&st, scene_count);
    out->seconds = sss_time_seconds() - t_start;
    return SSS_OK;
fail:
    sss_gl_context_destroy(st.rc.gl);
    if (st.scenes)
        for (int i = 0; i < scene_count; i++) sss_scene_free(&st.scenes[i]);
    free(st.scenes);
    free(st.specs);
    free_external(&st, scene_count);
    sss_eval_results_free(out);
    return r;
}
