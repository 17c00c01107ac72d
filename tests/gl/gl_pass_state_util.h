/* tests/gl/gl_pass_state_util.h — the GL state an engine may leave around sss_gl_pass_* calls, for
 * test_gl_pass: every item of the list in docs/integration.md ("What the pass sets and restores") set
 * away from its default (a hostile engine: wireframe, rasterizer discard, primitive restart at index 0,
 * reversed-Z clip control, byte-swapped unpacking, ...), queried back here with the GL's own queries
 * (independently of the library's save/restore), and reset to the GL defaults. */
#ifndef SSS_GL_PASS_STATE_UTIL_H
#define SSS_GL_PASS_STATE_UTIL_H

#include "gl/core/gl_base.h"
#include "gl_test_util.h"

#define MAX_STATE 2000
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
    int n = e == GL_VIEWPORT ? 4 : e == GL_POLYGON_MODE ? 2 : 1;
    for (int i = 0; i < n; i++) put(s, v[i]);
}

static int gl_limit(GLenum e)
{
    GLint n = 0;
    glGetIntegerv(e, &n);
    return n;
}

static const GLenum pixel_store_names[] = {
    GL_PACK_SWAP_BYTES,       GL_PACK_LSB_FIRST,         GL_PACK_ROW_LENGTH,   GL_PACK_IMAGE_HEIGHT,
    GL_PACK_SKIP_ROWS,        GL_PACK_SKIP_PIXELS,       GL_PACK_SKIP_IMAGES,  GL_PACK_ALIGNMENT,
    GL_PACK_COMPRESSED_BLOCK_WIDTH, GL_PACK_COMPRESSED_BLOCK_HEIGHT, GL_PACK_COMPRESSED_BLOCK_DEPTH,
    GL_PACK_COMPRESSED_BLOCK_SIZE, GL_UNPACK_SWAP_BYTES, GL_UNPACK_LSB_FIRST,  GL_UNPACK_ROW_LENGTH,
    GL_UNPACK_IMAGE_HEIGHT,   GL_UNPACK_SKIP_ROWS,       GL_UNPACK_SKIP_PIXELS, GL_UNPACK_SKIP_IMAGES,
    GL_UNPACK_ALIGNMENT,      GL_UNPACK_COMPRESSED_BLOCK_WIDTH, GL_UNPACK_COMPRESSED_BLOCK_HEIGHT,
    GL_UNPACK_COMPRESSED_BLOCK_DEPTH, GL_UNPACK_COMPRESSED_BLOCK_SIZE};
/* hostile values, in the order above (alignments 1 and 2, swapped bytes, rows of 7 pixels, ...) */
static const GLint pixel_store_hostile[] = {1, 1, 7, 3, 1, 2, 1, 1, 4, 4, 1, 16,
                                            1, 1, 7, 3, 1, 2, 1, 2, 4, 4, 1, 16};

/* The enables that are not indexed: hostile is the opposite of the GL default. */
static const struct {
    GLenum cap;
    GLboolean initially;
} caps_list[] = {{GL_DEPTH_TEST, 0},           {GL_CULL_FACE, 0},         {GL_POLYGON_OFFSET_FILL, 0},
                 {GL_POLYGON_OFFSET_LINE, 0},  {GL_POLYGON_OFFSET_POINT, 0}, {GL_RASTERIZER_DISCARD, 0},
                 {GL_PRIMITIVE_RESTART, 0},    {GL_PRIMITIVE_RESTART_FIXED_INDEX, 0}, {GL_STENCIL_TEST, 0},
                 {GL_DEPTH_CLAMP, 0},          {GL_COLOR_LOGIC_OP, 0},    {GL_FRAMEBUFFER_SRGB, 0},
                 {GL_DITHER, 1},               {GL_MULTISAMPLE, 1},       {GL_SAMPLE_ALPHA_TO_COVERAGE, 0},
                 {GL_SAMPLE_ALPHA_TO_ONE, 0},  {GL_SAMPLE_COVERAGE, 0},   {GL_SAMPLE_MASK, 0},
                 {GL_SAMPLE_SHADING, 0},       {GL_LINE_SMOOTH, 0},       {GL_POLYGON_SMOOTH, 0},
                 {GL_PROGRAM_POINT_SIZE, 0},   {GL_TEXTURE_CUBE_MAP_SEAMLESS, 0}};
#define COUNT_OF(a) (sizeof(a) / sizeof((a)[0]))

static void snapshot_fixed(snapshot *s)
{
    static const GLenum ints[] = {GL_DRAW_FRAMEBUFFER_BINDING, GL_READ_FRAMEBUFFER_BINDING, GL_CURRENT_PROGRAM,
                                  GL_VERTEX_ARRAY_BINDING, GL_DEPTH_FUNC, GL_CLIP_ORIGIN, GL_CLIP_DEPTH_MODE,
                                  GL_ACTIVE_TEXTURE, GL_UNIFORM_BUFFER_BINDING, GL_SHADER_STORAGE_BUFFER_BINDING,
                                  GL_ARRAY_BUFFER_BINDING, GL_DRAW_INDIRECT_BUFFER_BINDING,
                                  GL_DISPATCH_INDIRECT_BUFFER_BINDING, GL_PIXEL_PACK_BUFFER_BINDING,
                                  GL_PIXEL_UNPACK_BUFFER_BINDING, GL_QUERY_BUFFER_BINDING, GL_POLYGON_MODE,
                                  GL_CULL_FACE_MODE, GL_FRONT_FACE, GL_PROVOKING_VERTEX,
                                  GL_FRAGMENT_SHADER_DERIVATIVE_HINT};
    for (size_t i = 0; i < COUNT_OF(ints); i++) geti(s, ints[i]);
    for (size_t i = 0; i < COUNT_OF(pixel_store_names); i++) geti(s, pixel_store_names[i]);
    for (size_t i = 0; i < COUNT_OF(caps_list); i++) put(s, glIsEnabled(caps_list[i].cap));
    for (int i = 0; i < gl_limit(GL_MAX_CLIP_DISTANCES); i++) put(s, glIsEnabled(GL_CLIP_DISTANCE0 + (GLenum)i));
    GLboolean b;
    glGetBooleanv(GL_DEPTH_WRITEMASK, &b);
    put(s, b);
    GLfloat f[2];
    glGetFloatv(GL_POLYGON_OFFSET_FACTOR, &f[0]);
    glGetFloatv(GL_POLYGON_OFFSET_UNITS, &f[1]);
    put(s, (long long)(f[0] * 1000));
    put(s, (long long)(f[1] * 1000));
}

/* Per draw buffer and per viewport (glViewport, glDepthRange, glBlendFunc, ... set them all). */
static void snapshot_indexed(snapshot *s)
{
    static const GLenum blend[] = {GL_BLEND_SRC_RGB,   GL_BLEND_DST_RGB,      GL_BLEND_SRC_ALPHA,
                                   GL_BLEND_DST_ALPHA, GL_BLEND_EQUATION_RGB, GL_BLEND_EQUATION_ALPHA};
    for (GLuint i = 0; i < (GLuint)gl_limit(GL_MAX_DRAW_BUFFERS); i++) {
        put(s, glIsEnabledi(GL_BLEND, i));
        GLboolean m[4];
        glGetBooleani_v(GL_COLOR_WRITEMASK, i, m);
        for (int k = 0; k < 4; k++) put(s, m[k]);
        for (size_t k = 0; k < COUNT_OF(blend); k++) {
            GLint v = 0;
            glGetIntegeri_v(blend[k], i, &v);
            put(s, v);
        }
    }
    for (GLuint i = 0; i < (GLuint)gl_limit(GL_MAX_VIEWPORTS); i++) {
        put(s, glIsEnabledi(GL_SCISSOR_TEST, i));
        GLfloat v[4];
        GLdouble d[2];
        glGetFloati_v(GL_VIEWPORT, i, v);
        glGetDoublei_v(GL_DEPTH_RANGE, i, d);
        for (int k = 0; k < 4; k++) put(s, (long long)(v[k] * 1000));
        for (int k = 0; k < 2; k++) put(s, (long long)(d[k] * 1e6));
    }
}

static void snapshot_bindings(snapshot *s)
{
    GLint active = 0;
    glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
    static const GLenum tex[] = {GL_TEXTURE_BINDING_2D, GL_TEXTURE_BINDING_2D_ARRAY, GL_TEXTURE_BINDING_CUBE_MAP,
                                 GL_TEXTURE_BINDING_CUBE_MAP_ARRAY, GL_TEXTURE_BINDING_3D, GL_SAMPLER_BINDING};
    for (int u = 0; u < SSS_GL_PASS_TEXTURE_UNITS; u++) {
        glActiveTexture(GL_TEXTURE0 + (GLenum)u);
        for (size_t t = 0; t < COUNT_OF(tex); t++) geti(s, tex[t]);
    }
    glActiveTexture((GLenum)active);
    static const GLenum img[] = {GL_IMAGE_BINDING_NAME,  GL_IMAGE_BINDING_LEVEL,  GL_IMAGE_BINDING_LAYERED,
                                 GL_IMAGE_BINDING_LAYER, GL_IMAGE_BINDING_ACCESS, GL_IMAGE_BINDING_FORMAT};
    for (GLuint i = 0; i < SSS_GL_PASS_IMAGE_UNITS; i++)
        for (size_t k = 0; k < COUNT_OF(img); k++) {
            GLint v = 0;
            glGetIntegeri_v(img[k], i, &v);
            put(s, v);
        }
    static const GLenum buf[] = {GL_UNIFORM_BUFFER_BINDING,      GL_UNIFORM_BUFFER_START,
                                 GL_UNIFORM_BUFFER_SIZE,         GL_SHADER_STORAGE_BUFFER_BINDING,
                                 GL_SHADER_STORAGE_BUFFER_START, GL_SHADER_STORAGE_BUFFER_SIZE};
    for (GLuint i = 0; i < SSS_GL_PASS_BUFFER_BINDINGS; i++)
        for (size_t k = 0; k < COUNT_OF(buf); k++) {
            GLint64 v = 0;
            glGetInteger64i_v(buf[k], i, &v);
            put(s, v);
        }
}

static void take_snapshot(snapshot *s)
{
    memset(s, 0, sizeof *s);
    snapshot_fixed(s);
    snapshot_indexed(s);
    snapshot_bindings(s);
    CHECK(s->count < MAX_STATE);
}

/* 1 when equal; prints the items that differ. */
static int same_snapshot(const snapshot *a, const snapshot *b)
{
    int same = a->count == b->count;
    for (int i = 0; same && i < a->count; i++)
        if (a->v[i] != b->v[i]) fprintf(stderr, "  state item %d: %lld -> %lld\n", i, a->v[i], b->v[i]);
    return same && memcmp(a->v, b->v, sizeof(long long) * (size_t)a->count) == 0;
}

/* ---- The engine's state ----------------------------------------------------------------------- */

typedef struct caller_gl {
    GLuint fbo, program, vao, tex2d, tex_array, sampler, buffer, image;
} caller_gl;

static void set_caller_objects(caller_gl *c)
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
    for (GLuint u = 0; u < SSS_GL_PASS_TEXTURE_UNITS; u++) glBindTextureUnit(u, (u & 1) ? c->tex_array : c->tex2d);
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
    glBindBuffer(GL_QUERY_BUFFER, c->buffer); /* the pass's query results would land in it */
}

/* Each item that reaches the pass's draws, clears and uploads, set the way it breaks them. */
static void set_caller_fixed(void)
{
    for (size_t i = 0; i < COUNT_OF(caps_list); i++)
        if (caps_list[i].initially) glDisable(caps_list[i].cap);
        else glEnable(caps_list[i].cap);
    for (int i = 0; i < gl_limit(GL_MAX_CLIP_DISTANCES); i++) glEnable(GL_CLIP_DISTANCE0 + (GLenum)i);
    for (size_t i = 0; i < COUNT_OF(pixel_store_names); i++) glPixelStorei(pixel_store_names[i], pixel_store_hostile[i]);
    glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    glPrimitiveRestartIndex(0); /* would cut every indexed mesh at its first vertex */
    glStencilFunc(GL_NEVER, 1, 0xff);
    glLogicOp(GL_CLEAR);
    glSampleCoverage(0.0f, GL_FALSE);
    glSampleMaski(0, 0);
    glMinSampleShading(1.0f);
    glCullFace(GL_FRONT_AND_BACK);
    glFrontFace(GL_CW);
    glProvokingVertex(GL_FIRST_VERTEX_CONVENTION);
    glHint(GL_FRAGMENT_SHADER_DERIVATIVE_HINT, GL_FASTEST);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    glPolygonOffset(2.0f, 3.0f);
    glClipControl(GL_UPPER_LEFT, GL_ZERO_TO_ONE); /* reversed-Z engines */
}

/* Per draw buffer and per viewport, and each index differently. */
static void set_caller_indexed(void)
{
    glViewport(3, 5, 17, 19);
    glViewportIndexedf(1, 1.0f, 2.0f, 30.0f, 40.0f);
    glDepthRange(0.25, 0.75);
    glDepthRangeIndexed(1, 0.1, 0.2);
    glScissor(0, 0, 1, 1);
    glEnable(GL_SCISSOR_TEST);
    glDisablei(GL_SCISSOR_TEST, 3);
    glEnable(GL_BLEND);
    glDisablei(GL_BLEND, 1);
    glColorMask(GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE);
    glColorMaski(1, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ZERO);
    glBlendFunci(2, GL_ZERO, GL_ONE_MINUS_SRC_COLOR);
    glBlendEquationSeparate(GL_MAX, GL_FUNC_SUBTRACT);
    glBlendEquationi(3, GL_MIN);
}

static void set_caller_state(caller_gl *c)
{
    set_caller_objects(c);
    set_caller_fixed();
    set_caller_indexed();
}

/* Back to the GL defaults the next renderer of this process expects. */
static void free_caller_state(caller_gl *c)
{
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glUseProgram(0);
    glBindVertexArray(0);
    glBindSampler(4, 0);
    glActiveTexture(GL_TEXTURE0);
    glBindBuffer(GL_QUERY_BUFFER, 0);
    for (size_t i = 0; i < COUNT_OF(caps_list); i++)
        if (caps_list[i].initially) glEnable(caps_list[i].cap);
        else glDisable(caps_list[i].cap);
    for (int i = 0; i < gl_limit(GL_MAX_CLIP_DISTANCES); i++) glDisable(GL_CLIP_DISTANCE0 + (GLenum)i);
    for (size_t i = 0; i < COUNT_OF(pixel_store_names); i++)
        glPixelStorei(pixel_store_names[i], pixel_store_names[i] == GL_PACK_ALIGNMENT ||
                                                    pixel_store_names[i] == GL_UNPACK_ALIGNMENT ? 4 : 0);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glPrimitiveRestartIndex(0);
    glStencilFunc(GL_ALWAYS, 0, 0xff);
    glLogicOp(GL_COPY);
    glSampleCoverage(1.0f, GL_FALSE);
    glSampleMaski(0, ~0u);
    glMinSampleShading(0.0f);
    glCullFace(GL_BACK);
    glFrontFace(GL_CCW);
    glProvokingVertex(GL_LAST_VERTEX_CONVENTION);
    glHint(GL_FRAGMENT_SHADER_DERIVATIVE_HINT, GL_DONT_CARE);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glPolygonOffset(0.0f, 0.0f);
    glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    glDepthRange(0.0, 1.0);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_BLEND);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glBlendFunc(GL_ONE, GL_ZERO);
    glBlendEquation(GL_FUNC_ADD);
    glDeleteFramebuffers(1, &c->fbo);
    glDeleteProgram(c->program);
    glDeleteVertexArrays(1, &c->vao);
    GLuint t[3] = {c->tex2d, c->tex_array, c->image};
    glDeleteTextures(3, t);
    glDeleteSamplers(1, &c->sampler);
    glDeleteBuffers(1, &c->buffer);
}

#endif
