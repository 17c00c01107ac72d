/* gl/context.c — OpenGL 4.5 core contexts: headless EGL (surfaceless Mesa platform, then the device
 * platform) rendering into FBOs, or a GLFW window.
 *
 * Why eglGetPlatformDisplayEXT and not eglGetPlatformDisplay: before any display exists libepoxy cannot
 * tell the EGL version and aborts the process on the EGL 1.5 entry point (GL-NOTES.md). Every missing
 * piece (EGL client extension, no-config/surfaceless contexts, GL version, display for a window) is
 * reported as an error naming it; nothing here aborts.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <epoxy/egl.h>
#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "gl/core/gl_base.h"

static const char *egl_error_name(EGLint e)
{
    switch (e) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE: return "EGL_BAD_SURFACE";
    default: return "EGL error";
    }
}

/* The GLFW error callback is global: keep the last message for the next report. */
static char glfw_last_error[256];
static void glfw_error_callback(int code, const char *message)
{
    snprintf(glfw_last_error, sizeof glfw_last_error, "%s (GLFW error 0x%x)", message ? message : "?",
             code);
}

static void debug_callback(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei length,
                           const GLchar *message, const void *user)
{
    (void)source; (void)id; (void)length;
    sss_gl_context *ctx = (sss_gl_context *)(uintptr_t)user;
    if (type != GL_DEBUG_TYPE_ERROR && severity != GL_DEBUG_SEVERITY_HIGH) return;
    if (ctx->debug_message[0]) return; /* keep the first one until a pass check reports it */
    snprintf(ctx->debug_message, sizeof ctx->debug_message, "%s", message ? message : "?");
}

/* Version, renderer and required features of the current context. */
static sss_result finish_context(sss_gl_context *ctx, int want_major, int want_minor, sss_error *err)
{
    int version = epoxy_gl_version();
    if (version < want_major * 10 + want_minor)
        return sss_error_set(err, SSS_ERROR_UNSUPPORTED,
                             "OpenGL %d.%d core is required, the %s context offers %d.%d (%s)", want_major,
                             want_minor, ctx->platform, version / 10, version % 10,
                             (const char *)glGetString(GL_RENDERER));
    snprintf(ctx->renderer, sizeof ctx->renderer, "%s", (const char *)glGetString(GL_RENDERER));
    snprintf(ctx->version, sizeof ctx->version, "%s", (const char *)glGetString(GL_VERSION));
    /* Software rasterisers: GL_TIME_ELAPSED is meaningless there (GL-NOTES.md), time with glFinish. */
    ctx->software = strstr(ctx->renderer, "llvmpipe") || strstr(ctx->renderer, "softpipe") ||
                    strstr(ctx->renderer, "SwiftShader") || strstr(ctx->renderer, "Software");
    if (ctx->debug && epoxy_has_gl_extension("GL_KHR_debug")) {
        glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
        glDebugMessageCallback(debug_callback, ctx);
    }
    GLint v = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &v);
    ctx->max_texture_size = v;
    GLint vp[2] = {0, 0};
    glGetIntegerv(GL_MAX_VIEWPORT_DIMS, vp);
    ctx->max_viewport[0] = vp[0] > 0 ? vp[0] : v; /* (always set by a 4.5 context) */
    ctx->max_viewport[1] = vp[1] > 0 ? vp[1] : v;
    while (glGetError() != GL_NO_ERROR) {}
    return SSS_OK;
}

static sss_result create_egl(sss_gl_context *ctx, const sss_gl_context_desc *desc, int major, int minor,
                             sss_error *err)
{
    if (!epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_platform_base"))
        return sss_error_set(err, SSS_ERROR_UNSUPPORTED,
                             "headless OpenGL: the EGL client extension EGL_EXT_platform_base is missing "
                             "(install libegl-mesa0 and libegl1)");
    EGLDisplay dpy = EGL_NO_DISPLAY;
    int want_surfaceless = desc->platform == SSS_GL_PLATFORM_HEADLESS ||
                           desc->platform == SSS_GL_PLATFORM_SURFACELESS;
    int want_device = desc->platform == SSS_GL_PLATFORM_HEADLESS || desc->platform == SSS_GL_PLATFORM_DEVICE;
    char tried[256] = "";
    if (want_surfaceless) {
        if (epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_MESA_platform_surfaceless")) {
            dpy = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
            if (dpy != EGL_NO_DISPLAY && !eglInitialize(dpy, NULL, NULL)) {
                snprintf(tried, sizeof tried, "surfaceless platform failed to initialise (%s)",
                         egl_error_name(eglGetError()));
                dpy = EGL_NO_DISPLAY;
            } else if (dpy != EGL_NO_DISPLAY) {
                ctx->platform = "EGL surfaceless (Mesa)";
            }
        } else {
            snprintf(tried, sizeof tried, "EGL_MESA_platform_surfaceless is missing");
        }
    }
    if (dpy == EGL_NO_DISPLAY && want_device) {
        if (!epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_platform_device") ||
            !epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_device_enumeration")) {
            return sss_error_set(err, SSS_ERROR_UNSUPPORTED,
                                 "headless OpenGL: %s%sEGL_EXT_platform_device/EGL_EXT_device_enumeration "
                                 "are missing",
                                 tried, tried[0] ? "; " : "");
        }
        EGLDeviceEXT devices[16];
        EGLint count = 0;
        if (!eglQueryDevicesEXT(16, devices, &count) || count <= 0)
            return sss_error_set(err, SSS_ERROR_UNSUPPORTED, "headless OpenGL: %s%sno EGL device found",
                                 tried, tried[0] ? "; " : "");
        if (desc->device_index < 0 || desc->device_index >= count)
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                                 "EGL device %d requested, but only %d device%s exist%s",
                                 desc->device_index, (int)count, count == 1 ? "" : "s",
                                 count == 1 ? "s" : "");
        dpy = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[desc->device_index], NULL);
        if (dpy == EGL_NO_DISPLAY || !eglInitialize(dpy, NULL, NULL))
            return sss_error_set(err, SSS_ERROR_UNSUPPORTED,
                                 "headless OpenGL: %s%sthe EGL device platform failed to initialise (%s)",
                                 tried, tried[0] ? "; " : "", egl_error_name(eglGetError()));
        ctx->platform = "EGL device";
    }
    if (dpy == EGL_NO_DISPLAY)
        return sss_error_set(err, SSS_ERROR_UNSUPPORTED, "headless OpenGL: %s",
                             tried[0] ? tried : "no EGL platform available");
    ctx->egl_display = dpy;
    if (!epoxy_has_egl_extension(dpy, "EGL_KHR_no_config_context") &&
        !epoxy_has_egl_extension(dpy, "EGL_MESA_configless_context"))
        return sss_error_set(err, SSS_ERROR_UNSUPPORTED,
                             "headless OpenGL: EGL_KHR_no_config_context is missing on the %s display",
                             ctx->platform);
    if (!epoxy_has_egl_extension(dpy, "EGL_KHR_surfaceless_context"))
        return sss_error_set(err, SSS_ERROR_UNSUPPORTED,
                             "headless OpenGL: EGL_KHR_surfaceless_context is missing on the %s display",
                             ctx->platform);
    if (!eglBindAPI(EGL_OPENGL_API))
        return sss_error_set(err, SSS_ERROR_UNSUPPORTED, "headless OpenGL: eglBindAPI(EGL_OPENGL_API) failed (%s)",
                             egl_error_name(eglGetError()));
    EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION, major, EGL_CONTEXT_MINOR_VERSION, minor,
                        EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                        EGL_CONTEXT_OPENGL_DEBUG, desc->debug ? EGL_TRUE : EGL_FALSE, EGL_NONE};
    ctx->egl_context = eglCreateContext(dpy, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
    if (ctx->egl_context == EGL_NO_CONTEXT)
        return sss_error_set(err, SSS_ERROR_UNSUPPORTED,
                             "headless OpenGL: no OpenGL %d.%d core context on the %s display (%s)", major,
                             minor, ctx->platform, egl_error_name(eglGetError()));
    if (!eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx->egl_context))
        return sss_error_set(err, SSS_ERROR_UNSUPPORTED, "headless OpenGL: eglMakeCurrent failed (%s)",
                             egl_error_name(eglGetError()));
    return finish_context(ctx, major, minor, err);
}

static sss_result create_window(sss_gl_context *ctx, const sss_gl_context_desc *desc, int major,
                                int minor, sss_error *err)
{
    const char *display = getenv("DISPLAY");
    const char *wayland = getenv("WAYLAND_DISPLAY");
    if ((!display || !display[0]) && (!wayland || !wayland[0]))
        return sss_error_set(err, SSS_ERROR_UNSUPPORTED,
                             "cannot open a window: no display (the DISPLAY environment variable is not "
                             "set); use `sss render` for headless rendering to an image, or run under "
                             "`xvfb-run -a`");
    glfw_last_error[0] = '\0';
    glfwSetErrorCallback(glfw_error_callback);
    if (!glfwInit())
        return sss_error_set(err, SSS_ERROR_UNSUPPORTED,
                             "cannot open a window: GLFW failed to initialise: %s; use `sss render` for "
                             "headless rendering",
                             glfw_last_error[0] ? glfw_last_error : "unknown reason");
    ctx->glfw_initialised = 1;
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, major);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, minor);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, desc->debug ? GLFW_TRUE : GLFW_FALSE);
    int w = desc->window_width > 0 ? desc->window_width : 960;
    int h = desc->window_height > 0 ? desc->window_height : 540;
    ctx->window = glfwCreateWindow(w, h, desc->window_title ? desc->window_title : "sss", NULL, NULL);
    if (!ctx->window)
        return sss_error_set(err, SSS_ERROR_UNSUPPORTED,
                             "cannot open a window with an OpenGL %d.%d core context: %s", major, minor,
                             glfw_last_error[0] ? glfw_last_error : "unknown reason");
    glfwMakeContextCurrent(ctx->window);
    glfwSwapInterval(0);
    ctx->platform = "GLFW window";
    return finish_context(ctx, major, minor, err);
}

sss_result sss_gl_context_create(const sss_gl_context_desc *desc_in, sss_gl_context **out, sss_error *err)
{
    if (!out) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sss_gl_context_create: out is NULL");
    *out = NULL;
    sss_gl_context_desc desc = {0};
    if (desc_in) desc = *desc_in;
    int major = desc.gl_major > 0 ? desc.gl_major : 4;
    int minor = desc.gl_major > 0 ? desc.gl_minor : 5;
    if (major < 4 || (major == 4 && minor < 5))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                             "OpenGL %d.%d requested: the renderer needs at least 4.5 core", major, minor);
    if ((int)desc.platform < 0 || desc.platform > SSS_GL_PLATFORM_WINDOW)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "unknown GL platform %d", (int)desc.platform);
#ifndef NDEBUG
    desc.debug = 1; /* debug builds: KHR_debug reports errors at the pass that caused them */
#endif
    sss_gl_context *ctx = calloc(1, sizeof *ctx);
    if (!ctx) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (GL context)");
    ctx->debug = desc.debug;
    ctx->platform = "none";
    sss_result r = desc.platform == SSS_GL_PLATFORM_WINDOW ? create_window(ctx, &desc, major, minor, err)
                                                            : create_egl(ctx, &desc, major, minor, err);
    if (r != SSS_OK) {
        sss_gl_context_destroy(ctx);
        return r;
    }
    *out = ctx;
    return SSS_OK;
}

sss_result sss_gl_context_adopt_current(sss_gl_context **out, sss_error *err)
{
    if (!out) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sss_gl_context_adopt_current: out is NULL");
    *out = NULL;
    /* glGetString is NULL without a current context, whatever the window system (EGL, GLX, WGL). */
    if (!glGetString(GL_VERSION))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                             "sss_gl_context_adopt_current: no OpenGL context is current on this thread "
                             "(make the engine's context current first)");
    GLint profile = 0;
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
    while (glGetError() != GL_NO_ERROR) {}
    if (!(profile & GL_CONTEXT_CORE_PROFILE_BIT))
        return sss_error_set(err, SSS_ERROR_UNSUPPORTED,
                             "sss_gl_context_adopt_current: the current context is not a core profile "
                             "(%s, %s); OpenGL 4.5 core is required",
                             (const char *)glGetString(GL_VERSION), (const char *)glGetString(GL_RENDERER));
    sss_gl_context *ctx = calloc(1, sizeof *ctx);
    if (!ctx) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (GL context)");
    ctx->adopted = 1;
    ctx->egl_context = eglGetCurrentContext();
    if (ctx->egl_context != EGL_NO_CONTEXT) {
        ctx->egl_display = eglGetCurrentDisplay();
        ctx->egl_draw = eglGetCurrentSurface(EGL_DRAW);
        ctx->egl_read = eglGetCurrentSurface(EGL_READ);
        ctx->platform = "adopted (EGL)";
    } else {
        ctx->platform = "adopted";
    }
    /* No debug callback: the engine's own, if any, stays installed. */
    sss_result r = finish_context(ctx, 4, 5, err);
    if (r != SSS_OK) {
        free(ctx);
        return r;
    }
    *out = ctx;
    return SSS_OK;
}

void sss_gl_context_destroy(sss_gl_context *ctx)
{
    if (!ctx) return;
    if (ctx->adopted) { /* the caller's context: only the wrapper goes */
        free(ctx);
        return;
    }
    if (ctx->egl_display != EGL_NO_DISPLAY && ctx->egl_display) {
        eglMakeCurrent(ctx->egl_display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (ctx->egl_context != EGL_NO_CONTEXT && ctx->egl_context)
            eglDestroyContext(ctx->egl_display, ctx->egl_context);
        /* No eglTerminate: an EGL display is a per-process singleton (the next context gets the same
         * handle back and eglInitialize is then a no-op), and terminating unloads Mesa's driver, whose
         * one-time (pthread_once) initialisation is then leaked on every reload. */
        eglReleaseThread();
    }
    if (ctx->window) glfwDestroyWindow(ctx->window);
    if (ctx->glfw_initialised) glfwTerminate();
    free(ctx);
}

void sss_gl_context_get_info(const sss_gl_context *ctx, sss_gl_context_info *out)
{
    if (!out) return;
    memset(out, 0, sizeof *out);
    if (!ctx) return;
    out->platform = ctx->platform;
    out->renderer = ctx->renderer;
    out->version = ctx->version;
    out->software = ctx->software;
}

int sss_gl_context_video_memory(sss_gl_context *ctx, size_t *total_bytes, size_t *available_bytes)
{
    if (total_bytes) *total_bytes = 0;
    if (available_bytes) *available_bytes = 0;
    if (!ctx || !sss_gl_context_make_current(ctx) || !epoxy_has_gl_extension("GL_NVX_gpu_memory_info")) return 0;
    GLint total_kib = 0, available_kib = 0; /* the extension counts KiB */
    glGetIntegerv(GL_GPU_MEMORY_INFO_DEDICATED_VIDMEM_NVX, &total_kib);
    glGetIntegerv(GL_GPU_MEMORY_INFO_CURRENT_AVAILABLE_VIDMEM_NVX, &available_kib);
    if (total_bytes) *total_bytes = (size_t)(total_kib > 0 ? total_kib : 0) * 1024;
    if (available_bytes) *available_bytes = (size_t)(available_kib > 0 ? available_kib : 0) * 1024;
    return 1;
}

int sss_gl_context_make_current(sss_gl_context *ctx)
{
    if (!ctx) return 0;
    if (ctx->adopted) { /* EGL: make it current again; other window systems: is some context current */
        if (ctx->egl_context == EGL_NO_CONTEXT) return glGetString(GL_VERSION) != NULL;
        return eglGetCurrentContext() == ctx->egl_context ||
               eglMakeCurrent(ctx->egl_display, ctx->egl_draw, ctx->egl_read, ctx->egl_context) == EGL_TRUE;
    }
    if (ctx->window) {
        glfwMakeContextCurrent(ctx->window);
        return 1;
    }
    return eglMakeCurrent(ctx->egl_display, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx->egl_context) == EGL_TRUE;
}

int sss_gl_window_should_close(sss_gl_context *ctx)
{
    if (!ctx || !ctx->window) return 1;
    glfwPollEvents();
    return glfwWindowShouldClose(ctx->window);
}

void sss_gl_window_swap(sss_gl_context *ctx)
{
    if (ctx && ctx->window) glfwSwapBuffers(ctx->window);
}

void sss_gl_window_size(sss_gl_context *ctx, int *width, int *height)
{
    int w = 0, h = 0;
    if (ctx && ctx->window) glfwGetFramebufferSize(ctx->window, &w, &h);
    if (width) *width = w;
    if (height) *height = h;
}

sss_result gl_check(sss_gl_context *ctx, const char *what, sss_error *err)
{
    GLenum e = glGetError();
    const char *dbg = ctx && ctx->debug_message[0] ? ctx->debug_message : NULL;
    if (e == GL_NO_ERROR && !dbg) return SSS_OK;
    const char *name = "GL error";
    switch (e) {
    case GL_INVALID_ENUM: name = "GL_INVALID_ENUM"; break;
    case GL_INVALID_VALUE: name = "GL_INVALID_VALUE"; break;
    case GL_INVALID_OPERATION: name = "GL_INVALID_OPERATION"; break;
    case GL_INVALID_FRAMEBUFFER_OPERATION: name = "GL_INVALID_FRAMEBUFFER_OPERATION"; break;
    case GL_OUT_OF_MEMORY: name = "GL_OUT_OF_MEMORY"; break;
    case GL_NO_ERROR: name = "KHR_debug"; break;
    default: break;
    }
    sss_result code = e == GL_OUT_OF_MEMORY ? SSS_ERROR_OUT_OF_MEMORY : SSS_ERROR_NUMERIC;
    sss_error_set(err, code, "OpenGL error in %s: %s%s%s", what, name, dbg ? ": " : "", dbg ? dbg : "");
    while (glGetError() != GL_NO_ERROR) {}
    if (ctx) ctx->debug_message[0] = '\0';
    return code;
}
