/* Technique "screen" = Maisch & Ropinski 2020's screen-space part alone (maisch2020 without the translucency pass):
 *  - its parameters are maisch2020's screen-space ones (same names, types, defaults and ranges);
 *  - it runs maisch2020's code: its image equals maisch2020 with translucency = 0 bit for bit, with
 *    default and with changed parameters (n, layers, brightening), on the back-lit dragon, where the
 *    two differ most from the full technique;
 *  - it has the "screen" buffer but no translucency buffers, and times the screen-space pass. */
#include "gl_test_util.h"

static void test_params(void)
{
    const sss_gl_technique_info *s = sss_gl_technique_find("screen"), *m = sss_gl_technique_find("maisch2020");
    CHECK(s && m);
    if (!s || !m) return;
    for (int i = 0; i < s->param_count; i++) {
        int found = 0;
        for (int j = 0; j < m->param_count; j++) {
            if (strcmp(s->params[i].name, m->params[j].name) != 0) continue;
            found = 1;
            CHECK(s->params[i].type == m->params[j].type);
            CHECK(s->params[i].default_value == m->params[j].default_value);
            CHECK(s->params[i].min_value == m->params[j].min_value && s->params[i].max_value == m->params[j].max_value);
        }
        CHECK_MSG(found, "screen parameter %s is not maisch2020's", s->params[i].name);
        CHECK(strcmp(s->params[i].name, "translucency") != 0);
    }
}

static int same_image(const sss_image *a, const sss_image *b)
{
    if (a->width != b->width || a->height != b->height) return 0;
    return memcmp(a->pixels, b->pixels, sizeof(float) * 3 * (size_t)a->width * (size_t)a->height) == 0;
}

static void test_equal_to_maisch(void)
{
    sss_scene scene;
    if (!gt_load("gl_backlit.json", &scene)) {
        CHECK(0);
        return;
    }
    sss_gl_param_value none[1] = {{"translucency", 0}};
    sss_gl_param_value changed[6] = {{"n", 1},           {"layers", 6},          {"brightening", 1},
                                     {"grazing_sources", 0.1}, {"footprint_split", 3}, {"translucency", 0}};
    for (int k = 0; k < 2; k++) {
        sss_image a, b;
        const sss_gl_param_value *p = k ? changed : none;
        int np = k ? 6 : 1;
        CHECK(gt_render(&scene, "screen", 0.0, k ? changed : NULL, k ? 5 : 0, &a));
        CHECK(gt_render(&scene, "maisch2020", 0.0, p, np, &b));
        int same = same_image(&a, &b);
        printf("screen %s parameters: %s maisch2020 with translucency = 0\n", k ? "changed" : "default",
               same ? "identical to" : "DIFFERS from");
        CHECK(same);
        CHECK(sss_image_count_nonfinite(&a) == 0);
        sss_image_free(&a);
        sss_image_free(&b);
    }
    /* buffers and timings */
    sss_gl_renderer_desc d;
    memset(&d, 0, sizeof d);
    d.technique = "screen";
    d.timings = 1;
    sss_gl_renderer *r = NULL;
    sss_error err = {0};
    CHECK(sss_gl_renderer_create(gt_ctx(), &scene, &d, &r, &err) == SSS_OK);
    CHECK(r && sss_gl_renderer_render(r, 0.0, &err) == SSS_OK);
    sss_image buf;
    CHECK(sss_gl_renderer_read_buffer(r, "screen", &buf, &err) == SSS_OK);
    sss_image_free(&buf);
    CHECK(sss_gl_renderer_read_buffer(r, "translucency", &buf, &err) != SSS_OK);
    sss_gl_timings t;
    sss_gl_renderer_timings(r, &t);
    int has_screen = 0, has_trans = 0;
    for (int i = 0; i < t.pass_count; i++) {
        has_screen |= strcmp(t.passes[i].name, "screen_space") == 0;
        has_trans |= strcmp(t.passes[i].name, "translucency") == 0;
    }
    CHECK(has_screen && !has_trans);
    sss_gl_renderer_destroy(r);
    sss_scene_free(&scene);
}

int main(void)
{
    test_params();
    test_equal_to_maisch();
    return CHECK_DONE();
}
