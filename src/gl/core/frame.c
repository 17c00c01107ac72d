/* gl/frame.c — screen-sized shared targets and the shared passes every technique can request:
 * G-buffer (Maisch & Ropinski 2020, pass 1), illumination (pass 3) and the area-weighted mip chains (end of pass 3).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/vecmath.h"
#include "gl/core/gl_core.h"

size_t gl_format_bytes(GLenum format)
{
    switch (format) {
    case GL_RGBA32F: return 16;
    case GL_RGB32F: return 12;
    case GL_RGBA16F: return 8;
    case GL_RG32F: return 8;
    case GL_R32F: return 4;
    case GL_RGBA8: return 4;
    case GL_DEPTH_COMPONENT32F: return 4;
    case GL_DEPTH_COMPONENT24: return 4;
    default: return 16;
    }
}

int gl_mip_levels(int width, int height)
{
    int m = width > height ? width : height, levels = 1;
    while (m > 1) {
        m >>= 1;
        levels++;
    }
    return levels;
}

static size_t level_texels(int width, int height, int levels)
{
    size_t n = 0;
    for (int l = 0; l < levels; l++) {
        n += (size_t)width * (size_t)height;
        width = width > 1 ? width / 2 : 1;
        height = height > 1 ? height / 2 : 1;
    }
    return n;
}

GLuint gl_texture_2d(GLenum format, int width, int height, int levels, size_t *bytes)
{
    GLuint t = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &t);
    glTextureStorage2D(t, levels, format, width, height);
    glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, levels > 1 ? GL_NEAREST_MIPMAP_NEAREST : GL_NEAREST);
    glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    if (bytes) *bytes += gl_format_bytes(format) * level_texels(width, height, levels);
    return t;
}

GLuint gl_framebuffer(const GLuint *color, int count, GLuint depth)
{
    GLuint fbo = 0;
    glCreateFramebuffers(1, &fbo);
    GLenum bufs[8];
    for (int i = 0; i < count; i++) {
        glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0 + (GLenum)i, color[i], 0);
        bufs[i] = GL_COLOR_ATTACHMENT0 + (GLenum)i;
    }
    glNamedFramebufferDrawBuffers(fbo, count, bufs);
    if (depth) glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, depth, 0);
    return fbo;
}

sss_result gl_frame_create(gl_frame *f, int width, int height, int normal_mips, sss_error *err)
{
    memset(f, 0, sizeof *f);
    f->width = width;
    f->height = height;
    f->levels = gl_mip_levels(width, height);
    f->normal_mips = normal_mips;
    f->pos = gl_texture_2d(GL_RGBA32F, width, height, f->levels, &f->bytes);
    f->nrm = gl_texture_2d(GL_RGBA32F, width, height, normal_mips ? f->levels : 1, &f->bytes);
    f->albedo = gl_texture_2d(GL_RGBA16F, width, height, 1, &f->bytes);
    f->depth = gl_texture_2d(GL_DEPTH_COMPONENT32F, width, height, 1, &f->bytes);
    f->irr = gl_texture_2d(GL_RGBA32F, width, height, f->levels, &f->bytes);
    /* bilinear within one (premultiplied) level for the wide screen-space samples */
    GLuint filtered[2] = {f->pos, f->irr};
    for (int i = 0; i < 2; i++) {
        glTextureParameteri(filtered[i], GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_NEAREST);
        glTextureParameteri(filtered[i], GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    }
    f->refl = gl_texture_2d(GL_RGBA16F, width, height, 1, &f->bytes);
    f->final = gl_texture_2d(GL_RGBA32F, width, height, 1, &f->bytes);
    GLuint g[3] = {f->pos, f->nrm, f->albedo};
    f->fbo_gbuffer = gl_framebuffer(g, 3, f->depth);
    GLuint l[2] = {f->irr, f->refl};
    f->fbo_light = gl_framebuffer(l, 2, 0);
    f->fbo_final = gl_framebuffer(&f->final, 1, 0);
    GLuint fbos[3] = {f->fbo_gbuffer, f->fbo_light, f->fbo_final};
    for (int i = 0; i < 3; i++) {
        GLenum st = glCheckNamedFramebufferStatus(fbos[i], GL_FRAMEBUFFER);
        if (st != GL_FRAMEBUFFER_COMPLETE) {
            gl_frame_free(f);
            return sss_error_set(err, SSS_ERROR_UNSUPPORTED,
                                 "OpenGL: a %dx%d render target is incomplete (status 0x%x)", width, height,
                                 (unsigned)st);
        }
    }
    return SSS_OK;
}

sss_result gl_frame_create_external(gl_frame *f, int width, int height, int normal_mips, sss_error *err)
{
    memset(f, 0, sizeof *f);
    f->external = 1;
    f->width = width;
    f->height = height;
    f->levels = gl_mip_levels(width, height);
    f->normal_mips = normal_mips;
    f->black = gl_texture_2d(GL_RGBA16F, width, height, 1, &f->bytes);
    const float zero[4] = {0, 0, 0, 0};
    glClearTexImage(f->black, 0, GL_RGBA, GL_FLOAT, zero);
    glCreateFramebuffers(1, &f->fbo_final);
    glNamedFramebufferDrawBuffer(f->fbo_final, GL_COLOR_ATTACHMENT0);
    (void)err;
    return SSS_OK;
}

void gl_frame_free(gl_frame *f)
{
    if (f->external) {
        glDeleteFramebuffers(1, &f->fbo_final);
        glDeleteTextures(1, &f->black);
        memset(f, 0, sizeof *f);
        return;
    }
    GLuint fb[3] = {f->fbo_gbuffer, f->fbo_light, f->fbo_final};
    glDeleteFramebuffers(3, fb);
    GLuint t[7] = {f->pos, f->nrm, f->albedo, f->depth, f->irr, f->refl, f->final};
    glDeleteTextures(7, t);
    memset(f, 0, sizeof *f);
}

void gl_core_scene_camera(gl_core *core, gl_camera *c)
{
    sss_camera cam = core->scene->camera;
    cam.width = core->width;
    cam.height = core->height;
    sss_camera_basis b;
    if (sss_camera_basis_init(&cam, &b, NULL) != SSS_OK) b = core->scene->basis;
    /* Depth range from the scene bounds (padded for animations): far beyond the farthest corner. */
    double far_d = 0.0;
    for (int i = 0; i < 8; i++) {
        double p[3] = {(i & 1) ? core->gs.bounds_max[0] : core->gs.bounds_min[0],
                       (i & 2) ? core->gs.bounds_max[1] : core->gs.bounds_min[1],
                       (i & 4) ? core->gs.bounds_max[2] : core->gs.bounds_min[2]};
        double d = 0.0;
        for (int k = 0; k < 3; k++) d += (p[k] - b.origin[k]) * (p[k] - b.origin[k]);
        if (sqrt(d) > far_d) far_d = sqrt(d);
    }
    if (!(far_d > 0.0)) far_d = 1.0;
    core->far_plane = far_d * 1.05;
    double near_plane = core->far_plane * 1e-5;
    double v[16], p[16];
    sss_camera_view_matrix(&b, v);
    sss_camera_projection_matrix(&b, near_plane, core->far_plane, p);
    /* Reversed-Z with an infinite far plane (depth = near / distance along the view axis, used with
     * glClipControl(ZERO_TO_ONE), a GREATER test and a 32-bit float depth buffer): nearly uniform
     * relative precision. The standard mapping with near = 1e-5 far resolves only ~0.1% of the
     * distance and let the inner and outer layers of thin shells fight. */
    p[10] = 0.0;
    p[11] = near_plane;
    memset(c, 0, sizeof *c);
    m4_from_rows(v, c->view);
    m4_from_rows(p, c->proj);
    for (int k = 0; k < 3; k++) {
        c->position[k] = b.origin[k];
        c->forward[k] = b.forward[k];
    }
    c->near_plane = near_plane;
    c->pixel_size = 2.0 * b.tan_half[1] / core->height;
}

int gl_camera_from_matrices(const float view[16], const float proj[16], int height, gl_camera *c)
{
    memset(c, 0, sizeof *c);
    /* a perspective projection: w = -z_eye, focal lengths on the diagonal */
    if (proj[11] != -1.0f || proj[15] != 0.0f || !(proj[0] > 0.0f) || !(proj[5] > 0.0f)) return 0;
    double near_plane = proj[10] == 0.0f ? proj[14] : proj[14] / (proj[10] - 1.0);
    if (!(near_plane > 0.0) || !isfinite(near_plane)) return 0;
    memcpy(c->view, view, sizeof c->view);
    memcpy(c->proj, proj, sizeof c->proj);
    c->proj[10] = 0.0f; /* reversed-Z, infinite far plane (gl_camera_from_scene) */
    c->proj[14] = (float)near_plane;
    /* eye -> world: the position is -R^T t, the view axis -(third row of R) */
    for (int i = 0; i < 3; i++) {
        double d = 0.0;
        for (int j = 0; j < 3; j++) d += (double)view[4 * i + j] * view[12 + j];
        c->position[i] = -d;
        c->forward[i] = -(double)view[4 * i + 2];
    }
    c->near_plane = near_plane;
    c->pixel_size = 2.0 / (proj[5] * (double)height);
    return 1;
}

/* Mirrors common.glsl FrameBlock (std140). */
typedef struct frame_ubo {
    float view[16], proj[16], view_proj[16], inv_view_proj[16];
    float camera_pos[4], camera_fwd[4], viewport[4];
    int32_t counts[4];
    float misc[4];
} frame_ubo;
_Static_assert(sizeof(frame_ubo) == 4 * 64 + 5 * 16, "frame_ubo must match common.glsl FrameBlock (std140)");

void gl_frame_ubo_write(gl_core *core, const gl_camera *c, double time, double grazing_cutoff)
{
    frame_ubo u;
    memset(&u, 0, sizeof u);
    memcpy(u.view, c->view, sizeof u.view);
    memcpy(u.proj, c->proj, sizeof u.proj);
    m4_mul(u.proj, u.view, u.view_proj);
    if (!m4_inverse(u.view_proj, u.inv_view_proj)) memset(u.inv_view_proj, 0, sizeof u.inv_view_proj);
    core->view.camera = *c;
    memcpy(core->view.view_proj, u.view_proj, sizeof core->view.view_proj);
    core->view.time = time;
    for (int k = 0; k < 3; k++) {
        u.camera_pos[k] = (float)c->position[k];
        u.camera_fwd[k] = (float)c->forward[k];
    }
    u.camera_pos[3] = (float)time;
    u.camera_fwd[3] = (float)c->pixel_size;
    u.viewport[0] = (float)core->width;
    u.viewport[1] = (float)core->height;
    u.viewport[2] = 1.0f / (float)core->width;
    u.viewport[3] = 1.0f / (float)core->height;
    u.counts[0] = core->gs.object_count;
    u.counts[1] = core->gs.light_count;
    u.counts[2] = core->gs.mat.count;
    u.counts[3] = core->frame.levels;
    u.misc[0] = (float)core->scene->render.exposure;
    u.misc[1] = (float)grazing_cutoff; /* Maisch & Ropinski 2020, Eq. 8 */
    u.misc[2] = (float)core->shared[GL_P_SHADOW_BIAS];
    u.misc[3] = (float)c->near_plane;
    glNamedBufferSubData(core->ubo_frame, 0, sizeof u, &u);
    glBindBufferBase(GL_UNIFORM_BUFFER, GL_UBO_FRAME, core->ubo_frame);
}

size_t gl_frame_ubo_size(void) { return sizeof(frame_ubo); }

void gl_fullscreen_triangle(GLuint vao_empty)
{
    glBindVertexArray(vao_empty);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
}

void gl_scene_draw_objects(const gl_scene *gs, GLint object_uniform, int subsurface_only)
{
    for (int i = 0; i < gs->object_count; i++) {
        const gl_object *o = &gs->objects[i];
        if (subsurface_only && !o->subsurface) continue;
        glUniform1i(object_uniform, i);
        glBindVertexArray(o->vao);
        glDrawElements(GL_TRIANGLES, (GLsizei)(3 * o->triangle_count), GL_UNSIGNED_INT, NULL);
    }
    glBindVertexArray(0);
}

sss_result gl_frame_mipmaps(sss_gl_context *ctx, const gl_frame *f, GLuint prog, sss_error *err)
{
    glUseProgram(prog);
    GLint u_pre = glGetUniformLocation(prog, "u_src_premultiplied");
    GLint u_level = glGetUniformLocation(prog, "u_dst_level");
    glUniform2i(glGetUniformLocation(prog, "u_base_size"), f->width, f->height);
    int w = f->width, h = f->height;
    for (int l = 1; l < f->levels; l++) {
        int dw = w > 1 ? w / 2 : 1, dh = h > 1 ? h / 2 : 1;
        glBindImageTexture(0, f->pos, l - 1, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
        glBindImageTexture(1, f->irr, l - 1, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
        glBindImageTexture(2, f->pos, l, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        glBindImageTexture(3, f->irr, l, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        if (f->normal_mips) {
            glBindImageTexture(4, f->nrm, l - 1, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
            glBindImageTexture(5, f->nrm, l, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        }
        glUniform1i(u_pre, l > 1);
        glUniform1i(u_level, l);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        glDispatchCompute((GLuint)(dw + 7) / 8, (GLuint)(dh + 7) / 8, 1);
        w = dw;
        h = dh;
    }
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    return gl_check(ctx, "the mip-chain pass", err);
}

sss_result gl_read_texture_rgb(GLuint tex, int level, int width, int height, sss_image *out, sss_error *err)
{
    memset(out, 0, sizeof *out);
    sss_result res = sss_image_create(out, width, height, err);
    if (res != SSS_OK) return res;
    size_t n = (size_t)width * (size_t)height;
    float *rgba = malloc(n * 4 * sizeof(float));
    if (!rgba) {
        sss_image_free(out);
        return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (read-back of %dx%d)", width, height);
    }
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glGetTextureImage(tex, level, GL_RGBA, GL_FLOAT, (GLsizei)(n * 4 * sizeof(float)), rgba);
    /* GL rows run bottom-up; images are stored top row first. */
    for (int y = 0; y < height; y++) {
        const float *src = rgba + (size_t)(height - 1 - y) * (size_t)width * 4;
        float *dst = out->pixels + (size_t)y * (size_t)width * 3;
        for (int x = 0; x < width; x++)
            for (int c = 0; c < 3; c++) dst[3 * x + c] = src[4 * x + c];
    }
    free(rgba);
    return SSS_OK;
}
