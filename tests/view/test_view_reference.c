/* tests/view/test_view_reference.c — the viewer's background reference: the worker's image is the one
 * sss_reference_render gives for the same scene text and time (the renderer is deterministic), errors
 * come back through the job, abandoned jobs free themselves, and the cache keeps the newest entries. */
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "check.h"
#include "sss/reference.h"
#include "view/view_internal.h"

static const char scene_text[] =
    "{\"camera\": {\"position\": [0, 0.5, 4], \"look_at\": [0, 0, 0], \"fov\": 40, \"width\": 24, \"height\": 16},"
    " \"objects\": [{\"procedural\": {\"shape\": \"sphere\", \"radius\": 1, \"subdivisions\": 2},"
    "   \"material\": {\"type\": \"subsurface\", \"medium\": \"Skin1\", \"scale\": 20}}],"
    " \"lights\": [{\"type\": \"point\", \"position\": [2, 3, 2], \"intensity\": [20, 20, 20]}]}";

static void wait_done(view_ref_job *j)
{
    struct timespec ts = {0, 20000000L};
    double progress = -1.0;
    const char *stage = NULL;
    while (!view_ref_poll(j, &progress, &stage)) {
        CHECK(progress >= 0.0 && progress <= 1.0);
        nanosleep(&ts, NULL);
    }
}

static void test_same_as_direct(void)
{
    view_ref_job *j = NULL;
    sss_error err = {0};
    CHECK(view_ref_start(scene_text, ".", "ref.json", 0.0, 1, &j, &err) == SSS_OK);
    if (!j) return;
    wait_done(j);
    sss_image got = {0};
    CHECK(view_ref_finish(j, &got, &err) == SSS_OK);

    sss_scene s;
    CHECK(sss_scene_parse(scene_text, strlen(scene_text), ".", "ref.json", NULL, &s, &err) == SSS_OK);
    sss_reference_desc d;
    memset(&d, 0, sizeof d);
    d.quality = SSS_REFERENCE_DRAFT;
    sss_image want = {0};
    CHECK(sss_reference_render(&s, &d, &want, NULL, NULL, NULL, &err) == SSS_OK);
    CHECK(got.width == 24 && got.height == 16 && want.width == 24 && want.height == 16);
    if (got.pixels && want.pixels) {
        size_t n = 3u * 24u * 16u, diff = 0;
        double sum = 0.0;
        for (size_t i = 0; i < n; i++) {
            diff += got.pixels[i] != want.pixels[i];
            sum += want.pixels[i];
        }
        CHECK(diff == 0);
        CHECK(sum > 0.0); /* the sphere is lit: a black image would compare equal too */
    }
    sss_image_free(&got);
    sss_image_free(&want);
    sss_scene_free(&s);
}

static void test_errors_and_abandon(void)
{
    view_ref_job *j = NULL;
    sss_error err = {0};
    CHECK(view_ref_start("{\"camera\": 1}", ".", "broken.json", 0.0, 1, &j, &err) == SSS_OK);
    if (j) {
        wait_done(j);
        sss_image img = {0};
        CHECK(view_ref_finish(j, &img, &err) != SSS_OK);
        CHECK(strstr(err.message, "broken.json") != NULL);
        CHECK(img.pixels == NULL);
    }
    /* abandoned while running and after finishing: the worker or the caller frees it (ASan checks) */
    view_ref_job *a = NULL, *b = NULL;
    CHECK(view_ref_start(scene_text, ".", "a.json", 0.0, 1, &a, &err) == SSS_OK);
    CHECK(view_ref_start(scene_text, ".", "b.json", 0.0, 1, &b, &err) == SSS_OK);
    if (b) {
        wait_done(b);
        view_ref_abandon(b);
    }
    if (a) {
        view_ref_abandon(a);
        struct timespec ts = {1, 0}; /* give the worker time to finish before the process ends */
        nanosleep(&ts, NULL);
    }
}

static void test_cache(void)
{
    view_ref_cache c;
    memset(&c, 0, sizeof c);
    sss_error err = {0};
    char key[32];
    for (int i = 0; i < VIEW_REF_CACHE + 2; i++) {
        sss_image img = {0};
        CHECK(sss_image_create(&img, 1 + i, 1, &err) == SSS_OK);
        snprintf(key, sizeof key, "view %d", i);
        CHECK(view_ref_cache_put(&c, key, &img, &err) == SSS_OK);
        CHECK(img.pixels == NULL); /* moved into the cache */
    }
    CHECK(view_ref_cache_find(&c, "view 0") == NULL); /* the oldest two are gone */
    CHECK(view_ref_cache_find(&c, "view 1") == NULL);
    for (int i = 2; i < VIEW_REF_CACHE + 2; i++) {
        snprintf(key, sizeof key, "view %d", i);
        const sss_image *img = view_ref_cache_find(&c, key);
        CHECK(img && img->width == 1 + i);
    }
    view_ref_cache_free(&c);
    CHECK(view_ref_cache_find(&c, "view 5") == NULL);
}

int main(void)
{
    test_same_as_direct();
    test_errors_and_abandon();
    test_cache();
    return CHECK_DONE();
}
