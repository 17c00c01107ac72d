/* gl/gpu_memory.c — the GPU memory of textures and buffers, counted where the GL allocates and frees it.
 *
 * gl_base.h routes glTextureStorage2D/3D, glNamedBufferStorage, glDeleteTextures and glDeleteBuffers of
 * every file that includes it through the functions below, so no allocation of the renderer, its shared
 * passes or a technique escapes the count (there is no other place where the GL is given storage).
 * Counted: objects with immutable storage (the only kind the renderer makes). The size is read back from
 * the GL after the allocation and before the deletion with the same function, so the two always cancel:
 * sum over mip levels of width x height x depth (layers; 6 faces of a cube map) x the bits of the
 * internal format's channels / 8, and GL_BUFFER_SIZE for buffers. That is the logical size the program
 * asked for; drivers pad rows and align allocations, which GL_NVX_gpu_memory_info sees
 * (sss_gl_context_video_memory, bench/bench_techniques.c compares the two).
 * The count is per thread: a GL context is current on one thread, and sss_gl_allocated_bytes() is then
 * the sum over this thread's contexts.
 */
#include "gl/core/gl_base.h"

static _Thread_local long long live_bytes;

long long gl_mem_live(void) { return live_bytes; }

size_t sss_gl_allocated_bytes(void) { return live_bytes > 0 ? (size_t)live_bytes : 0; }

static size_t texel_bits(GLuint t, GLint level)
{
    static const GLenum channels[] = {GL_TEXTURE_RED_SIZE,   GL_TEXTURE_GREEN_SIZE, GL_TEXTURE_BLUE_SIZE,
                                      GL_TEXTURE_ALPHA_SIZE, GL_TEXTURE_DEPTH_SIZE, GL_TEXTURE_STENCIL_SIZE};
    size_t bits = 0;
    for (size_t i = 0; i < sizeof channels / sizeof channels[0]; i++) {
        GLint b = 0;
        glGetTextureLevelParameteriv(t, level, channels[i], &b);
        bits += b > 0 ? (size_t)b : 0;
    }
    return bits;
}

/* Bytes of a texture with immutable storage (0 for any other name, which the GL is not asked about
 * further: a query on a name that is no texture would leave an error for the next gl_check). */
static size_t texture_bytes(GLuint t)
{
    if (!t || !glIsTexture(t)) return 0;
    GLint immutable = 0, levels = 0, target = 0;
    glGetTextureParameteriv(t, GL_TEXTURE_IMMUTABLE_FORMAT, &immutable);
    if (!immutable) return 0;
    glGetTextureParameteriv(t, GL_TEXTURE_IMMUTABLE_LEVELS, &levels);
    glGetTextureParameteriv(t, GL_TEXTURE_TARGET, &target);
    size_t faces = target == GL_TEXTURE_CUBE_MAP ? 6 : 1, bytes = 0;
    for (GLint l = 0; l < levels; l++) {
        GLint w = 0, h = 0, d = 0;
        glGetTextureLevelParameteriv(t, l, GL_TEXTURE_WIDTH, &w);
        glGetTextureLevelParameteriv(t, l, GL_TEXTURE_HEIGHT, &h);
        glGetTextureLevelParameteriv(t, l, GL_TEXTURE_DEPTH, &d);
        size_t texels = (size_t)(w > 0 ? w : 0) * (size_t)(h > 0 ? h : 0) * (size_t)(d > 0 ? d : 0) * faces;
        bytes += texels * ((texel_bits(t, l) + 7) / 8);
    }
    return bytes;
}

static size_t buffer_bytes(GLuint b)
{
    if (!b || !glIsBuffer(b)) return 0;
    GLint immutable = 0;
    glGetNamedBufferParameteriv(b, GL_BUFFER_IMMUTABLE_STORAGE, &immutable);
    if (!immutable) return 0;
    GLint64 size = 0;
    glGetNamedBufferParameteri64v(b, GL_BUFFER_SIZE, &size);
    return size > 0 ? (size_t)size : 0;
}

void gl_mem_texture_storage_2d(GLuint t, GLsizei levels, GLenum format, GLsizei w, GLsizei h)
{
    epoxy_glTextureStorage2D(t, levels, format, w, h);
    live_bytes += (long long)texture_bytes(t);
}

void gl_mem_texture_storage_3d(GLuint t, GLsizei levels, GLenum format, GLsizei w, GLsizei h, GLsizei d)
{
    epoxy_glTextureStorage3D(t, levels, format, w, h, d);
    live_bytes += (long long)texture_bytes(t);
}

void gl_mem_buffer_storage(GLuint b, GLsizeiptr size, const void *data, GLbitfield flags)
{
    epoxy_glNamedBufferStorage(b, size, data, flags);
    live_bytes += (long long)buffer_bytes(b);
}

void gl_mem_delete_textures(GLsizei n, const GLuint *t)
{
    for (GLsizei i = 0; i < n; i++) live_bytes -= (long long)texture_bytes(t[i]);
    epoxy_glDeleteTextures(n, t);
}

void gl_mem_delete_buffers(GLsizei n, const GLuint *b)
{
    for (GLsizei i = 0; i < n; i++) live_bytes -= (long long)buffer_bytes(b[i]);
    epoxy_glDeleteBuffers(n, b);
}
