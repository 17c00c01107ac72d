/* sss_gl_renderer_update_materials: a renderer created for one scene and given another with the same
 * geometry but other materials renders what a new renderer of that scene renders (the independent
 * computation), for techniques with no material state (maisch2020) and with a materials_changed
 * callback (ssss: kernels, mertens2003: sampling tables, sam: maps and its front side's kernels); with
 * the tables of sss_gl_tables_build; for a material edited in place (scene NULL); and when an object
 * stops scattering or was moved in place (everything rebuilt). Another geometry is refused, naming what differs, and the
 * renderer keeps drawing its scene. */
#include "gl_test_util.h"

#define W 64
#define H 48

static char *read_scene_text(const char *name, size_t *size)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/scenes/%s", SSS_SOURCE_DIR, name);
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    char *text = calloc(1, 1 << 16);
    *size = text ? fread(text, 1, (1 << 16) - 1, f) : 0;
    fclose(f);
    return text;
}

/* gl_area.json with `from` replaced by `to` (the first occurrence). */
static int load_edited(const char *from, const char *to, sss_scene *out)
{
    size_t size = 0;
    char *text = read_scene_text("gl_area.json", &size), *edited = calloc(1, (1 << 16) + 64);
    char *at = text ? strstr(text, from) : NULL;
    int ok = at && edited;
    if (ok) {
        size_t head = (size_t)(at - text);
        memcpy(edited, text, head);
        snprintf(edited + head, (1 << 16) + 64 - head, "%s%s", to, at + strlen(from));
        sss_error err = {0};
        ok = sss_scene_parse(edited, strlen(edited), SSS_SOURCE_DIR "/scenes", "gl_area_edited.json", NULL, out, &err) ==
             SSS_OK;
        if (!ok) fprintf(stderr, "parse: %s\n", err.message);
    }
    free(text);
    free(edited);
    return ok;
}

static int render_into(sss_gl_renderer *r, sss_image *out)
{
    sss_error err = {0};
    memset(out, 0, sizeof *out);
    int ok = sss_gl_renderer_render(r, 0.0, &err) == SSS_OK && sss_image_create(out, W, H, &err) == SSS_OK &&
             sss_gl_renderer_read(r, out, &err) == SSS_OK;
    if (!ok) fprintf(stderr, "render: %s\n", err.message);
    return ok;
}

static sss_gl_renderer *create(const sss_scene *scene, const char *technique)
{
    sss_gl_renderer_desc d = gt_desc(technique, NULL, 0, 0);
    d.width = W;
    d.height = H;
    sss_gl_renderer *r = NULL;
    sss_error err = {0};
    if (sss_gl_renderer_create(gt_ctx(), scene, &d, &r, &err) != SSS_OK) fprintf(stderr, "create: %s\n", err.message);
    return r;
}

static int fresh_image(const sss_scene *scene, const char *technique, sss_image *out)
{
    sss_gl_renderer *r = create(scene, technique);
    int ok = r && render_into(r, out);
    sss_gl_renderer_destroy(r);
    return ok;
}

/* The largest per-pixel difference relative to b's brightest value. */
static double max_difference(const sss_image *a, const sss_image *b)
{
    double worst = 0.0, peak = 0.0;
    for (size_t i = 0; i < (size_t)3 * W * H; i++) {
        worst = fmax(worst, fabs((double)a->pixels[i] - b->pixels[i]));
        peak = fmax(peak, fabs((double)b->pixels[i]));
    }
    return peak > 0.0 ? worst / peak : worst;
}

/* Two renders of the same scene agree to float rounding, except for maisch2020's additive splat
 * blending, whose order varies between runs (measured up to 1.6e-5 of the peak under AddressSanitizer);
 * a stale material is off by 0.05 or more (the materials here), a stale kernel by 6.5. */
static double tolerance(const char *technique) { return strcmp(technique, "maisch2020") == 0 ? 2e-4 : 1e-5; }

static void check_technique(const char *technique, const sss_scene *marble, const sss_scene *ketchup,
                            const sss_scene *diffuse)
{
    double tol = tolerance(technique);
    sss_image want_ketchup = {0}, want_diffuse = {0}, got = {0}, before = {0};
    CHECK(fresh_image(ketchup, technique, &want_ketchup) && fresh_image(diffuse, technique, &want_diffuse));
    sss_gl_renderer *r = create(marble, technique);
    CHECK(r && render_into(r, &before));
    CHECK_MSG(max_difference(&before, &want_ketchup) > 0.05, "%s: the two materials look alike", technique);
    sss_error err = {0};
    CHECK_MSG(sss_gl_renderer_update_materials(r, ketchup, NULL, &err) == SSS_OK, "%s: %s", technique, err.message);
    CHECK(render_into(r, &got));
    CHECK_MSG(max_difference(&got, &want_ketchup) < tol, "%s: in place %g from a new renderer", technique,
              max_difference(&got, &want_ketchup));
    sss_image_free(&got);
    /* with the tables of the other scene */
    sss_gl_renderer_desc d = gt_desc(technique, NULL, 0, 0);
    sss_gl_tables *tables = NULL;
    CHECK(sss_gl_tables_build(marble, &d, &tables, &err) == SSS_OK);
    CHECK(sss_gl_renderer_update_materials(r, marble, tables, &err) == SSS_OK && render_into(r, &got));
    sss_gl_stats st;
    sss_gl_renderer_stats(r, &st);
    CHECK_MSG(st.luts_precomputed == 1 && max_difference(&got, &before) < tol, "%s: with tables: took %d, %g off",
              technique, st.luts_precomputed, max_difference(&got, &before));
    sss_gl_tables_free(tables);
    sss_image_free(&got);
    /* the torus stops scattering: everything again */
    CHECK(sss_gl_renderer_update_materials(r, diffuse, NULL, &err) == SSS_OK && render_into(r, &got));
    CHECK_MSG(max_difference(&got, &want_diffuse) < tol, "%s: diffuse %g off", technique,
              max_difference(&got, &want_diffuse));
    sss_gl_renderer_destroy(r);
    sss_image_free(&got);
    sss_image_free(&before);
    sss_image_free(&want_ketchup);
    sss_image_free(&want_diffuse);
}

/* scene NULL: the renderer's own scene, its material edited in place. */
static void check_in_place(sss_scene *marble, const sss_scene *ketchup)
{
    sss_image want = {0}, got = {0}, before = {0};
    CHECK(fresh_image(ketchup, "ssss", &want));
    sss_gl_renderer *r = create(marble, "ssss");
    CHECK(r && render_into(r, &before));
    sss_scene_material saved = marble->objects[0].material;
    marble->objects[0].material = ketchup->objects[0].material;
    sss_error err = {0};
    CHECK(sss_gl_renderer_update_materials(r, NULL, NULL, &err) == SSS_OK && render_into(r, &got));
    CHECK_MSG(max_difference(&got, &want) < tolerance("ssss"), "edited in place: %g off", max_difference(&got, &want));
    marble->objects[0].material = saved;
    sss_gl_renderer_destroy(r);
    sss_image_free(&got);
    sss_image_free(&before);
    sss_image_free(&want);
}

/* scene NULL after a transform edit in place: rebuilt whole (mertens2003 keeps light-view bounds of the
 * objects from its creation), the image of a new renderer of the moved scene. */
static void check_moved_in_place(sss_scene *marble)
{
    sss_scene moved;
    CHECK(load_edited("\"rotate\": [1, 0, 0, 60]", "\"rotate\": [1, 0, 0, 20]", &moved));
    sss_image want = {0}, got = {0}, before = {0};
    CHECK(fresh_image(&moved, "mertens2003", &want));
    sss_gl_renderer *r = create(marble, "mertens2003");
    CHECK(r && render_into(r, &before));
    CHECK(max_difference(&before, &want) > 0.05);
    sss_transform saved = marble->objects[0].transform;
    marble->objects[0].transform = moved.objects[0].transform;
    sss_error err = {0};
    CHECK(sss_gl_renderer_update_materials(r, NULL, NULL, &err) == SSS_OK && render_into(r, &got));
    CHECK_MSG(max_difference(&got, &want) < tolerance("mertens2003"), "moved in place: %g off", max_difference(&got, &want));
    marble->objects[0].transform = saved;
    sss_gl_renderer_destroy(r);
    sss_scene_free(&moved);
    sss_image_free(&got);
    sss_image_free(&before);
    sss_image_free(&want);
}

/* Another geometry: refused, named, and the renderer draws its own scene as before. */
static void check_refused(const sss_scene *marble)
{
    sss_scene moved, more;
    CHECK(load_edited("\"rotate\": [1, 0, 0, 60]", "\"rotate\": [1, 0, 0, 50]", &moved));
    CHECK(load_edited("\"segments\": 48", "\"segments\": 40", &more));
    sss_image before = {0}, after = {0};
    sss_gl_renderer *r = create(marble, "maisch2020");
    CHECK(r && render_into(r, &before));
    sss_error err = {0};
    CHECK(sss_gl_renderer_update_materials(r, &moved, NULL, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK_MSG(strstr(err.message, "objects[0]") && strstr(err.message, "transform"), "%s", err.message);
    CHECK(sss_gl_renderer_update_materials(r, &more, NULL, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK_MSG(strstr(err.message, "objects[0]") && strstr(err.message, "mesh"), "%s", err.message);
    CHECK(sss_gl_renderer_update_materials(NULL, &more, NULL, &err) == SSS_ERROR_INVALID_ARGUMENT);
    sss_scene_free(&moved); /* the renderer must hold no pointer into them */
    sss_scene_free(&more);
    CHECK(render_into(r, &after));
    CHECK_MSG(max_difference(&after, &before) < tolerance("maisch2020"), "after a refused update: %g off",
              max_difference(&after, &before));
    sss_gl_renderer_destroy(r);
    sss_image_free(&before);
    sss_image_free(&after);
}

int main(int argc, char **argv)
{
    sss_scene marble, ketchup, diffuse;
    CHECK(gt_load("gl_area.json", &marble));
    CHECK(load_edited("\"medium\": \"Marble\",", "\"medium\": \"Ketchup\",", &ketchup));
    CHECK(load_edited("\"type\": \"subsurface\",\n        \"medium\": \"Marble\",\n        \"scale\": 5.0,\n        \"eta\": 1.33",
                      "\"type\": \"diffuse\", \"reflectance\": [0.7, 0.5, 0.3]", &diffuse));
    static const char *const techniques[] = {"maisch2020", "ssss", "mertens2003", "sam"};
    for (size_t i = 0; i < sizeof techniques / sizeof techniques[0]; i++)
        if (argc < 2 || strcmp(argv[1], techniques[i]) == 0) check_technique(techniques[i], &marble, &ketchup, &diffuse);
    check_in_place(&marble, &ketchup);
    check_moved_in_place(&marble);
    check_refused(&marble);
    sss_scene_free(&marble);
    sss_scene_free(&ketchup);
    sss_scene_free(&diffuse);
    return CHECK_DONE();
}
