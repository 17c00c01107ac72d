/* gl/pass.c — sss_gl_pass (sss/gl_pass.h): a technique as a pass over the caller's G-buffer.
 *
 * A pass is a runtime (runtime.h) whose core's frame is external: the technique reads the caller's
 * textures through the same gl_frame fields it reads the renderer's targets through, so the techniques
 * have one code path for both. The caller's GL state is saved and the state the passes assume set
 * around every call (pass_state.c). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gl/pass_depth.h"
#include "gl/pass_state.h"
#include "gl/runtime.h"

struct sss_gl_pass {
    gl_runtime rt;         /* its core's frame is external: slots for the caller's textures */
    GLuint attached;       /* the output texture attached to the frame's fbo_final */
    size_t object_count;   /* the registered scene's at creation (surface ids 1..object_count) */
    gl_pass_depth depth;   /* the positions made from a caller's depth buffer (frame.depth) */
};

/* ---- Creation and updates -------------------------------------------------------------------- */

sss_result sss_gl_pass_create(sss_gl_context *ctx, const sss_gl_pass_desc *desc, sss_gl_pass **out, sss_error *err)
{
    if (!out) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sss_gl_pass_create: out is NULL");
    *out = NULL;
    if (!ctx || !desc) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sss_gl_pass_create: no context or desc");
    if (!desc->scene)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                             "sss_gl_pass_create: desc.scene is NULL (it registers the surfaces' materials)");
    if (desc->width < 1 || desc->height < 1)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sss_gl_pass_create: desc.width x desc.height is %dx%d",
                             desc->width, desc->height);
    sss_gl_renderer_desc rd;
    memset(&rd, 0, sizeof rd);
    rd.technique = desc->technique;
    rd.width = desc->width;
    rd.height = desc->height;
    rd.params = desc->params;
    rd.param_count = desc->param_count;
    rd.timings = desc->timings;
    rd.data_file = desc->data_file;
    sss_gl_pass *pass = calloc(1, sizeof *pass);
    if (!pass) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (pass)");
    sss_result res = gl_runtime_init(&pass->rt, ctx, desc->scene, &rd, 1, err);
    if (res == SSS_OK && pass->rt.tech->not_a_pass)
        res = sss_error_set(err, SSS_ERROR_UNSUPPORTED, "sss_gl_pass_create: technique %s cannot run as a pass: %s",
                            pass->rt.tech->info.name, pass->rt.tech->not_a_pass);
    if (res == SSS_OK && !sss_gl_context_make_current(ctx))
        res = sss_error_set(err, SSS_ERROR_UNSUPPORTED, "cannot make the GL context current");
    if (res != SSS_OK) {
        free(pass);
        return res;
    }
    gl_pass_state saved;
    gl_pass_state_save(&saved);
    gl_pass_state_defaults();
    res = gl_runtime_create_gl(&pass->rt, NULL, err);
    if (res != SSS_OK) gl_runtime_free(&pass->rt);
    gl_pass_state_restore(&saved);
    if (res != SSS_OK) {
        free(pass);
        return res;
    }
    pass->object_count = desc->scene->object_count;
    *out = pass;
    return SSS_OK;
}

void sss_gl_pass_destroy(sss_gl_pass *pass)
{
    if (!pass) return;
    sss_gl_context_make_current(pass->rt.core.ctx);
    GL_MEM_ACCOUNT(pass->rt.core.frame_gpu_bytes, gl_pass_depth_free(&pass->depth));
    gl_runtime_free(&pass->rt);
    free(pass);
}

sss_result sss_gl_pass_resize(sss_gl_pass *pass, int width, int height, sss_error *err)
{
    if (!pass) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sss_gl_pass_resize: pass is NULL");
    gl_pass_state saved;
    gl_pass_state_save(&saved);
    gl_pass_state_defaults();
    sss_result res = gl_runtime_resize(&pass->rt, width, height, 1, err);
    pass->attached = 0; /* a new framebuffer when the size changed */
    gl_pass_state_restore(&saved);
    return res;
}

sss_result sss_gl_pass_set_param(sss_gl_pass *pass, const char *name, double value, sss_error *err)
{
    if (!pass) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sss_gl_pass_set_param: pass is NULL");
    gl_pass_state saved;
    gl_pass_state_save(&saved);
    gl_pass_state_defaults();
    sss_result res = gl_runtime_set_param(&pass->rt, name, value, err);
    gl_pass_state_restore(&saved);
    return res;
}

sss_result sss_gl_pass_update_materials(sss_gl_pass *pass, sss_error *err)
{
    if (!pass) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sss_gl_pass_update_materials: pass is NULL");
    if (pass->rt.core.scene->object_count != pass->object_count)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                             "sss_gl_pass_update_materials: the scene has %zu objects, the pass was created with %zu",
                             pass->rt.core.scene->object_count, pass->object_count);
    gl_pass_state saved;
    gl_pass_state_save(&saved);
    gl_pass_state_defaults();
    sss_result res = gl_runtime_update_materials(&pass->rt, NULL, NULL, err);
    gl_pass_state_restore(&saved);
    return res;
}

sss_result sss_gl_pass_update_lights(sss_gl_pass *pass, sss_error *err)
{
    if (!pass) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sss_gl_pass_update_lights: pass is NULL");
    /* the number and kinds are checked for every technique, also those that read no lights (and so
     * build no light records that gl_lights_update could compare) */
    sss_result res = gl_lights_check_kinds(&pass->rt.core, err);
    if (res == SSS_OK && (pass->rt.tech->reads & GL_READ_LIGHTS)) {
        gl_pass_state saved;
        gl_pass_state_save(&saved);
        gl_pass_state_defaults();
        res = gl_runtime_update_lights(&pass->rt, err);
        gl_pass_state_restore(&saved);
    }
    if (res != SSS_OK) sss_error_prefix(err, "sss_gl_pass_update_lights");
    return res;
}

void sss_gl_pass_get_info(const sss_gl_pass *pass, sss_gl_pass_info *out)
{
    if (!out) return;
    memset(out, 0, sizeof *out);
    if (!pass) return;
    unsigned reads = pass->rt.tech->reads;
    out->needs_mips = (reads & GL_READ_MIPS) != 0;
    out->needs_normal_mips = (reads & GL_READ_NORMAL_MIPS) != 0;
    out->uses_lights = (reads & GL_READ_LIGHTS) != 0;
    out->uses_geometry = (reads & (GL_READ_SPLAT_MESHES | GL_READ_LIGHTS)) != 0;
}

void sss_gl_pass_timings(const sss_gl_pass *pass, sss_gl_timings *out)
{
    gl_runtime_timings(pass ? &pass->rt : NULL, out);
}

void sss_gl_pass_stats(sss_gl_pass *pass, sss_gl_stats *out)
{
    gl_runtime_stats(pass ? &pass->rt : NULL, out);
}

/* ---- Frames ---------------------------------------------------------------------------------- */

/* One input texture: a 2D texture of the pass's size in one of `formats` (0-terminated) with at least
 * `levels` mip levels; `field` names it in the message. */
static sss_result check_texture(const gl_core *core, GLuint tex, const char *field, const GLenum *formats,
                                int levels, sss_error *err)
{
    if (!tex || !glIsTexture(tex))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sss_gl_pass_execute: frame.%s (%u) is not a texture",
                             field, tex);
    GLint target = 0, w = 0, h = 0, format = 0, immutable = 0, count = 1;
    glGetTextureParameteriv(tex, GL_TEXTURE_TARGET, &target);
    if (target != GL_TEXTURE_2D)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sss_gl_pass_execute: frame.%s (%u) is not a GL_TEXTURE_2D",
                             field, tex);
    glGetTextureLevelParameteriv(tex, 0, GL_TEXTURE_WIDTH, &w);
    glGetTextureLevelParameteriv(tex, 0, GL_TEXTURE_HEIGHT, &h);
    glGetTextureLevelParameteriv(tex, 0, GL_TEXTURE_INTERNAL_FORMAT, &format);
    if (w != core->width || h != core->height)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sss_gl_pass_execute: frame.%s (%u) is %dx%d, the pass %dx%d",
                             field, tex, w, h, core->width, core->height);
    int ok = 0;
    for (const GLenum *f = formats; *f; f++) ok |= (GLenum)format == *f;
    if (!ok)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                             "sss_gl_pass_execute: frame.%s (%u) has internal format 0x%x (see sss/gl_pass.h)", field, tex,
                             (unsigned)format);
    glGetTextureParameteriv(tex, GL_TEXTURE_IMMUTABLE_FORMAT, &immutable);
    if (immutable) glGetTextureParameteriv(tex, GL_TEXTURE_IMMUTABLE_LEVELS, &count);
    if (levels > 1 && count < levels)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                             "sss_gl_pass_execute: frame.%s (%u) needs %d mip levels (immutable storage), has %d", field,
                             tex, levels, immutable ? count : 1);
    return SSS_OK;
}

static sss_result check_frame(const gl_core *core, const sss_gl_pass_frame *f, sss_error *err)
{
    static const GLenum f32[] = {GL_RGBA32F, 0}, f16_32[] = {GL_RGBA16F, GL_RGBA32F, 0},
                        albedo[] = {GL_RGBA16F, GL_RGBA32F, GL_RGBA8, 0};
    static const GLenum depth[] = {GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT24, GL_DEPTH_COMPONENT16, GL_R32F, 0};
    int mips = (core->reads & GL_READ_MIPS) ? core->frame.levels : 1;
    int normal_mips = (core->reads & GL_READ_NORMAL_MIPS) ? core->frame.levels : 1;
    if (f->position && f->depth)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                             "sss_gl_pass_execute: frame.position (%u) and frame.depth (%u) are both given: one of them",
                             f->position, f->depth);
    sss_result res = f->position || !f->depth ? check_texture(core, f->position, "position", f32, mips, err)
                                              : check_texture(core, f->depth, "depth", depth, 1, err);
    if (res == SSS_OK) res = check_texture(core, f->normal, "normal", normal_mips > 1 ? f32 : f16_32, normal_mips, err);
    if (res == SSS_OK) res = check_texture(core, f->albedo, "albedo", albedo, 1, err);
    if (res == SSS_OK) res = check_texture(core, f->irradiance, "irradiance", f32, mips, err);
    if (res == SSS_OK && f->reflected) res = check_texture(core, f->reflected, "reflected", f16_32, 1, err);
    if (res == SSS_OK) res = check_texture(core, f->output, "output", f16_32, 1, err);
    if (res == SSS_OK && !isfinite(f->time))
        res = sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sss_gl_pass_execute: frame.time %g is not finite", f->time);
    for (int i = 0; i < 16 && res == SSS_OK; i++)
        if (!isfinite(f->view[i]) || !isfinite(f->proj[i]))
            res = sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sss_gl_pass_execute: frame.%s[%d] is not finite",
                                isfinite(f->view[i]) ? "proj" : "view", i);
    return res;
}

/* Points the frame at the caller's textures; the output is attached when it changes. */
static sss_result bind_inputs(sss_gl_pass *pass, const sss_gl_pass_frame *f, sss_error *err)
{
    gl_frame *fr = &pass->rt.core.frame;
    fr->pos = f->position ? f->position : pass->depth.position;
    fr->nrm = f->normal;
    fr->albedo = f->albedo;
    fr->irr = f->irradiance;
    fr->refl = f->reflected ? f->reflected : fr->black;
    fr->final = f->output;
    if (pass->attached == f->output) return SSS_OK;
    glNamedFramebufferTexture(fr->fbo_final, GL_COLOR_ATTACHMENT0, f->output, 0);
    GLenum st = glCheckNamedFramebufferStatus(fr->fbo_final, GL_FRAMEBUFFER);
    if (st != GL_FRAMEBUFFER_COMPLETE) {
        glNamedFramebufferTexture(fr->fbo_final, GL_COLOR_ATTACHMENT0, 0, 0);
        pass->attached = 0;
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                             "sss_gl_pass_execute: frame.output (%u) cannot be rendered to (status 0x%x)", f->output,
                             (unsigned)st);
    }
    pass->attached = f->output;
    return SSS_OK;
}

/* The frame: the caller's G-buffer and illumination, the shadow maps when the technique lights the
 * scene itself, the mip chains when it reads them, then the technique. */
static sss_result run_frame(sss_gl_pass *pass, const sss_gl_pass_frame *frame, const gl_camera *cam, sss_error *err)
{
    gl_runtime *rt = &pass->rt;
    gl_core *core = &rt->core;
    sss_result res = SSS_OK;
    if (!frame->position) /* the positions from the depth buffer, into a target of the pass */
        GL_MEM_ACCOUNT(core->frame_gpu_bytes,
                       res = gl_pass_depth_prepare(&pass->depth, core->width, core->height,
                                                   (rt->tech->reads & GL_READ_MIPS) ? core->frame.levels : 1, err));
    if (res == SSS_OK) res = bind_inputs(pass, frame, err);
    if (res == SSS_OK) res = gl_runtime_frame_begin(rt, cam, frame->time, err);
    if (res != SSS_OK) return res;
    if (!frame->position)
        res = gl_pass_depth_resolve(&pass->depth, core, frame->depth, frame->normal, frame->view, frame->proj, err);
    if (res == SSS_OK && (rt->tech->reads & GL_READ_LIGHTS)) res = gl_core_shadows(&rt->core, err);
    if (res == SSS_OK && (rt->tech->reads & GL_READ_MIPS)) res = gl_core_mipmaps(&rt->core, err);
    return gl_runtime_frame_finish(rt, res, err);
}

sss_result sss_gl_pass_execute(sss_gl_pass *pass, const sss_gl_pass_frame *frame, sss_error *err)
{
    if (!pass || !frame) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "sss_gl_pass_execute: no pass or frame");
    const gl_core *core = &pass->rt.core;
    if (!sss_gl_context_make_current(core->ctx))
        return sss_error_set(err, SSS_ERROR_UNSUPPORTED, "sss_gl_pass_execute: cannot make the GL context current");
    sss_result res = check_frame(core, frame, err);
    if (res != SSS_OK) return res;
    gl_camera cam;
    if (!gl_camera_from_matrices(frame->view, frame->proj, core->height, &cam))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT,
                             "sss_gl_pass_execute: frame.proj is not a perspective projection (OpenGL or reversed-Z "
                             "infinite, column-major)");
    gl_pass_state saved;
    gl_pass_state_save(&saved);
    gl_pass_state_defaults();
    while (glGetError() != GL_NO_ERROR) {} /* the caller's pending errors are not ours */
    res = run_frame(pass, frame, &cam, err);
    if (res == SSS_OK) res = gl_check(core->ctx, "the pass", err);
    if (res != SSS_OK) pass->rt.frame_rendered = 0;
    gl_pass_state_restore(&saved);
    return res;
}
