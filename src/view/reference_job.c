/* view/reference_job.c — the CPU reference of the viewer's current view, rendered by a worker thread
 * (sss_reference_render on a scene parsed from the viewer's JSON, so the worker shares nothing with the
 * window's scene), and a small cache of finished references keyed by scene text, time and quality. */
#include <stdlib.h>
#include <string.h>

#include "sss/reference.h"
#include "view/view_internal.h"

struct view_ref_job {
    view_job base; /* first: the thread, and the lock that also guards progress and stage */
    char *json, *base_dir, *name;
    double time;
    int draft;
    double progress; /* under base.lock */
    const char *stage;
    sss_result result; /* written by the worker before it is done */
    sss_error err;
    sss_image image;
};

static void job_free(view_job *base)
{
    view_ref_job *j = (view_ref_job *)base;
    view_job_destroy(&j->base);
    sss_image_free(&j->image);
    free(j->json);
    free(j->base_dir);
    free(j->name);
    free(j);
}

static void on_progress(void *user, double fraction, const char *stage)
{
    view_ref_job *j = user;
    pthread_mutex_lock(&j->base.lock);
    j->progress = fraction;
    j->stage = stage;
    pthread_mutex_unlock(&j->base.lock);
}

static void worker(view_job *base)
{
    view_ref_job *j = (view_ref_job *)base;
    sss_error err = {0};
    sss_image img = {0};
    sss_scene scene;
    sss_result res = sss_scene_parse(j->json, strlen(j->json), j->base_dir, j->name, NULL, &scene, &err);
    if (res == SSS_OK) {
        sss_reference_desc d;
        memset(&d, 0, sizeof d);
        d.quality = j->draft ? SSS_REFERENCE_DRAFT : SSS_REFERENCE_FINAL;
        d.time = j->time;
        res = sss_reference_render(&scene, &d, &img, on_progress, j, NULL, &err);
        sss_scene_free(&scene);
    }
    j->result = res;
    j->err = err;
    j->image = img;
}

char *view_dup_str(const char *s)
{
    if (!s) s = "";
    char *d = malloc(strlen(s) + 1);
    if (d) strcpy(d, s);
    return d;
}

sss_result view_ref_start(const char *json, const char *base_dir, const char *name, double time, int draft,
                          view_ref_job **out, sss_error *err)
{
    *out = NULL;
    view_ref_job *j = calloc(1, sizeof *j);
    if (!j) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (reference job)");
    j->json = view_dup_str(json);
    j->base_dir = view_dup_str(base_dir ? base_dir : ".");
    j->name = view_dup_str(name ? name : "scene");
    j->time = time;
    j->draft = draft;
    j->stage = "setup";
    sss_result res = view_job_init(&j->base, worker, job_free, err);
    if (res == SSS_OK && (!j->json || !j->base_dir || !j->name))
        res = sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (reference job)");
    if (res == SSS_OK) res = view_job_start(&j->base, err);
    if (res != SSS_OK) {
        job_free(&j->base);
        return res;
    }
    *out = j;
    return SSS_OK;
}

int view_ref_poll(view_ref_job *j, double *progress, const char **stage)
{
    pthread_mutex_lock(&j->base.lock);
    int done = j->base.done;
    if (progress) *progress = j->progress;
    if (stage) *stage = j->stage;
    pthread_mutex_unlock(&j->base.lock);
    return done;
}

sss_result view_ref_finish(view_ref_job *j, sss_image *image, sss_error *err)
{
    view_job_join(&j->base);
    sss_result res = j->result;
    if (res == SSS_OK) {
        *image = j->image;
        memset(&j->image, 0, sizeof j->image);
    } else if (err) {
        *err = j->err;
    }
    job_free(&j->base);
    return res;
}

void view_ref_abandon(view_ref_job *j)
{
    if (j) view_job_abandon(&j->base);
}

/* ---- Cache ---------------------------------------------------------------------------------- */

const sss_image *view_ref_cache_find(view_ref_cache *c, const char *key)
{
    for (int i = 0; i < VIEW_REF_CACHE; i++)
        if (c->keys[i] && strcmp(c->keys[i], key) == 0) return &c->images[i];
    return NULL;
}

sss_result view_ref_cache_put(view_ref_cache *c, const char *key, sss_image *image, sss_error *err)
{
    char *k = view_dup_str(key);
    if (!k) {
        sss_image_free(image);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (reference cache)");
    }
    /* Drop the oldest (last) entry and shift: the newest is first. */
    free(c->keys[VIEW_REF_CACHE - 1]);
    sss_image_free(&c->images[VIEW_REF_CACHE - 1]);
    memmove(&c->keys[1], &c->keys[0], sizeof c->keys[0] * (VIEW_REF_CACHE - 1));
    memmove(&c->images[1], &c->images[0], sizeof c->images[0] * (VIEW_REF_CACHE - 1));
    c->keys[0] = k;
    c->images[0] = *image;
    memset(image, 0, sizeof *image);
    return SSS_OK;
}

void view_ref_cache_free(view_ref_cache *c)
{
    for (int i = 0; i < VIEW_REF_CACHE; i++) {
        free(c->keys[i]);
        sss_image_free(&c->images[i]);
    }
    memset(c, 0, sizeof *c);
}
