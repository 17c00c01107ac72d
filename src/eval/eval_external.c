/* eval/eval_external.c — images rendered by other programs (sss_eval_desc.images, `sss eval --images
 * NAME=PATTERN`): checked and read before any work, so that a missing or mis-sized file stops the run
 * at once with its name, then scored as entries marked external (no timings). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "eval/eval_internal.h"

#define SCENE_KEY "{scene}"

sss_result eval_external_validate(const sss_eval_desc *d, int scene_count, sss_error *err)
{
    if (d->image_count < 0 || (d->image_count > 0 && !d->images))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "eval: images: bad count or NULL list");
    for (int j = 0; j < d->image_count; j++) {
        const sss_eval_image_source *s = &d->images[j];
        if (!s->name || !s->name[0] || !s->pattern || !s->pattern[0])
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "eval: images %d: empty name or pattern (NAME=PATTERN)", j);
        if (strlen(s->name) >= SSS_EVAL_LABEL_SIZE)
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "eval: images: name '%.40s...' is longer than %d bytes",
                                 s->name, SSS_EVAL_LABEL_SIZE - 1);
        if (scene_count > 1 && !strstr(s->pattern, SCENE_KEY))
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                                 "eval: images %s=%s: the pattern has no %s, so every scene would be scored against "
                                 "the same file", s->name, s->pattern, SCENE_KEY);
        for (int i = 0; i < d->technique_count; i++)
            if (d->techniques && d->techniques[i] && strcmp(d->techniques[i], s->name) == 0)
                return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                                     "eval: images: '%s' is also a technique of the run; name the images otherwise", s->name);
        for (int k = 0; k < j; k++)
            if (strcmp(d->images[k].name, s->name) == 0)
                return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "eval: images: the name '%s' is given twice", s->name);
    }
    return SSS_OK;
}

/* pattern with every "{scene}" replaced by stem; 0 when it does not fit. */
static int expand(const char *pattern, const char *stem, char *out, size_t cap)
{
    size_t at = 0, klen = strlen(SCENE_KEY), slen = strlen(stem);
    for (const char *p = pattern; *p;) {
        int key = strncmp(p, SCENE_KEY, klen) == 0;
        size_t n = key ? slen : 1;
        if (at + n >= cap) return 0;
        memcpy(out + at, key ? stem : p, n);
        at += n;
        p += key ? klen : 1;
    }
    out[at] = '\0';
    return 1;
}

static int has_extension(const char *path, const char *ext)
{
    size_t n = strlen(path), e = strlen(ext);
    return n > e && strcasecmp(path + n - e, ext) == 0;
}

/* Reads one image and checks it against the scene's size; PNG from display values to linear radiance
 * at the scene's exposure. */
static sss_result load_one(const sss_eval_image_source *s, const sss_eval_scene *es, int w, int h, char *path,
                           size_t cap, sss_image *img, sss_error *err)
{
    if (!expand(s->pattern, es->file_stem, path, cap))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "eval: images %s: the file name of scene %s is too long",
                             s->name, es->name);
    sss_result r = sss_image_read(path, img, err);
    if (r != SSS_OK) {
        char what[1200];
        snprintf(what, sizeof what, "eval: images %s (scene %s)", s->name, es->name);
        sss_error_prefix(err, what);
        return r;
    }
    if (img->width != w || img->height != h) {
        r = sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "eval: images %s: %s is %dx%d, the scene %s is compared at %dx%d",
                          s->name, path, img->width, img->height, es->name, w, h);
        sss_image_free(img);
        return r;
    }
    size_t bad = sss_image_count_nonfinite(img);
    if (bad) {
        sss_image_free(img);
        return sss_error_set(err, SSS_ERROR_NUMERIC, "eval: images %s: %s holds %zu NaN/Inf values", s->name, path, bad);
    }
    if (has_extension(path, ".png")) {
        float k = (float)exp2(-es->exposure);
        for (size_t i = 0; i < (size_t)w * (size_t)h * 3; i++) img->pixels[i] *= k;
    }
    return SSS_OK;
}

sss_result eval_external_load(const sss_eval_desc *d, const sss_eval_scene *es, int w, int h, sss_image *imgs,
                              char (*paths)[1024], sss_error *err)
{
    for (int j = 0; j < d->image_count; j++) memset(&imgs[j], 0, sizeof imgs[j]);
    for (int j = 0; j < d->image_count; j++) {
        sss_result r = load_one(&d->images[j], es, w, h, paths[j], sizeof paths[j], &imgs[j], err);
        if (r != SSS_OK) {
            for (int k = 0; k < j; k++) sss_image_free(&imgs[k]);
            return r;
        }
    }
    return SSS_OK;
}

void eval_external_entry(int scene, const char *label, const char *path, sss_image *img, sss_eval_entry *e)
{
    memset(e, 0, sizeof *e);
    e->scene = scene;
    e->kind = SSS_EVAL_QUALITY;
    snprintf(e->label, sizeof e->label, "%s", label);
    snprintf(e->technique, sizeof e->technique, "external");
    snprintf(e->file, sizeof e->file, "%s", path);
    e->width = img->width;
    e->height = img->height;
    e->external = 1;
    e->ok = 1;
    e->supersample = 1;
    e->image = *img; /* the entry owns it now */
    memset(img, 0, sizeof *img);
}
