/* view/build_job.c — the CPU part of a material edit on a worker thread: the edited scene JSON through
 * the loader (PBD tables, materials, meshes), then the renderer's CPU tables for it (sss_gl_tables_build:
 * the kernel LUTs) under the technique and parameters the window will create its renderer with. The
 * worker owns copies of everything it reads, so the window keeps drawing its old scene meanwhile and
 * only uploads (view_build_finish hands the scene and tables over). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "view/view_internal.h"

struct view_build_job {
    view_job base; /* first: the thread */
    char *json, *base_dir, *name;
    sss_gl_renderer_desc desc;
    sss_gl_param_value *params;
    char (*param_names)[64];
    double delay_s;
    sss_result result; /* results: written by the worker before it is done */
    sss_error err;
    sss_scene *scene;
    sss_gl_tables *tables;
    double scene_ms, tables_ms;
};

static void job_free(view_job *base)
{
    view_build_job *j = (view_build_job *)base;
    view_job_destroy(&j->base);
    if (j->scene) sss_scene_free(j->scene);
    free(j->scene);
    sss_gl_tables_free(j->tables);
    free(j->json);
    free(j->base_dir);
    free(j->name);
    free(j->params);
    free(j->param_names);
    free(j);
}

static void sleep_seconds(double s)
{
    struct timespec ts = {(time_t)s, (long)((s - (double)(time_t)s) * 1e9)};
    nanosleep(&ts, NULL);
}

static sss_result build(view_build_job *j, sss_error *err)
{
    if (j->delay_s > 0.0) sleep_seconds(j->delay_s); /* test hook: a slow build, the window must not wait */
    double start = sss_time_seconds();
    j->scene = calloc(1, sizeof *j->scene);
    if (!j->scene) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (scene)");
    sss_result res = sss_scene_parse(j->json, strlen(j->json), j->base_dir, j->name, NULL, j->scene, err);
    if (res != SSS_OK) {
        free(j->scene);
        j->scene = NULL;
        return res;
    }
    double parsed = sss_time_seconds();
    res = sss_gl_tables_build(j->scene, &j->desc, &j->tables, err);
    j->scene_ms = 1000.0 * (parsed - start);
    j->tables_ms = 1000.0 * (sss_time_seconds() - parsed);
    return res;
}

static void worker(view_job *base)
{
    view_build_job *j = (view_build_job *)base;
    j->result = build(j, &j->err);
}

/* The desc with its own copy of the parameter names (the viewer's may change while the worker runs). */
static int copy_desc(view_build_job *j, const sss_gl_renderer_desc *desc)
{
    j->desc = *desc;
    int n = desc->param_count;
    j->params = calloc((size_t)(n > 0 ? n : 1), sizeof *j->params);
    j->param_names = calloc((size_t)(n > 0 ? n : 1), sizeof *j->param_names);
    if (!j->params || !j->param_names) return 0;
    for (int i = 0; i < n; i++) {
        snprintf(j->param_names[i], sizeof j->param_names[i], "%s", desc->params[i].name ? desc->params[i].name : "");
        j->params[i].name = j->param_names[i];
        j->params[i].value = desc->params[i].value;
    }
    j->desc.params = j->params; /* desc->technique: a registry name, a static string */
    j->desc.tables = NULL;
    return 1;
}

sss_result view_build_start(const char *json, const char *base_dir, const char *name,
                            const sss_gl_renderer_desc *desc, double delay_s, view_build_job **out, sss_error *err)
{
    *out = NULL;
    view_build_job *j = calloc(1, sizeof *j);
    if (!j) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (build job)");
    j->json = view_dup_str(json);
    j->base_dir = view_dup_str(base_dir ? base_dir : ".");
    j->name = view_dup_str(name ? name : "scene");
    j->delay_s = delay_s;
    sss_result res = view_job_init(&j->base, worker, job_free, err);
    if (res == SSS_OK && (!j->json || !j->base_dir || !j->name || !copy_desc(j, desc)))
        res = sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (build job)");
    if (res == SSS_OK) res = view_job_start(&j->base, err);
    if (res != SSS_OK) {
        job_free(&j->base);
        return res;
    }
    *out = j;
    return SSS_OK;
}

int view_build_poll(view_build_job *j) { return view_job_done(&j->base); }

sss_result view_build_finish(view_build_job *j, view_build_result *out, sss_error *err)
{
    view_job_join(&j->base);
    memset(out, 0, sizeof *out);
    sss_result res = j->result;
    if (res == SSS_OK) {
        out->scene = j->scene;
        out->tables = j->tables;
        out->scene_ms = j->scene_ms;
        out->tables_ms = j->tables_ms;
        j->scene = NULL;
        j->tables = NULL;
    } else if (err) {
        *err = j->err;
    }
    job_free(&j->base);
    return res;
}

void view_build_abandon(view_build_job *j)
{
    if (j) view_job_abandon(&j->base);
}

void view_build_result_free(view_build_result *r)
{
    if (r->scene) sss_scene_free(r->scene);
    free(r->scene);
    sss_gl_tables_free(r->tables);
    memset(r, 0, sizeof *r);
}
