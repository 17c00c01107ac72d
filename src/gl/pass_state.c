/* gl/pass_state.c — saves and restores the GL state a pass changes (the list in sss/gl_pass.h), so
 * that a technique runs inside someone else's frame without disturbing it. Queries only: nothing is
 * allocated. */
#include <string.h>

#include "gl/gl_internal.h"

static const GLenum texture_targets[GL_PASS_TEXTURE_TARGETS] = {
    GL_TEXTURE_2D, GL_TEXTURE_2D_ARRAY, GL_TEXTURE_CUBE_MAP, GL_TEXTURE_CUBE_MAP_ARRAY, GL_TEXTURE_3D};
static const GLenum texture_queries[GL_PASS_TEXTURE_TARGETS] = {
    GL_TEXTURE_BINDING_2D, GL_TEXTURE_BINDING_2D_ARRAY, GL_TEXTURE_BINDING_CUBE_MAP,
    GL_TEXTURE_BINDING_CUBE_MAP_ARRAY, GL_TEXTURE_BINDING_3D};

static const GLenum generic_buffers[GL_PASS_GENERIC_BUFFERS] = {
    GL_UNIFORM_BUFFER, GL_SHADER_STORAGE_BUFFER, GL_ARRAY_BUFFER, GL_DRAW_INDIRECT_BUFFER,
    GL_DISPATCH_INDIRECT_BUFFER, GL_PIXEL_PACK_BUFFER, GL_PIXEL_UNPACK_BUFFER};
static const GLenum generic_queries[GL_PASS_GENERIC_BUFFERS] = {
    GL_UNIFORM_BUFFER_BINDING, GL_SHADER_STORAGE_BUFFER_BINDING, GL_ARRAY_BUFFER_BINDING,
    GL_DRAW_INDIRECT_BUFFER_BINDING, GL_DISPATCH_INDIRECT_BUFFER_BINDING, GL_PIXEL_PACK_BUFFER_BINDING,
    GL_PIXEL_UNPACK_BUFFER_BINDING};

static const GLenum capabilities[GL_PASS_CAPABILITIES] = {GL_DEPTH_TEST, GL_BLEND, GL_CULL_FACE,
                                                          GL_POLYGON_OFFSET_FILL, GL_SCISSOR_TEST};

static void save_buffers(gl_pass_state *s)
{
    static const GLenum indexed[2][3] = {
        {GL_UNIFORM_BUFFER_BINDING, GL_UNIFORM_BUFFER_START, GL_UNIFORM_BUFFER_SIZE},
        {GL_SHADER_STORAGE_BUFFER_BINDING, GL_SHADER_STORAGE_BUFFER_START, GL_SHADER_STORAGE_BUFFER_SIZE}};
    for (int k = 0; k < 2; k++)
        for (GLuint i = 0; i < SSS_GL_PASS_BUFFER_BINDINGS; i++) {
            glGetIntegeri_v(indexed[k][0], i, &s->indexed_buffer[k][i]);
            glGetInteger64i_v(indexed[k][1], i, &s->indexed_start[k][i]);
            glGetInteger64i_v(indexed[k][2], i, &s->indexed_size[k][i]);
        }
    for (int i = 0; i < GL_PASS_GENERIC_BUFFERS; i++) glGetIntegerv(generic_queries[i], &s->generic_buffer[i]);
}

static void restore_buffers(const gl_pass_state *s)
{
    static const GLenum targets[2] = {GL_UNIFORM_BUFFER, GL_SHADER_STORAGE_BUFFER};
    for (int k = 0; k < 2; k++)
        for (GLuint i = 0; i < SSS_GL_PASS_BUFFER_BINDINGS; i++) {
            GLuint b = (GLuint)s->indexed_buffer[k][i];
            if (b && s->indexed_size[k][i] > 0)
                glBindBufferRange(targets[k], i, b, (GLintptr)s->indexed_start[k][i],
                                  (GLsizeiptr)s->indexed_size[k][i]);
            else
                glBindBufferBase(targets[k], i, b);
        }
    /* after the indexed ones: glBindBufferBase/Range also set the generic binding */
    for (int i = 0; i < GL_PASS_GENERIC_BUFFERS; i++) glBindBuffer(generic_buffers[i], (GLuint)s->generic_buffer[i]);
}

static void save_textures(gl_pass_state *s)
{
    glGetIntegerv(GL_ACTIVE_TEXTURE, &s->active_texture);
    for (GLuint u = 0; u < SSS_GL_PASS_TEXTURE_UNITS; u++) {
        glActiveTexture(GL_TEXTURE0 + u);
        for (int t = 0; t < GL_PASS_TEXTURE_TARGETS; t++) glGetIntegerv(texture_queries[t], &s->texture[u][t]);
        glGetIntegerv(GL_SAMPLER_BINDING, &s->sampler[u]);
    }
    glActiveTexture((GLenum)s->active_texture);
    for (GLuint i = 0; i < SSS_GL_PASS_IMAGE_UNITS; i++) {
        GLint *im = s->image[i];
        glGetIntegeri_v(GL_IMAGE_BINDING_NAME, i, &im[0]);
        glGetIntegeri_v(GL_IMAGE_BINDING_LEVEL, i, &im[1]);
        glGetIntegeri_v(GL_IMAGE_BINDING_LAYERED, i, &im[2]);
        glGetIntegeri_v(GL_IMAGE_BINDING_LAYER, i, &im[3]);
        glGetIntegeri_v(GL_IMAGE_BINDING_ACCESS, i, &im[4]);
        glGetIntegeri_v(GL_IMAGE_BINDING_FORMAT, i, &im[5]);
    }
}

static void restore_textures(const gl_pass_state *s)
{
    for (GLuint u = 0; u < SSS_GL_PASS_TEXTURE_UNITS; u++) {
        glActiveTexture(GL_TEXTURE0 + u);
        for (int t = 0; t < GL_PASS_TEXTURE_TARGETS; t++) glBindTexture(texture_targets[t], (GLuint)s->texture[u][t]);
        glBindSampler(u, (GLuint)s->sampler[u]);
    }
    glActiveTexture((GLenum)s->active_texture);
    for (GLuint i = 0; i < SSS_GL_PASS_IMAGE_UNITS; i++) {
        const GLint *im = s->image[i];
        glBindImageTexture(i, (GLuint)im[0], im[1], (GLboolean)im[2], im[3], (GLenum)im[4], (GLenum)im[5]);
    }
}

static void save_fixed(gl_pass_state *s)
{
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &s->draw_fbo);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &s->read_fbo);
    glGetIntegerv(GL_CURRENT_PROGRAM, &s->program);
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &s->vertex_array);
    glGetIntegerv(GL_VIEWPORT, s->viewport);
    for (int i = 0; i < GL_PASS_CAPABILITIES; i++) s->enabled[i] = glIsEnabled(capabilities[i]);
    glGetIntegerv(GL_DEPTH_FUNC, &s->depth_func);
    glGetBooleanv(GL_DEPTH_WRITEMASK, &s->depth_mask);
    glGetBooleanv(GL_COLOR_WRITEMASK, s->color_mask);
    glGetIntegerv(GL_BLEND_SRC_RGB, &s->blend[0]);
    glGetIntegerv(GL_BLEND_DST_RGB, &s->blend[1]);
    glGetIntegerv(GL_BLEND_SRC_ALPHA, &s->blend[2]);
    glGetIntegerv(GL_BLEND_DST_ALPHA, &s->blend[3]);
    glGetIntegerv(GL_BLEND_EQUATION_RGB, &s->blend[4]);
    glGetIntegerv(GL_BLEND_EQUATION_ALPHA, &s->blend[5]);
    glGetFloatv(GL_POLYGON_OFFSET_FACTOR, &s->polygon_offset[0]);
    glGetFloatv(GL_POLYGON_OFFSET_UNITS, &s->polygon_offset[1]);
    glGetIntegerv(GL_CLIP_ORIGIN, &s->clip[0]);
    glGetIntegerv(GL_CLIP_DEPTH_MODE, &s->clip[1]);
    glGetIntegerv(GL_PACK_ALIGNMENT, &s->alignment[0]);
    glGetIntegerv(GL_UNPACK_ALIGNMENT, &s->alignment[1]);
}

static void restore_fixed(const gl_pass_state *s)
{
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)s->draw_fbo);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)s->read_fbo);
    glUseProgram((GLuint)s->program);
    glBindVertexArray((GLuint)s->vertex_array);
    glViewport(s->viewport[0], s->viewport[1], s->viewport[2], s->viewport[3]);
    for (int i = 0; i < GL_PASS_CAPABILITIES; i++) {
        if (s->enabled[i]) glEnable(capabilities[i]);
        else glDisable(capabilities[i]);
    }
    glDepthFunc((GLenum)s->depth_func);
    glDepthMask(s->depth_mask);
    glColorMask(s->color_mask[0], s->color_mask[1], s->color_mask[2], s->color_mask[3]);
    glBlendFuncSeparate((GLenum)s->blend[0], (GLenum)s->blend[1], (GLenum)s->blend[2], (GLenum)s->blend[3]);
    glBlendEquationSeparate((GLenum)s->blend[4], (GLenum)s->blend[5]);
    glPolygonOffset(s->polygon_offset[0], s->polygon_offset[1]);
    glClipControl((GLenum)s->clip[0], (GLenum)s->clip[1]);
    glPixelStorei(GL_PACK_ALIGNMENT, s->alignment[0]);
    glPixelStorei(GL_UNPACK_ALIGNMENT, s->alignment[1]);
}

void gl_pass_state_save(gl_pass_state *s)
{
    memset(s, 0, sizeof *s);
    save_fixed(s);
    save_textures(s);
    save_buffers(s);
}

void gl_pass_state_restore(const gl_pass_state *s)
{
    restore_textures(s);
    restore_buffers(s);
    restore_fixed(s);
}

void gl_pass_state_defaults(void)
{
    for (int i = 0; i < GL_PASS_CAPABILITIES; i++) glDisable(capabilities[i]);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
    glBlendFunc(GL_ONE, GL_ZERO);
    glBlendEquation(GL_FUNC_ADD);
    glPolygonOffset(0.0f, 0.0f);
    glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    for (GLuint u = 0; u < SSS_GL_PASS_TEXTURE_UNITS; u++) glBindSampler(u, 0);
    glActiveTexture(GL_TEXTURE0);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
}
