/* sss_gl_tables: the CPU tables built without GL (here on a second thread while the first renders the
 * same scene) and handed to sss_gl_renderer_create give the image the renderer computes by itself,
 * bit for bit, and are taken only where they match: another LUT size, another scene object (its own
 * PBD tables) or NULL make the renderer compute its own (sss_gl_stats.luts_precomputed counts what it
 * took). sam's adjacency maps are taken the same way. Errors name the technique and the parameter. */
#include <pthread.h>

#include "gl_test_util.h"
#include "gl/gl_test.h"
#include "gl/techniques/sam/tech_sam.h"

#define W 64
#define H 48

typedef struct build_args {
    const sss_scene *scene;
    sss_gl_renderer_desc desc;
    sss_gl_tables *tables;
    sss_result res;
    sss_error err;
} build_args;

static void *build_thread(void *arg)
{
    build_args *a = arg;
    a->res = sss_gl_tables_build(a->scene, &a->desc, &a->tables, &a->err);
    return NULL;
}

/* Renders scene with technique at W x H with tables (may be NULL) into out; the renderer, for the
 * caller to read and destroy (NULL when creation failed). */
static sss_gl_renderer *render_with(const char *technique, const sss_scene *scene, const sss_gl_tables *tables,
                                    sss_image *out)
{
    sss_gl_renderer_desc d = gt_desc(technique, NULL, 0, 0);
    d.width = W;
    d.height = H;
    d.tables = tables;
    sss_gl_renderer *r = NULL;
    sss_error err = {0};
    memset(out, 0, sizeof *out);
    int ok = sss_gl_renderer_create(gt_ctx(), scene, &d, &r, &err) == SSS_OK &&
             sss_gl_renderer_render(r, 0.0, &err) == SSS_OK && sss_image_create(out, W, H, &err) == SSS_OK &&
             sss_gl_renderer_read(r, out, &err) == SSS_OK;
    if (!ok) fprintf(stderr, "render %s: %s\n", technique, err.message);
    if (!ok) sss_image_free(out);
    return r;
}

/* maisch2020; *taken receives luts_precomputed. */
static int render(const sss_scene *scene, const sss_gl_tables *tables, sss_image *out, int *taken)
{
    sss_gl_renderer *r = render_with("maisch2020", scene, tables, out);
    sss_gl_stats st;
    sss_gl_renderer_stats(r, &st);
    *taken = st.luts_precomputed;
    sss_gl_renderer_destroy(r);
    return out->pixels != NULL;
}

static int subsurface_materials(const sss_scene *s)
{
    int n = 0;
    for (size_t i = 0; i < s->object_count; i++) n += s->objects[i].material.type == SSS_SCENE_MATERIAL_SUBSURFACE;
    return n;
}

static void check_same_image(void)
{
    sss_scene scene, other;
    CHECK(gt_load("gl_area.json", &scene) && gt_load("gl_area.json", &other));
    build_args a = {&scene, gt_desc("maisch2020", NULL, 0, 0), NULL, SSS_OK, {0}};
    pthread_t t;
    CHECK(pthread_create(&t, NULL, build_thread, &a) == 0);
    sss_image own = {0}, with = {0}, foreign = {0}, small = {0};
    int taken = -1;
    CHECK(render(&scene, NULL, &own, &taken) && taken == 0); /* meanwhile, on this thread */
    pthread_join(t, NULL);
    CHECK_MSG(a.res == SSS_OK, "tables: %s", a.err.message);
    CHECK(render(&scene, a.tables, &with, &taken));
    CHECK_MSG(taken >= 1 && taken == subsurface_materials(&scene), "took %d LUT cascades", taken);
    CHECK(memcmp(own.pixels, with.pixels, sizeof(float) * 3 * W * H) == 0);
    /* another scene object from the same file: its own PBD tables, so nothing is taken */
    CHECK(render(&other, a.tables, &foreign, &taken) && taken == 0);
    /* tables of another LUT size are not taken either */
    sss_gl_param_value p = {"lut_size", 64};
    sss_gl_renderer_desc d = gt_desc("maisch2020", &p, 1, 0);
    sss_gl_tables *small_tables = NULL;
    CHECK(sss_gl_tables_build(&scene, &d, &small_tables, NULL) == SSS_OK);
    CHECK(render(&scene, small_tables, &small, &taken) && taken == 0);
    CHECK(memcmp(own.pixels, small.pixels, sizeof(float) * 3 * W * H) == 0);
    sss_gl_tables_free(small_tables);
    sss_gl_tables_free(a.tables);
    sss_image_free(&own);
    sss_image_free(&with);
    sss_image_free(&foreign);
    sss_image_free(&small);
    sss_scene_free(&scene);
    sss_scene_free(&other);
}

/* sam's adjacency maps come from the tables when they were built for the same scene object and
 * parameters (the renderer then builds none: build_seconds 0) and give the same image; tables of
 * another seed are not taken. */
static int render_sam(const sss_scene *scene, const sss_gl_tables *tables, sss_image *out, double *build_seconds)
{
    sss_gl_renderer *r = render_with("sam", scene, tables, out);
    *build_seconds = r ? ((sam_state *)gl_test_renderer_state(r))->build_seconds : -1.0;
    sss_gl_renderer_destroy(r);
    return out->pixels != NULL;
}

static void check_sam_maps(void)
{
    sss_scene scene;
    CHECK(gt_load("gl_area.json", &scene));
    sss_gl_param_value seed = {"seed", 7};
    sss_gl_renderer_desc d = gt_desc("sam", NULL, 0, 0), d7 = gt_desc("sam", &seed, 1, 0);
    sss_gl_tables *t = NULL, *t7 = NULL;
    sss_error err = {0};
    CHECK_MSG(sss_gl_tables_build(&scene, &d, &t, &err) == SSS_OK && sss_gl_tables_build(&scene, &d7, &t7, &err) == SSS_OK,
              "%s", err.message);
    sss_image own = {0}, with = {0}, other = {0};
    double own_s = -1, with_s = -1, other_s = -1;
    CHECK(render_sam(&scene, NULL, &own, &own_s) && render_sam(&scene, t, &with, &with_s) &&
          render_sam(&scene, t7, &other, &other_s));
    CHECK_MSG(own_s > 0.0 && with_s == 0.0 && other_s > 0.0, "map build seconds: own %g, with tables %g, other seed %g",
              own_s, with_s, other_s);
    CHECK(memcmp(own.pixels, with.pixels, sizeof(float) * 3 * W * H) == 0);
    CHECK(memcmp(own.pixels, other.pixels, sizeof(float) * 3 * W * H) == 0);
    sss_gl_tables_free(t);
    sss_gl_tables_free(t7);
    sss_image_free(&own);
    sss_image_free(&with);
    sss_image_free(&other);
    sss_scene_free(&scene);
}

static void check_errors(void)
{
    sss_scene scene;
    CHECK(gt_load("gl_area.json", &scene));
    sss_gl_tables *t = (sss_gl_tables *)&scene; /* must be reset to NULL on failure */
    sss_error err = {0};
    sss_gl_renderer_desc d = gt_desc("no_such_technique", NULL, 0, 0);
    CHECK(sss_gl_tables_build(&scene, &d, &t, &err) == SSS_ERROR_INVALID_ARGUMENT && !t);
    CHECK_MSG(strstr(err.message, "no_such_technique") != NULL, "%s", err.message);
    sss_gl_param_value p = {"lut_size", 3};
    d = gt_desc("maisch2020", &p, 1, 0);
    CHECK(sss_gl_tables_build(&scene, &d, &t, &err) == SSS_ERROR_INVALID_ARGUMENT && !t);
    CHECK_MSG(strstr(err.message, "lut_size") != NULL, "%s", err.message);
    CHECK(sss_gl_tables_build(NULL, NULL, &t, NULL) == SSS_ERROR_INVALID_ARGUMENT && !t);
    CHECK(sss_gl_tables_build(&scene, NULL, NULL, NULL) == SSS_ERROR_INVALID_ARGUMENT);
    sss_gl_tables_free(NULL);
    sss_scene_free(&scene);
}

int main(void)
{
    check_same_image();
    check_sam_maps();
    check_errors();
    return CHECK_DONE();
}
