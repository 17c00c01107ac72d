/* The pass API (sss/gl_pass.h) on G-buffer textures the test owns:
 *  - same image: a pass fed with the renderer's own G-buffer, irradiance and reflected light (its
 *    textures, by name) and the camera as plain OpenGL matrices from the public camera functions
 *    writes the renderer's image, for every technique (sam with few links, built at creation);
 *  - GL state (docs/integration.md, "What the pass sets and restores"): a pass created and run in a
 *    hostile engine state (every listed item away from its default: wireframe, rasterizer discard,
 *    primitive restart at index 0, reversed-Z clip control, byte-swapped unpacking, ...) writes the
 *    image of a pass created and run in the GL defaults, bit for bit where the technique repeats its
 *    own image bit for bit, and every item reads back unchanged after each call (queried here,
 *    independently of the library's save/restore: gl_pass_state_util.h);
 *  - lights: sss_gl_pass_update_lights refuses a light removed or of another kind, for every technique
 *    (as documented), naming what changed;
 *  - chen2012, which never reads the frame's irradiance, is refused as a pass (sss_gl_pass_create);
 *  - bad frames: wrong size, format, a name that is not a texture, missing mip levels, a projection
 *    that is not perspective: INVALID_ARGUMENT naming the field, the output texture untouched. */
#include "gl/gl_test.h"
#include "gl_pass_state_util.h"
#include "gl_test_util.h"
#include "sss/gl_pass.h"

/* ---- Frames from a renderer's targets --------------------------------------------------------- */

/* The renderer's camera as plain OpenGL matrices (standard depth range), from the public camera API. */
static void camera_matrices(const sss_gl_renderer *r, sss_gl_pass_frame *f)
{
    const gl_core *core = gl_test_renderer_core(r);
    sss_camera cam = core->scene->camera;
    cam.width = core->width;
    cam.height = core->height;
    sss_camera_basis b;
    sss_camera_basis_init(&cam, &b, NULL);
    double v[16], p[16];
    sss_camera_view_matrix(&b, v);
    sss_camera_projection_matrix(&b, core->view.camera.near_plane, core->far_plane, p);
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) {
            f->view[4 * j + i] = (float)v[4 * i + j];
            f->proj[4 * j + i] = (float)p[4 * i + j];
        }
}

static GLuint output_texture(int w, int h, float fill)
{
    GLuint t = gl_texture_2d(GL_RGBA32F, w, h, 1, NULL);
    const float v[4] = {fill, fill, fill, fill};
    glClearTexImage(t, 0, GL_RGBA, GL_FLOAT, v);
    return t;
}

static int read_rgba(GLuint tex, int w, int h, float *out)
{
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glGetTextureImage(tex, 0, GL_RGBA, GL_FLOAT, (GLsizei)((size_t)w * h * 4 * sizeof(float)), out);
    return glGetError() == GL_NO_ERROR;
}

/* Small shadow maps, LUTs and light-view buffers (fast); sam with few links (built at creation). */
static int technique_params(const char *technique, sss_gl_param_value params[5])
{
    int n = 0;
    params[n++] = (sss_gl_param_value){"shadow_size", 256};
    params[n++] = (sss_gl_param_value){"shadow_cube_size", 128};
    params[n++] = (sss_gl_param_value){"lut_size", 128};
    if (strcmp(technique, "sam") == 0) {
        params[n++] = (sss_gl_param_value){"samples", 16};
        params[n++] = (sss_gl_param_value){"n", 4};
    }
    if (strcmp(technique, "mertens2003") == 0) params[n++] = (sss_gl_param_value){"light_view_size", 256};
    return n;
}

/* Runs the pass on the frame into a new output texture (returned; 0 on failure). */
static GLuint run_pass(sss_gl_pass *pass, sss_gl_pass_frame *f, int w, int h, const char *technique, const char *what)
{
    sss_error err = {0};
    f->output = output_texture(w, h, 0.0f);
    sss_result res = sss_gl_pass_execute(pass, f, &err);
    CHECK_MSG(res == SSS_OK, "%s: %s pass: %s", technique, what, err.message);
    return f->output;
}

/* Differences of the rgb of two images of n floats: values that differ, the largest difference and
 * the sums of |a - b| and |b|. */
typedef struct image_diff {
    size_t differ;
    double worst, diff, sum, peak;
} image_diff;

/* A NaN or infinity in either image counts as an infinite difference. */
static image_diff compare_rgb(const float *a, const float *b, size_t n)
{
    image_diff d = {0, 0.0, 0.0, 0.0, 0.0};
    for (size_t i = 0; i < n; i++) {
        if (i % 4 == 3) continue;
        double e = isfinite(a[i]) && isfinite(b[i]) ? fabs((double)a[i] - b[i]) : INFINITY;
        d.differ += !(a[i] == b[i]);
        d.diff += e;
        d.sum += fabs(b[i]);
        d.peak = fmax(d.peak, fabs(b[i]));
        if (e > d.worst) d.worst = e;
    }
    return d;
}

/* maisch2020 and dss append their splats in the order atomicAdd hands out the slots and blend them
 * additively in that order, so their sums round differently from run to run (seen on llvmpipe:
 * maisch2020 0-2 values by up to 1e-5, dss up to a few thousand by up to 1.1e-6, mean |diff| / mean
 * below 1e-7); the other techniques repeat their image bit for bit. */
static int repeats_bit_for_bit(const char *technique)
{
    return strcmp(technique, "maisch2020") != 0 && strcmp(technique, "dss") != 0;
}

/* The output textures read back (in the GL defaults) into malloc'd floats, then deleted. */
static float *take_image(GLuint tex, int w, int h)
{
    float *px = malloc((size_t)w * h * 4 * sizeof(float));
    int ok = px && tex && read_rgba(tex, w, h, px);
    if (tex) glDeleteTextures(1, &tex);
    if (ok) return px;
    free(px);
    return NULL;
}

/* Every call of the pass API in the hostile engine state of gl_pass_state_util.h: the state reads
 * back unchanged after each; returns the output of the pass created and run in it. */
static GLuint hostile_pass(const sss_gl_pass_desc *pd, sss_gl_pass_frame *f, int w, int h, const char *technique)
{
    sss_error err = {0};
    GLuint out = output_texture(w, h, 0.0f);
    caller_gl c;
    set_caller_state(&c);
    CHECK_MSG(glGetError() == GL_NO_ERROR, "%s: GL error setting the caller's state", technique);
    snapshot before, after;
    take_snapshot(&before);
    sss_gl_pass *pass = NULL;
    static const char *const calls[] = {"create", "execute", "update_materials", "update_lights", "set_param"};
    for (int k = 0; k < 5; k++) {
        sss_result res = SSS_OK;
        if (k == 0) res = sss_gl_pass_create(gt_ctx(), pd, &pass, &err);
        if (k == 1) {
            f->output = out;
            res = sss_gl_pass_execute(pass, f, &err);
        }
        if (k == 2) res = sss_gl_pass_update_materials(pass, &err);
        if (k == 3) res = sss_gl_pass_update_lights(pass, &err);
        if (k == 4) res = sss_gl_pass_set_param(pass, "shadow_bias", 1.5, &err);
        take_snapshot(&after);
        CHECK_MSG(res == SSS_OK, "%s: %s in the engine's state: %s", technique, calls[k], err.message);
        CHECK_MSG(glGetError() == GL_NO_ERROR, "%s: GL error left by %s", technique, calls[k]);
        CHECK_MSG(same_snapshot(&before, &after), "%s: GL state changed by %s", technique, calls[k]);
        if (!pass) break;
    }
    free_caller_state(&c);
    sss_gl_pass_destroy(pass);
    return out;
}

/* sss_gl_pass_update_lights keeps the lights' number and kinds (sss/gl_pass.h, as the renderer's),
 * for every technique: a light removed, or turned into another kind, is refused naming what changed;
 * the lights as they were are accepted. scene: gl_spot.json (a spot and a directional light). */
static void check_update_lights(sss_gl_pass *pass, sss_scene *scene, const char *technique)
{
    sss_error err = {0};
    scene->light_count = 1;
    sss_result res = sss_gl_pass_update_lights(pass, &err);
    CHECK_MSG(res == SSS_ERROR_INVALID_ARGUMENT && strstr(err.message, "has 1 light,") && strstr(err.message, "had 2"),
              "%s: a light removed: %d %s", technique, (int)res, err.message);
    scene->light_count = 2;
    sss_light directional = scene->lights[1];
    scene->lights[1].type = SSS_LIGHT_POINT;
    scene->lights[1].position[1] = 3.0;
    scene->lights[1].intensity[0] = scene->lights[1].intensity[1] = scene->lights[1].intensity[2] = 10.0;
    res = sss_gl_pass_update_lights(pass, &err);
    CHECK_MSG(res == SSS_ERROR_INVALID_ARGUMENT && strstr(err.message, "lights[1] is a point light") &&
                  strstr(err.message, "was a directional light"),
              "%s: a light of another kind: %d %s", technique, (int)res, err.message);
    scene->lights[1] = directional;
    res = sss_gl_pass_update_lights(pass, &err);
    CHECK_MSG(res == SSS_OK, "%s: the lights as they were: %s", technique, err.message);
}

/* Renders `technique` with a renderer, then runs passes on the renderer's targets: in the GL defaults
 * (twice: does the technique repeat its image bit for bit?) and in a hostile engine state. */
static void check_technique(sss_scene *scene, const char *technique)
{
    sss_error err = {0};
    sss_gl_param_value params[5];
    int nparams = technique_params(technique, params);
    sss_gl_renderer_desc rd = gt_desc(technique, params, nparams, 0);
    sss_gl_renderer *r = NULL;
    sss_gl_pass *pass = NULL;
    sss_gl_pass_desc pd;
    memset(&pd, 0, sizeof pd);
    pd.technique = technique;
    pd.params = params;
    pd.param_count = nparams;
    pd.scene = scene;
    pd.width = scene->camera.width;
    pd.height = scene->camera.height;
    pd.timings = 1; /* its timer queries must not write into the engine's GL_QUERY_BUFFER */
    int ok = sss_gl_renderer_create(gt_ctx(), scene, &rd, &r, &err) == SSS_OK &&
             sss_gl_renderer_render(r, 0.25, &err) == SSS_OK && sss_gl_pass_create(gt_ctx(), &pd, &pass, &err) == SSS_OK;
    CHECK_MSG(ok, "%s: %s", technique, err.message);
    if (!ok) {
        sss_gl_renderer_destroy(r);
        return;
    }
    int w = pd.width, h = pd.height;
    sss_gl_pass_frame f;
    memset(&f, 0, sizeof f);
    f.position = gl_test_renderer_core(r)->frame.pos;
    f.normal = gl_test_renderer_core(r)->frame.nrm;
    f.albedo = gl_test_renderer_core(r)->frame.albedo;
    f.irradiance = gl_test_renderer_core(r)->frame.irr;
    f.reflected = gl_test_renderer_core(r)->frame.refl;
    f.time = 0.25;
    camera_matrices(r, &f);
    GLuint t_clean = run_pass(pass, &f, w, h, technique, "clean");
    GLuint t_again = run_pass(pass, &f, w, h, technique, "clean, again");
    GLuint t_hostile = hostile_pass(&pd, &f, w, h, technique);
    check_update_lights(pass, scene, technique);
    size_t n = (size_t)w * h * 4;
    float *clean = take_image(t_clean, w, h), *again = take_image(t_again, w, h),
          *hostile = take_image(t_hostile, w, h), *own = malloc(n * sizeof(float));
    CHECK(clean && again && hostile && own && read_rgba(gl_test_renderer_core(r)->frame.final, w, h, own));
    if (clean && again && hostile && own) {
        image_diff vs_renderer = compare_rgb(clean, own, n), repeat = compare_rgb(again, clean, n),
                   vs_clean = compare_rgb(hostile, clean, n);
        printf("%-12s pass vs renderer: mean |diff| / mean %.2e, max |diff| %.2e\n", technique,
               vs_renderer.diff / (vs_renderer.sum > 0 ? vs_renderer.sum : 1), vs_renderer.worst);
        printf("%-12s engine state vs GL defaults: %zu values differ, max |diff| %.2e, mean |diff| / mean %.2e "
               "(pass repeated: %zu, %.2e)\n",
               technique, vs_clean.differ, vs_clean.worst, vs_clean.diff / (vs_clean.sum > 0 ? vs_clean.sum : 1),
               repeat.differ, repeat.worst);
        CHECK_MSG(vs_renderer.sum > 0.0, "%s: black image", technique);
        CHECK_MSG(vs_renderer.diff <= 1e-4 * vs_renderer.sum, "%s: the pass differs from the renderer (%.3g of the image)",
                  technique, vs_renderer.diff / (vs_renderer.sum > 0 ? vs_renderer.sum : 1));
        /* bit for bit where the technique repeats itself; else within the rounding of its splat order
         * (primitive restart alone, left to leak into the pass, moved the mean by 7e-5 on both) */
        int same = vs_clean.differ == 0 ||
                   (!repeats_bit_for_bit(technique) && vs_clean.worst <= 1e-4 * vs_clean.peak &&
                    vs_clean.diff <= 1e-6 * vs_clean.sum);
        CHECK_MSG(same, "%s: the engine's GL state changes the image: %zu values, by up to %.3g", technique,
                  vs_clean.differ, vs_clean.worst);
        CHECK_MSG(!repeats_bit_for_bit(technique) || repeat.differ == 0, "%s: the pass did not repeat its image",
                  technique);
    }
    sss_gl_stats st;
    sss_gl_pass_stats(pass, &st);
    printf("%-12s pass-owned memory: %zu B per pixel, %zu B per splat, %zu splats, textures %zu B, buffers %zu B\n",
           technique, st.per_pixel_bytes, st.per_splat_bytes, (size_t)st.splat_total, st.texture_bytes,
           st.buffer_bytes);
    free(clean);
    free(again);
    free(hostile);
    free(own);
    sss_gl_pass_destroy(pass);
    sss_gl_renderer_destroy(r);
}

/* chen2012 reads no frame irradiance (its sources are lit in light space): refused as a pass, with the
 * reason, and nothing is created. */
static void check_refused(const sss_scene *scene, const char *technique)
{
    sss_error err = {0};
    sss_gl_pass_desc pd;
    memset(&pd, 0, sizeof pd);
    pd.technique = technique;
    pd.scene = scene;
    pd.width = scene->camera.width;
    pd.height = scene->camera.height;
    sss_gl_pass *pass = (sss_gl_pass *)&pd; /* must become NULL */
    sss_result res = sss_gl_pass_create(gt_ctx(), &pd, &pass, &err);
    printf("%s: %s\n", technique, err.message);
    CHECK_MSG(res == SSS_ERROR_UNSUPPORTED && !pass && strstr(err.message, technique) &&
                  strstr(err.message, "irradiance"),
              "%s as a pass: %d %s", technique, (int)res, err.message);
    if (res == SSS_OK) sss_gl_pass_destroy(pass);
}

/* ---- Bad frames -------------------------------------------------------------------------------- */

static void expect_error(sss_gl_pass *pass, const sss_gl_pass_frame *f, const char *field, int w, int h)
{
    sss_error err = {0};
    sss_result res = sss_gl_pass_execute(pass, f, &err);
    CHECK_MSG(res == SSS_ERROR_INVALID_ARGUMENT && strstr(err.message, field), "expected an error naming %s, got %d: %s",
              field, (int)res, err.message);
    float *px = malloc((size_t)w * h * 4 * sizeof(float));
    int untouched = px && read_rgba(f->output, w, h, px);
    for (size_t i = 0; untouched && i < (size_t)w * h * 4; i++) untouched = px[i] == 7.0f;
    CHECK_MSG(untouched, "output written despite the error on %s", field);
    free(px);
}

static void check_bad_frames(const sss_scene *scene)
{
    sss_error err = {0};
    int w = scene->camera.width, h = scene->camera.height;
    sss_gl_param_value params[3] = {{"shadow_size", 256}, {"shadow_cube_size", 128}, {"lut_size", 128}};
    sss_gl_renderer_desc rd = gt_desc("maisch2020", params, 3, 0);
    sss_gl_pass_desc pd;
    memset(&pd, 0, sizeof pd);
    pd.technique = "maisch2020";
    pd.params = params;
    pd.param_count = 3;
    pd.scene = scene;
    pd.width = w;
    pd.height = h;
    sss_gl_renderer *r = NULL;
    sss_gl_pass *pass = NULL;
    int ok = sss_gl_renderer_create(gt_ctx(), scene, &rd, &r, &err) == SSS_OK &&
             sss_gl_renderer_render(r, 0.0, &err) == SSS_OK && sss_gl_pass_create(gt_ctx(), &pd, &pass, &err) == SSS_OK;
    CHECK_MSG(ok, "%s", err.message);
    if (!ok) {
        sss_gl_renderer_destroy(r);
        return;
    }
    sss_gl_pass_frame good;
    memset(&good, 0, sizeof good);
    good.position = gl_test_renderer_core(r)->frame.pos;
    good.normal = gl_test_renderer_core(r)->frame.nrm;
    good.albedo = gl_test_renderer_core(r)->frame.albedo;
    good.irradiance = gl_test_renderer_core(r)->frame.irr;
    good.output = output_texture(w, h, 7.0f);
    camera_matrices(r, &good);
    GLuint small = gl_texture_2d(GL_RGBA32F, w / 2, h, 1, NULL);
    GLuint bytes = gl_texture_2d(GL_RGBA8, w, h, 1, NULL);
    GLuint no_mips = gl_texture_2d(GL_RGBA32F, w, h, 1, NULL);
    sss_gl_pass_frame f = good;
    f.normal = small;
    expect_error(pass, &f, "frame.normal", w, h);
    f = good;
    f.irradiance = bytes;
    expect_error(pass, &f, "frame.irradiance", w, h);
    f = good;
    f.albedo = 123456;
    expect_error(pass, &f, "frame.albedo", w, h);
    f = good;
    f.position = no_mips; /* maisch2020 sums mip chains */
    expect_error(pass, &f, "mip levels", w, h);
    f = good;
    memset(f.proj, 0, sizeof f.proj); /* orthographic: w = 1 */
    f.proj[0] = f.proj[5] = 1.0f;
    f.proj[10] = -1.0f;
    f.proj[15] = 1.0f;
    expect_error(pass, &f, "frame.proj", w, h);
    f = good;
    f.time = NAN;
    expect_error(pass, &f, "frame.time", w, h);
    /* material updates rebuild before the next frame, which then runs */
    CHECK_MSG(sss_gl_pass_update_materials(pass, &err) == SSS_OK && sss_gl_pass_execute(pass, &good, &err) == SSS_OK,
              "update_materials: %s", err.message);
    sss_gl_pass_info info;
    sss_gl_pass_get_info(pass, &info);
    CHECK(info.needs_mips && info.uses_lights && info.uses_geometry);
    GLuint t[4] = {small, bytes, no_mips, good.output};
    glDeleteTextures(4, t);
    sss_gl_pass_destroy(pass);
    sss_gl_renderer_destroy(r);
    /* creation: the scene and the size are required */
    pd.scene = NULL;
    CHECK(sss_gl_pass_create(gt_ctx(), &pd, &pass, &err) == SSS_ERROR_INVALID_ARGUMENT && strstr(err.message, "desc.scene"));
    pd.scene = scene;
    pd.width = 0;
    CHECK(sss_gl_pass_create(gt_ctx(), &pd, &pass, &err) == SSS_ERROR_INVALID_ARGUMENT && strstr(err.message, "desc.width"));
}

/* frame.depth instead of frame.position: the renderer's own reversed-Z depth buffer with the camera it
 * drew it with (reversed-Z, infinite far plane, GL_ZERO_TO_ONE) gives the image of its positions. The
 * pixel area comes from the solid angle and the shading normal instead of the triangle's plane
 * (pass_depth.frag.glsl), so the images agree within a bound, not bit for bit: on smooth meshes the
 * shading normal departs from the face by up to a few degrees. Measured on gl_spot: screen 0.20% of the
 * mean (2% of the peak at one pixel), ssss 1e-7 (it reads no areas). */
static void check_depth_input(const sss_scene *scene, const char *technique)
{
    sss_error err = {0};
    sss_gl_param_value params[5];
    int n = technique_params(technique, params);
    sss_gl_renderer_desc rd = gt_desc(technique, params, n, 0);
    sss_gl_pass_desc pd;
    memset(&pd, 0, sizeof pd);
    pd.technique = technique;
    pd.params = params;
    pd.param_count = n;
    pd.scene = scene;
    pd.width = scene->camera.width;
    pd.height = scene->camera.height;
    sss_gl_renderer *r = NULL;
    sss_gl_pass *pass = NULL;
    int ok = sss_gl_renderer_create(gt_ctx(), scene, &rd, &r, &err) == SSS_OK &&
             sss_gl_renderer_render(r, 0.0, &err) == SSS_OK && sss_gl_pass_create(gt_ctx(), &pd, &pass, &err) == SSS_OK;
    CHECK_MSG(ok, "%s: %s", technique, err.message);
    if (!ok) {
        sss_gl_renderer_destroy(r);
        return;
    }
    const gl_core *core = gl_test_renderer_core(r);
    int w = pd.width, h = pd.height;
    sss_gl_pass_frame f;
    memset(&f, 0, sizeof f);
    f.position = core->frame.pos;
    f.normal = core->frame.nrm;
    f.albedo = core->frame.albedo;
    f.irradiance = core->frame.irr;
    f.reflected = core->frame.refl;
    memcpy(f.view, core->view.camera.view, sizeof f.view);
    memcpy(f.proj, core->view.camera.proj, sizeof f.proj);
    GLuint t_pos = run_pass(pass, &f, w, h, technique, "positions");
    sss_gl_pass_frame d = f;
    d.position = 0;
    d.depth = core->frame.depth;
    GLuint t_depth = run_pass(pass, &d, w, h, technique, "depth");
    float *a = take_image(t_pos, w, h), *b = take_image(t_depth, w, h);
    if (a && b) {
        image_diff diff = compare_rgb(b, a, (size_t)w * h * 4);
        double rel = diff.diff / (diff.sum > 0.0 ? diff.sum : 1.0);
        printf("%-12s depth vs positions: mean |diff| / mean %.2e, max |diff| / peak %.2e\n", technique, rel,
               diff.worst / (diff.peak > 0.0 ? diff.peak : 1.0));
        CHECK_MSG(rel < 0.005, "%s: the depth input's image is %.3g off the positions' (mean)", technique, rel);
    }
    free(a);
    free(b);
    /* one of the two: both given is an error naming them */
    d.position = core->frame.pos;
    d.output = output_texture(w, h, 7.0f);
    expect_error(pass, &d, "frame.depth", w, h);
    glDeleteTextures(1, &d.output);
    sss_gl_pass_destroy(pass);
    sss_gl_renderer_destroy(r);
}

int main(int argc, char **argv)
{
    sss_scene scene;
    CHECK(gt_load("gl_spot.json", &scene));
    static const char *const techniques[] = {"maisch2020", "screen", "local", "ssss", "ssss-gauss6", "ssss-svd",
                                             "mertens2003", "dss", "sam"};
    for (size_t i = 0; i < sizeof techniques / sizeof techniques[0]; i++)
        if (argc < 2 || strcmp(argv[1], techniques[i]) == 0) check_technique(&scene, techniques[i]); /* argv: one */
    check_refused(&scene, "chen2012");
    check_bad_frames(&scene);
    check_depth_input(&scene, "screen");
    check_depth_input(&scene, "ssss");
    sss_scene_free(&scene);
    return CHECK_DONE();
}
