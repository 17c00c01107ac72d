/* gl/core/core.c — the GL core's life: creation, the scene's resources, sizes, and a frame's shared
 * steps (gl_core.h). */
#include <math.h>
#include <string.h>

#include "gl/core/gl_core.h"

void gl_core_init(gl_core *core, sss_gl_context *ctx, const sss_scene *scene, unsigned reads, int external,
                  int width, int height, int k, int timings)
{
    core->ctx = ctx;
    core->scene = scene;
    core->reads = reads;
    core->external = external;
    core->frame.external = external;
    core->supersample = k;
    core->out_width = width;
    core->out_height = height;
    core->width = width * k;
    core->height = height * k;
    gl_timer_init(&core->timer, timings, ctx->software);
}

/* A pass over a caller's frame has no G-buffer or illumination of its own: only techniques that light
 * the scene's meshes themselves need lights and shadow maps there. */
static sss_result build_scene(gl_core *core, sss_error *err)
{
    sss_result res = gl_scene_upload(core, err);
    if (res == SSS_OK) res = gl_lights_record_kinds(core, err);
    if (res == SSS_OK && (!core->external || (core->reads & GL_READ_LIGHTS))) res = gl_lights_build(core, err);
    if (res == SSS_OK && (core->reads & GL_READ_SPLAT_MESHES)) res = gl_scene_prepare_splats(core, err);
    return res;
}

static sss_result create_frame(gl_core *core, sss_error *err)
{
    int normal_mips = (core->reads & GL_READ_NORMAL_MIPS) != 0;
    sss_result res;
    if (core->external)
        GL_MEM_ACCOUNT(core->frame_gpu_bytes,
                       res = gl_frame_create_external(&core->frame, core->width, core->height, normal_mips, err));
    else
        GL_MEM_ACCOUNT(core->frame_gpu_bytes,
                       res = gl_frame_create(&core->frame, core->width, core->height, normal_mips, err));
    if (res == SSS_OK) GL_MEM_ACCOUNT(core->frame_gpu_bytes, res = gl_ssaa_resize(core, err));
    return res;
}

sss_result gl_core_create_gl(gl_core *core, const gl_lut_set *luts, sss_error *err)
{
    sss_result res = gl_program_vf("shadow.vert.glsl", "shadow.frag.glsl", NULL, &core->prog_shadow, err);
    if (res == SSS_OK)
        res = gl_program_compute("mip_reduce.comp.glsl",
                                 (core->reads & GL_READ_NORMAL_MIPS) ? "#define WITH_NORMALS 1\n" : NULL,
                                 &core->prog_reduce, err);
    if (res != SSS_OK) return res;
    glCreateBuffers(1, &core->ubo_frame);
    glNamedBufferStorage(core->ubo_frame, (GLsizeiptr)gl_frame_ubo_size(), NULL, GL_DYNAMIC_STORAGE_BIT);
    glCreateVertexArrays(1, &core->vao_empty);
    core->luts = luts;
    res = build_scene(core, err);
    core->luts = NULL;
    if (res == SSS_OK) res = create_frame(core, err);
    return res;
}

sss_result gl_core_rebuild_scene(gl_core *core, const sss_scene *scene, sss_error *err)
{
    gl_core next = *core; /* the core's parameters and GL objects, read by the build */
    memset(&next.gs, 0, sizeof next.gs);
    next.scene = scene;
    sss_result res = build_scene(&next, err);
    if (res != SSS_OK) {
        gl_scene_free(&next.gs);
        return res;
    }
    gl_scene_free(&core->gs);
    core->gs = next.gs;
    core->scene = scene;
    return SSS_OK;
}

void gl_core_free(gl_core *core)
{
    gl_ssaa_free(core);
    gl_bounce_free(&core->bounce);
    gl_frame_free(&core->frame);
    gl_scene_free(&core->gs);
    GLuint progs[2] = {core->prog_shadow, core->prog_reduce};
    for (int i = 0; i < 2; i++)
        if (progs[i]) glDeleteProgram(progs[i]);
    if (core->ubo_frame) glDeleteBuffers(1, &core->ubo_frame);
    if (core->vao_empty) glDeleteVertexArrays(1, &core->vao_empty);
    gl_timer_free(&core->timer);
    memset(core, 0, sizeof *core);
}

sss_result gl_core_resize(gl_core *core, int width, int height, int k, sss_error *err)
{
    GL_MEM_ACCOUNT(core->frame_gpu_bytes, gl_frame_free(&core->frame));
    core->frame.external = core->external;
    core->supersample = k;
    core->out_width = width;
    core->out_height = height;
    core->width = width * k;
    core->height = height * k;
    return create_frame(core, err);
}

void gl_core_frame_begin(gl_core *core, const gl_camera *c, double time, double grazing_cutoff)
{
    gl_frame_ubo_write(core, c, time, grazing_cutoff);
    gl_scene_bind(core);
    gl_timer_frame_begin(&core->timer);
}

sss_result gl_core_shadows(gl_core *core, sss_error *err)
{
    gl_timer_begin(&core->timer, "shadows");
    return gl_shadows_render(core, err);
}

sss_result gl_core_mipmaps(gl_core *core, sss_error *err)
{
    gl_timer_begin(&core->timer, "mipmaps");
    return gl_frame_mipmaps(core->ctx, &core->frame, core->prog_reduce, err);
}
