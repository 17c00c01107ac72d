/* sss_gl_context_adopt_current: a context the test creates with plain EGL calls, as an engine would.
 *  - no current context: INVALID_ARGUMENT saying so, nothing returned;
 *  - a compatibility-profile context: UNSUPPORTED (the renderer needs core);
 *  - the test's core context adopted: a renderer on it writes the image a renderer on a context of
 *    sss_gl_context_create writes (same driver, so the same bits);
 *  - destroying the wrapper leaves the test's context current and usable (a clear reads back). */
#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include "gl_test_util.h"

/* A surfaceless OpenGL 4.5 context of the given profile, made current; EGL_NO_CONTEXT on failure. */
static EGLContext engine_context(EGLDisplay *dpy, EGLint profile_bit)
{
    *dpy = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
    if (*dpy == EGL_NO_DISPLAY || !eglInitialize(*dpy, NULL, NULL) || !eglBindAPI(EGL_OPENGL_API))
        return EGL_NO_CONTEXT;
    EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                        EGL_CONTEXT_OPENGL_PROFILE_MASK, profile_bit, EGL_NONE};
    EGLContext c = eglCreateContext(*dpy, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
    if (c != EGL_NO_CONTEXT && !eglMakeCurrent(*dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, c)) {
        eglDestroyContext(*dpy, c);
        return EGL_NO_CONTEXT;
    }
    return c;
}

static void test_no_current_context(void)
{
    sss_gl_context *ctx = (sss_gl_context *)&ctx; /* must be reset to NULL */
    sss_error err = {0};
    CHECK(sss_gl_context_adopt_current(&ctx, &err) == SSS_ERROR_INVALID_ARGUMENT);
    CHECK(ctx == NULL);
    CHECK_MSG(strstr(err.message, "no OpenGL context is current") != NULL, "message: %s", err.message);
    CHECK(sss_gl_context_adopt_current(NULL, &err) == SSS_ERROR_INVALID_ARGUMENT);
}

static void test_compatibility_profile(void)
{
    EGLDisplay dpy;
    EGLContext compat = engine_context(&dpy, EGL_CONTEXT_OPENGL_COMPATIBILITY_PROFILE_BIT);
    if (compat == EGL_NO_CONTEXT) {
        fprintf(stderr, "note: no 4.5 compatibility context on this driver, profile check skipped\n");
        return;
    }
    sss_gl_context *ctx = NULL;
    sss_error err = {0};
    CHECK(sss_gl_context_adopt_current(&ctx, &err) == SSS_ERROR_UNSUPPORTED);
    CHECK(ctx == NULL);
    CHECK_MSG(strstr(err.message, "core profile") != NULL, "message: %s", err.message);
    eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(dpy, compat);
}

static int render_on(sss_gl_context *ctx, const sss_scene *scene, sss_image *out)
{
    sss_error err = {0};
    sss_gl_renderer_desc d = gt_desc("screen", NULL, 0, 0);
    sss_gl_renderer *r = NULL;
    memset(out, 0, sizeof *out);
    int ok = sss_gl_renderer_create(ctx, scene, &d, &r, &err) == SSS_OK &&
             sss_gl_renderer_render(r, 0.0, &err) == SSS_OK &&
             sss_image_create(out, scene->camera.width, scene->camera.height, &err) == SSS_OK &&
             sss_gl_renderer_read(r, out, &err) == SSS_OK;
    if (!ok) fprintf(stderr, "render failed: %s\n", err.message);
    sss_gl_renderer_destroy(r);
    return ok;
}

/* Clears a fresh framebuffer of the current context and reads the colour back. */
static int context_usable(void)
{
    GLuint tex = 0, fbo = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    glTextureStorage2D(tex, 1, GL_RGBA32F, 4, 4);
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, tex, 0);
    const float value[4] = {0.25f, 0.5f, 0.75f, 1.0f};
    glClearNamedFramebufferfv(fbo, GL_COLOR, 0, value);
    float back[4 * 4 * 4] = {0};
    glGetTextureImage(tex, 0, GL_RGBA, GL_FLOAT, (GLsizei)sizeof back, back);
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(1, &tex);
    return glGetError() == GL_NO_ERROR && memcmp(back + 4 * 15, value, sizeof value) == 0;
}

static void test_adopted_renders(void)
{
    sss_scene scene;
    if (!gt_load("gl_backlit.json", &scene)) {
        CHECK(0);
        return;
    }
    sss_image owned, adopted;
    CHECK(render_on(gt_ctx(), &scene, &owned)); /* a context sss made (now current) */
    EGLDisplay dpy;
    EGLContext mine = engine_context(&dpy, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT);
    CHECK(mine != EGL_NO_CONTEXT);
    sss_gl_context *ctx = NULL;
    sss_error err = {0};
    CHECK_MSG(sss_gl_context_adopt_current(&ctx, &err) == SSS_OK, "%s", err.message);
    sss_gl_context_info info;
    sss_gl_context_get_info(ctx, &info);
    CHECK(info.platform && strcmp(info.platform, "adopted (EGL)") == 0);
    CHECK(render_on(ctx, &scene, &adopted));
    CHECK(sss_image_count_nonfinite(&adopted) == 0);
    double max_diff = 0.0, sum = 0.0;
    for (size_t i = 0; i < (size_t)owned.width * owned.height * 3; i++) {
        max_diff = fmax(max_diff, fabs(owned.pixels[i] - adopted.pixels[i]));
        sum += adopted.pixels[i];
    }
    CHECK_MSG(max_diff == 0.0, "adopted and owned contexts differ by %g", max_diff);
    CHECK(sum > 0.0);
    /* A renderer on sss's own context makes that one current; the adopted EGL context is made
     * current again by its wrapper. */
    CHECK(sss_gl_context_make_current(gt_ctx()));
    CHECK(sss_gl_context_make_current(ctx));
    CHECK(eglGetCurrentContext() == mine);
    sss_gl_context_destroy(ctx);
    CHECK(eglGetCurrentContext() == mine);
    CHECK(context_usable());
    eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(dpy, mine);
    sss_image_free(&owned);
    sss_image_free(&adopted);
    sss_scene_free(&scene);
}

int main(void)
{
    test_no_current_context();
    test_compatibility_profile();
    test_adopted_renders();
    sss_gl_context_destroy(gt_ctx());
    return CHECK_DONE();
}
