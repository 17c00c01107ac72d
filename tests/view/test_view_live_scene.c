/* tests/view/test_view_live_scene.c — what the viewer relies on in the renderer (headless GL): a camera
 * moved in the scene the renderer was created with is used by the next frame, and that frame equals a
 * new renderer's frame of the scene loaded from the viewer's edited JSON (so the reference of the
 * current view, rendered from that JSON, sees the same view as the window). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "core/file_util.h"
#include "sss/gl.h"
#include "view/view_internal.h"

#define W 48
#define H 40

static int render(sss_gl_context *ctx, const sss_scene *s, sss_gl_renderer **keep, sss_image *out)
{
    sss_error err = {0};
    sss_gl_renderer_desc d;
    memset(&d, 0, sizeof d);
    d.technique = "local"; /* the cheapest registered technique */
    d.width = W;
    d.height = H;
    sss_gl_renderer *r = keep && *keep ? *keep : NULL;
    if (!r && sss_gl_renderer_create(ctx, s, &d, &r, &err) != SSS_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 0;
    }
    int ok = sss_gl_renderer_render(r, 0.0, &err) == SSS_OK && sss_image_create(out, W, H, &err) == SSS_OK &&
             sss_gl_renderer_read(r, out, &err) == SSS_OK;
    if (!ok) fprintf(stderr, "%s\n", err.message);
    if (keep) *keep = r;
    else sss_gl_renderer_destroy(r);
    return ok;
}

static double max_diff(const sss_image *a, const sss_image *b, double *peak)
{
    double m = 0.0;
    *peak = 0.0;
    for (size_t i = 0; i < 3u * W * H; i++) {
        m = fmax(m, fabs(a->pixels[i] - b->pixels[i]));
        *peak = fmax(*peak, fabs(b->pixels[i]));
    }
    return m;
}

int main(void)
{
    sss_error err = {0};
    sss_gl_context *ctx = NULL;
    if (sss_gl_context_create(NULL, &ctx, &err) != SSS_OK) {
        fprintf(stderr, "no headless GL context: %s\n", err.message);
        return 1;
    }
    const char *path = SSS_SOURCE_DIR "/scenes/gl_area.json";
    sss_scene s;
    char *text = NULL;
    size_t size = 0;
    CHECK(sss_scene_load(path, NULL, &s, &err) == SSS_OK);
    CHECK(sss_read_file(path, SSS_SCENE_MAX_FILE_SIZE, &text, &size, &err) == SSS_OK);
    s.camera.width = W;
    s.camera.height = H;

    sss_gl_renderer *r = NULL;
    sss_image before = {0}, moved = {0}, fresh = {0};
    CHECK(render(ctx, &s, &r, &before));
    /* the viewer's mouse: orbit, pan and zoom the live scene's camera, then the next frame */
    view_orbit(&s.camera, 35.0, 12.0);
    view_pan(&s.camera, 3.0, -2.0, W, H);
    view_zoom(&s.camera, 0.8);
    CHECK(render(ctx, &s, &r, &moved));
    sss_gl_renderer_destroy(r);

    /* the same view through the edited file and a new renderer */
    view_edits e = {&s.camera, NULL, -1, 1.0};
    char *json = NULL;
    sss_scene s2;
    CHECK(view_scene_json(text, size, path, &e, &json, &err) == SSS_OK);
    CHECK(json && sss_scene_parse(json, strlen(json), s.base_dir, path, NULL, &s2, &err) == SSS_OK);
    CHECK(render(ctx, &s2, NULL, &fresh));
    if (before.pixels && moved.pixels && fresh.pixels) {
        double peak = 0.0;
        CHECK(max_diff(&moved, &fresh, &peak) <= 1e-5 * peak);
        CHECK(max_diff(&before, &moved, &peak) > 0.05 * peak); /* the camera did move */
        CHECK(peak > 0.0);
    }
    sss_image_free(&before);
    sss_image_free(&moved);
    sss_image_free(&fresh);
    free(json);
    free(text);
    sss_scene_free(&s2);
    sss_scene_free(&s);
    sss_gl_context_destroy(ctx);
    return CHECK_DONE();
}
