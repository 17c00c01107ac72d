/* The pass API (sss/gl_pass.h) on G-buffer textures the test owns:
 *  - same image: a pass fed with the renderer's own G-buffer, irradiance and reflected light (its
 *    textures, by name) and the camera as plain OpenGL matrices from the public camera functions
 *    writes the renderer's image, for every technique (sam with few links, built at creation);
 *  - GL state: every state sss/gl_pass.h lists, set to non-default values before the pass, reads back
 *    unchanged after it (queried here, independently of the library's save/restore);
 *  - bad frames: wrong size, format, a name that is not a texture, missing mip levels, a projection
 *    that is not perspective: INVALID_ARGUMENT naming the field, the output texture untouched. */
#include "gl/gl_internal.h"
#include "gl_test_util.h"
#include "sss/gl_pass.h"

/* ---- The listed GL state, queried by the test ------------------------------------------------ */

#define MAX_STATE 1200
typedef struct snapshot {
    int count;
    long long v[MAX_STATE];
} snapshot;

static void put(snapshot *s, long long v)
{
    if (s->count < MAX_STATE) s->v[s->count++] = v;
}

static void geti(snapshot *s, GLenum e)
{
    GLint v[4] = {0, 0, 0, 0};
    glGetIntegerv(e, v);
    int n = e == GL_VIEWPORT ? 4 : 1;
    for (int i = 0; i < n; i++) put(s, v[i]);
}

static void take_snapshot(snapshot *s)
{
    memset(s, 0, sizeof *s);
    static const GLenum ints[] = {GL_DRAW_FRAMEBUFFER_BINDING, GL_READ_FRAMEBUFFER_BINDING, GL_CURRENT_PROGRAM,
                                  GL_VERTEX_ARRAY_BINDING, GL_VIEWPORT, GL_DEPTH_FUNC, GL_BLEND_SRC_RGB,
                                  GL_BLEND_DST_RGB, GL_BLEND_SRC_ALPHA, GL_BLEND_DST_ALPHA, GL_BLEND_EQUATION_RGB,
                                  GL_BLEND_EQUATION_ALPHA, GL_CLIP_ORIGIN, GL_CLIP_DEPTH_MODE, GL_PACK_ALIGNMENT,
                                  GL_UNPACK_ALIGNMENT, GL_ACTIVE_TEXTURE, GL_UNIFORM_BUFFER_BINDING,
                                  GL_SHADER_STORAGE_BUFFER_BINDING, GL_ARRAY_BUFFER_BINDING,
                                  GL_DRAW_INDIRECT_BUFFER_BINDING, GL_DISPATCH_INDIRECT_BUFFER_BINDING,
                                  GL_PIXEL_PACK_BUFFER_BINDING, GL_PIXEL_UNPACK_BUFFER_BINDING};
    for (size_t i = 0; i < sizeof ints / sizeof ints[0]; i++) geti(s, ints[i]);
    static const GLenum caps[] = {GL_DEPTH_TEST, GL_BLEND, GL_CULL_FACE, GL_POLYGON_OFFSET_FILL, GL_SCISSOR_TEST};
    for (size_t i = 0; i < sizeof caps / sizeof caps[0]; i++) put(s, glIsEnabled(caps[i]));
    GLboolean b[4];
    glGetBooleanv(GL_DEPTH_WRITEMASK, b);
    put(s, b[0]);
    glGetBooleanv(GL_COLOR_WRITEMASK, b);
    for (int i = 0; i < 4; i++) put(s, b[i]);
    GLfloat f[2];
    glGetFloatv(GL_POLYGON_OFFSET_FACTOR, &f[0]);
    glGetFloatv(GL_POLYGON_OFFSET_UNITS, &f[1]);
    put(s, (long long)(f[0] * 1000));
    put(s, (long long)(f[1] * 1000));
    GLint active = 0;
    glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
    static const GLenum tex[] = {GL_TEXTURE_BINDING_2D, GL_TEXTURE_BINDING_2D_ARRAY, GL_TEXTURE_BINDING_CUBE_MAP,
                                 GL_TEXTURE_BINDING_CUBE_MAP_ARRAY, GL_TEXTURE_BINDING_3D, GL_SAMPLER_BINDING};
    for (int u = 0; u < SSS_GL_PASS_TEXTURE_UNITS; u++) {
        glActiveTexture(GL_TEXTURE0 + (GLenum)u);
        for (size_t t = 0; t < sizeof tex / sizeof tex[0]; t++) geti(s, tex[t]);
    }
    glActiveTexture((GLenum)active);
    static const GLenum img[] = {GL_IMAGE_BINDING_NAME,  GL_IMAGE_BINDING_LEVEL,  GL_IMAGE_BINDING_LAYERED,
                                 GL_IMAGE_BINDING_LAYER, GL_IMAGE_BINDING_ACCESS, GL_IMAGE_BINDING_FORMAT};
    for (GLuint i = 0; i < SSS_GL_PASS_IMAGE_UNITS; i++)
        for (size_t k = 0; k < sizeof img / sizeof img[0]; k++) {
            GLint v = 0;
            glGetIntegeri_v(img[k], i, &v);
            put(s, v);
        }
    static const GLenum buf[] = {GL_UNIFORM_BUFFER_BINDING,        GL_UNIFORM_BUFFER_START,
                                 GL_UNIFORM_BUFFER_SIZE,           GL_SHADER_STORAGE_BUFFER_BINDING,
                                 GL_SHADER_STORAGE_BUFFER_START,   GL_SHADER_STORAGE_BUFFER_SIZE};
    for (GLuint i = 0; i < SSS_GL_PASS_BUFFER_BINDINGS; i++)
        for (size_t k = 0; k < sizeof buf / sizeof buf[0]; k++) {
            GLint64 v = 0;
            glGetInteger64i_v(buf[k], i, &v);
            put(s, v);
        }
}

/* The caller's state before its pass: every listed item away from its default. */
typedef struct caller_gl {
    GLuint fbo, program, vao, tex2d, tex_array, sampler, buffer, image;
} caller_gl;

static void set_caller_state(caller_gl *c)
{
    glCreateFramebuffers(1, &c->fbo);
    glCreateVertexArrays(1, &c->vao);
    c->tex2d = gl_texture_2d(GL_RGBA8, 4, 4, 1, NULL);
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &c->tex_array);
    glTextureStorage3D(c->tex_array, 1, GL_RGBA8, 4, 4, 2);
    c->image = gl_texture_2d(GL_RGBA32F, 4, 4, 1, NULL);
    glCreateSamplers(1, &c->sampler);
    glCreateBuffers(1, &c->buffer);
    glNamedBufferStorage(c->buffer, 4096, NULL, GL_DYNAMIC_STORAGE_BIT);
    const char *src = "#version 450 core\nout vec4 o;\nvoid main() { o = vec4(1.0); }\n";
    c->program = glCreateShaderProgramv(GL_FRAGMENT_SHADER, 1, &src);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, c->fbo);
    glUseProgram(c->program);
    glBindVertexArray(c->vao);
    glViewport(3, 5, 17, 19);
    glEnable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glEnable(GL_CULL_FACE);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glEnable(GL_SCISSOR_TEST);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    glColorMask(GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ZERO);
    glBlendEquationSeparate(GL_MAX, GL_FUNC_SUBTRACT);
    glPolygonOffset(2.0f, 3.0f);
    glClipControl(GL_UPPER_LEFT, GL_ZERO_TO_ONE);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 2);
    for (GLuint u = 0; u < SSS_GL_PASS_TEXTURE_UNITS; u++)
        glBindTextureUnit(u, (u & 1) ? c->tex_array : c->tex2d);
    glBindSampler(4, c->sampler);
    glActiveTexture(GL_TEXTURE3);
    glBindImageTexture(2, c->image, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
    for (GLuint i = 0; i < SSS_GL_PASS_BUFFER_BINDINGS; i += 3) {
        glBindBufferRange(GL_UNIFORM_BUFFER, i, c->buffer, 256, 1024);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, i + 1, c->buffer);
    }
    glBindBuffer(GL_ARRAY_BUFFER, c->buffer);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, c->buffer);
    glBindBuffer(GL_UNIFORM_BUFFER, c->buffer);
}

/* Back to the GL defaults the next renderer of this process expects. */
static void free_caller_state(caller_gl *c)
{
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glUseProgram(0);
    glBindVertexArray(0);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glDisable(GL_POLYGON_OFFSET_FILL);
    glDisable(GL_SCISSOR_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glBlendFunc(GL_ONE, GL_ZERO);
    glBlendEquation(GL_FUNC_ADD);
    glPolygonOffset(0.0f, 0.0f);
    glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glBindSampler(4, 0);
    glActiveTexture(GL_TEXTURE0);
    glDeleteFramebuffers(1, &c->fbo);
    glDeleteProgram(c->program);
    glDeleteVertexArrays(1, &c->vao);
    GLuint t[3] = {c->tex2d, c->tex_array, c->image};
    glDeleteTextures(3, t);
    glDeleteSamplers(1, &c->sampler);
    glDeleteBuffers(1, &c->buffer);
}

/* ---- Frames from a renderer's targets --------------------------------------------------------- */

/* The renderer's camera as plain OpenGL matrices (standard depth range), from the public camera API. */
static void camera_matrices(const sss_gl_renderer *r, sss_gl_pass_frame *f)
{
    sss_camera cam = r->scene->camera;
    cam.width = r->width;
    cam.height = r->height;
    sss_camera_basis b;
    sss_camera_basis_init(&cam, &b, NULL);
    double v[16], p[16];
    sss_camera_view_matrix(&b, v);
    sss_camera_projection_matrix(&b, r->near_plane, r->far_plane, p);
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

/* Renders `technique` with a renderer, then runs a pass on the renderer's targets; compares images and
 * the GL state around the pass. */
static void check_technique(const sss_scene *scene, const char *technique)
{
    sss_error err = {0};
    /* small shadow maps, LUTs and light-view buffers: the same for both, and fast */
    sss_gl_param_value params[5] = {{"shadow_size", 256}, {"shadow_cube_size", 128}, {"lut_size", 128}};
    int nparams = 3;
    if (strcmp(technique, "sam") == 0) { /* few links: its maps are built at creation, twice here */
        params[nparams++] = (sss_gl_param_value){"samples", 16};
        params[nparams++] = (sss_gl_param_value){"n", 4};
    }
    if (strcmp(technique, "chen2012") == 0) params[nparams++] = (sss_gl_param_value){"buffer_size", 256};
    if (strcmp(technique, "mertens2003") == 0) params[nparams++] = (sss_gl_param_value){"light_view_size", 256};
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
    f.position = r->frame.pos;
    f.normal = r->frame.nrm;
    f.albedo = r->frame.albedo;
    f.irradiance = r->frame.irr;
    f.reflected = r->frame.refl;
    f.output = output_texture(w, h, 0.0f);
    f.time = 0.25;
    camera_matrices(r, &f);
    caller_gl c;
    set_caller_state(&c);
    snapshot before, after;
    CHECK_MSG(glGetError() == GL_NO_ERROR, "%s: GL error setting the caller's state", technique);
    take_snapshot(&before);
    sss_result res = sss_gl_pass_execute(pass, &f, &err);
    take_snapshot(&after);
    CHECK_MSG(glGetError() == GL_NO_ERROR, "%s: GL error left by the pass", technique);
    CHECK_MSG(res == SSS_OK, "%s: pass: %s", technique, err.message);
    CHECK_MSG(before.count == after.count && memcmp(before.v, after.v, sizeof(long long) * (size_t)before.count) == 0,
              "%s: GL state changed by the pass", technique);
    for (int i = 0; i < before.count; i++)
        if (before.v[i] != after.v[i]) fprintf(stderr, "  state item %d: %lld -> %lld\n", i, before.v[i], after.v[i]);
    free_caller_state(&c);
    size_t n = (size_t)w * h * 4;
    float *a = malloc(n * sizeof(float)), *b = malloc(n * sizeof(float));
    CHECK(a && b && read_rgba(f.output, w, h, a) && read_rgba(r->frame.final, w, h, b));
    double diff = 0.0, sum = 0.0, worst = 0.0;
    for (size_t i = 0; a && b && i < n; i++) {
        if (i % 4 == 3) continue;
        diff += fabs(a[i] - b[i]);
        sum += fabs(b[i]);
        if (fabs(a[i] - b[i]) > worst) worst = fabs(a[i] - b[i]);
    }
    printf("%-12s pass vs renderer: mean |diff| / mean %.2e, max |diff| %.2e\n", technique, diff / (sum > 0 ? sum : 1),
           worst);
    CHECK_MSG(sum > 0.0, "%s: black image", technique);
    CHECK_MSG(diff <= 1e-4 * sum, "%s: the pass differs from the renderer (%.3g of the image)", technique,
              diff / (sum > 0 ? sum : 1));
    sss_gl_stats st;
    sss_gl_pass_stats(pass, &st);
    printf("%-12s pass-owned memory: %zu B per pixel, %zu B per splat, %zu splats, textures %zu B, buffers %zu B\n",
           technique, st.per_pixel_bytes, st.per_splat_bytes, (size_t)st.splat_total, st.texture_bytes,
           st.buffer_bytes);
    free(a);
    free(b);
    glDeleteTextures(1, &f.output);
    sss_gl_pass_destroy(pass);
    sss_gl_renderer_destroy(r);
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
    good.position = r->frame.pos;
    good.normal = r->frame.nrm;
    good.albedo = r->frame.albedo;
    good.irradiance = r->frame.irr;
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

int main(int argc, char **argv)
{
    sss_scene scene;
    CHECK(gt_load("gl_spot.json", &scene));
    static const char *const techniques[] = {"maisch2020", "screen", "local", "ssss", "ssss-gauss6", "ssss-svd",
                                             "mertens2003", "dss", "chen2012", "sam"};
    for (size_t i = 0; i < sizeof techniques / sizeof techniques[0]; i++)
        if (argc < 2 || strcmp(argv[1], techniques[i]) == 0) check_technique(&scene, techniques[i]); /* argv: one */
    check_bad_frames(&scene);
    sss_scene_free(&scene);
    return CHECK_DONE();
}
