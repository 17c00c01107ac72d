/* gl/pass_state.c — saves and restores the GL state a pass reads or changes (the list in sss/gl_pass.h
 * and docs/integration.md), and sets it to what the passes assume, so that a technique runs inside
 * someone else's frame without disturbing it and without being disturbed by it: an engine's
 * glPolygonMode(GL_LINE), rasterizer discard, primitive restart, depth range or clip distances would
 * otherwise reach the pass's draws. Queries only: nothing is allocated. */
#include <string.h>

#include "gl/pass_state.h"

static const GLenum texture_targets[GL_PASS_TEXTURE_TARGETS] = {
    GL_TEXTURE_2D, GL_TEXTURE_2D_ARRAY, GL_TEXTURE_CUBE_MAP, GL_TEXTURE_CUBE_MAP_ARRAY, GL_TEXTURE_3D};
static const GLenum texture_queries[GL_PASS_TEXTURE_TARGETS] = {
    GL_TEXTURE_BINDING_2D, GL_TEXTURE_BINDING_2D_ARRAY, GL_TEXTURE_BINDING_CUBE_MAP,
    GL_TEXTURE_BINDING_CUBE_MAP_ARRAY, GL_TEXTURE_BINDING_3D};

/* GL_QUERY_BUFFER: bound, glGetQueryObject* (the pass's timers) would write into it */
static const GLenum generic_buffers[GL_PASS_GENERIC_BUFFERS] = {
    GL_UNIFORM_BUFFER,           GL_SHADER_STORAGE_BUFFER, GL_ARRAY_BUFFER,         GL_DRAW_INDIRECT_BUFFER,
    GL_DISPATCH_INDIRECT_BUFFER, GL_PIXEL_PACK_BUFFER,     GL_PIXEL_UNPACK_BUFFER, GL_QUERY_BUFFER};
static const GLenum generic_queries[GL_PASS_GENERIC_BUFFERS] = {
    GL_UNIFORM_BUFFER_BINDING,          GL_SHADER_STORAGE_BUFFER_BINDING, GL_ARRAY_BUFFER_BINDING,
    GL_DRAW_INDIRECT_BUFFER_BINDING,    GL_DISPATCH_INDIRECT_BUFFER_BINDING, GL_PIXEL_PACK_BUFFER_BINDING,
    GL_PIXEL_UNPACK_BUFFER_BINDING,     GL_QUERY_BUFFER_BINDING};

/* The enables of rasterisation, per-fragment operations and vertex fetch (GL 4.5 core) that are not
 * indexed, with the value the passes assume: the GL defaults (dither and multisample on). The indexed
 * ones (blend per draw buffer, scissor test per viewport, clip distances) are in gl_pass_state. */
static const struct {
    GLenum cap;
    GLboolean on;
} capabilities[] = {
    {GL_DEPTH_TEST, GL_FALSE},          {GL_CULL_FACE, GL_FALSE},
    {GL_POLYGON_OFFSET_FILL, GL_FALSE}, {GL_POLYGON_OFFSET_LINE, GL_FALSE},
    {GL_POLYGON_OFFSET_POINT, GL_FALSE}, {GL_RASTERIZER_DISCARD, GL_FALSE},
    {GL_PRIMITIVE_RESTART, GL_FALSE},   {GL_PRIMITIVE_RESTART_FIXED_INDEX, GL_FALSE},
    {GL_STENCIL_TEST, GL_FALSE},        {GL_DEPTH_CLAMP, GL_FALSE},
    {GL_COLOR_LOGIC_OP, GL_FALSE},      {GL_FRAMEBUFFER_SRGB, GL_FALSE},
    {GL_DITHER, GL_TRUE},               {GL_MULTISAMPLE, GL_TRUE},
    {GL_SAMPLE_ALPHA_TO_COVERAGE, GL_FALSE}, {GL_SAMPLE_ALPHA_TO_ONE, GL_FALSE},
    {GL_SAMPLE_COVERAGE, GL_FALSE},     {GL_SAMPLE_MASK, GL_FALSE},
    {GL_SAMPLE_SHADING, GL_FALSE},      {GL_LINE_SMOOTH, GL_FALSE},
    {GL_POLYGON_SMOOTH, GL_FALSE},      {GL_PROGRAM_POINT_SIZE, GL_FALSE},
    {GL_TEXTURE_CUBE_MAP_SEAMLESS, GL_FALSE}};
_Static_assert(sizeof capabilities / sizeof capabilities[0] == GL_PASS_CAPABILITIES, "GL_PASS_CAPABILITIES");

/* Pixel storage of the uploads (LUTs, albedo textures, tables) and readbacks: the GL defaults. */
static const struct {
    GLenum name;
    GLint value;
} pixel_store[] = {
    {GL_PACK_SWAP_BYTES, 0},   {GL_PACK_LSB_FIRST, 0},    {GL_PACK_ROW_LENGTH, 0},
    {GL_PACK_IMAGE_HEIGHT, 0}, {GL_PACK_SKIP_ROWS, 0},    {GL_PACK_SKIP_PIXELS, 0},
    {GL_PACK_SKIP_IMAGES, 0},  {GL_PACK_ALIGNMENT, 4},    {GL_PACK_COMPRESSED_BLOCK_WIDTH, 0},
    {GL_PACK_COMPRESSED_BLOCK_HEIGHT, 0}, {GL_PACK_COMPRESSED_BLOCK_DEPTH, 0}, {GL_PACK_COMPRESSED_BLOCK_SIZE, 0},
    {GL_UNPACK_SWAP_BYTES, 0}, {GL_UNPACK_LSB_FIRST, 0},  {GL_UNPACK_ROW_LENGTH, 0},
    {GL_UNPACK_IMAGE_HEIGHT, 0}, {GL_UNPACK_SKIP_ROWS, 0}, {GL_UNPACK_SKIP_PIXELS, 0},
    {GL_UNPACK_SKIP_IMAGES, 0}, {GL_UNPACK_ALIGNMENT, 4}, {GL_UNPACK_COMPRESSED_BLOCK_WIDTH, 0},
    {GL_UNPACK_COMPRESSED_BLOCK_HEIGHT, 0}, {GL_UNPACK_COMPRESSED_BLOCK_DEPTH, 0},
    {GL_UNPACK_COMPRESSED_BLOCK_SIZE, 0}};
_Static_assert(sizeof pixel_store / sizeof pixel_store[0] == GL_PASS_PIXEL_STORE, "GL_PASS_PIXEL_STORE");

/* How many of an indexed state this GL has (GL_MAX_DRAW_BUFFERS, ...), at most GL_PASS_INDEXED. */
static int indexed_count(GLenum limit)
{
    GLint n = 0;
    glGetIntegerv(limit, &n);
    return n < 0 ? 0 : n > GL_PASS_INDEXED ? GL_PASS_INDEXED : (int)n;
}

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

/* Per draw buffer: blend enable, function and equation, colour mask. Per viewport: the viewport,
 * depth range and scissor test (glViewport, glDepthRange and glDisable(GL_SCISSOR_TEST) set them all).
 * Per clip distance: its enable. */
static void save_indexed(gl_pass_state *s)
{
    static const GLenum blend_queries[6] = {GL_BLEND_SRC_RGB,   GL_BLEND_DST_RGB,      GL_BLEND_SRC_ALPHA,
                                            GL_BLEND_DST_ALPHA, GL_BLEND_EQUATION_RGB, GL_BLEND_EQUATION_ALPHA};
    s->draw_buffers = indexed_count(GL_MAX_DRAW_BUFFERS);
    s->viewports = indexed_count(GL_MAX_VIEWPORTS);
    s->clip_distances = indexed_count(GL_MAX_CLIP_DISTANCES);
    for (GLuint i = 0; i < (GLuint)s->draw_buffers; i++) {
        s->blend[i] = glIsEnabledi(GL_BLEND, i);
        glGetBooleani_v(GL_COLOR_WRITEMASK, i, s->color_mask[i]);
        for (int k = 0; k < 6; k++) glGetIntegeri_v(blend_queries[k], i, &s->blend_func[i][k]);
    }
    for (GLuint i = 0; i < (GLuint)s->viewports; i++) {
        s->scissor[i] = glIsEnabledi(GL_SCISSOR_TEST, i);
        glGetFloati_v(GL_VIEWPORT, i, s->viewport[i]);
        glGetDoublei_v(GL_DEPTH_RANGE, i, s->depth_range[i]);
    }
    for (int i = 0; i < s->clip_distances; i++) s->clip_distance[i] = glIsEnabled(GL_CLIP_DISTANCE0 + (GLenum)i);
}

static void enable(GLenum cap, GLboolean on)
{
    if (on) glEnable(cap);
    else glDisable(cap);
}

static void enable_indexed(GLenum cap, GLuint i, GLboolean on)
{
    if (on) glEnablei(cap, i);
    else glDisablei(cap, i);
}

static void restore_indexed(const gl_pass_state *s)
{
    for (GLuint i = 0; i < (GLuint)s->draw_buffers; i++) {
        const GLint *b = s->blend_func[i];
        enable_indexed(GL_BLEND, i, s->blend[i]);
        glColorMaski(i, s->color_mask[i][0], s->color_mask[i][1], s->color_mask[i][2], s->color_mask[i][3]);
        glBlendFuncSeparatei(i, (GLenum)b[0], (GLenum)b[1], (GLenum)b[2], (GLenum)b[3]);
        glBlendEquationSeparatei(i, (GLenum)b[4], (GLenum)b[5]);
    }
    for (GLuint i = 0; i < (GLuint)s->viewports; i++) {
        enable_indexed(GL_SCISSOR_TEST, i, s->scissor[i]);
        glViewportIndexedfv(i, s->viewport[i]);
        glDepthRangeIndexed(i, s->depth_range[i][0], s->depth_range[i][1]);
    }
    for (int i = 0; i < s->clip_distances; i++) enable(GL_CLIP_DISTANCE0 + (GLenum)i, s->clip_distance[i]);
}

static void save_fixed(gl_pass_state *s)
{
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &s->draw_fbo);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &s->read_fbo);
    glGetIntegerv(GL_CURRENT_PROGRAM, &s->program);
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &s->vertex_array);
    for (int i = 0; i < GL_PASS_CAPABILITIES; i++) s->enabled[i] = glIsEnabled(capabilities[i].cap);
    for (int i = 0; i < GL_PASS_PIXEL_STORE; i++) glGetIntegerv(pixel_store[i].name, &s->pixel_store[i]);
    glGetIntegerv(GL_DEPTH_FUNC, &s->depth_func);
    glGetBooleanv(GL_DEPTH_WRITEMASK, &s->depth_mask);
    glGetFloatv(GL_POLYGON_OFFSET_FACTOR, &s->polygon_offset[0]);
    glGetFloatv(GL_POLYGON_OFFSET_UNITS, &s->polygon_offset[1]);
    glGetIntegerv(GL_CLIP_ORIGIN, &s->clip_control[0]);
    glGetIntegerv(GL_CLIP_DEPTH_MODE, &s->clip_control[1]);
    glGetIntegerv(GL_POLYGON_MODE, s->polygon_mode); /* front and back: the same in a core profile */
    glGetIntegerv(GL_CULL_FACE_MODE, &s->cull_face);
    glGetIntegerv(GL_FRONT_FACE, &s->front_face);
    glGetIntegerv(GL_PROVOKING_VERTEX, &s->provoking_vertex);
    glGetIntegerv(GL_FRAGMENT_SHADER_DERIVATIVE_HINT, &s->derivative_hint);
}

static void restore_fixed(const gl_pass_state *s)
{
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)s->draw_fbo);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)s->read_fbo);
    glUseProgram((GLuint)s->program);
    glBindVertexArray((GLuint)s->vertex_array);
    for (int i = 0; i < GL_PASS_CAPABILITIES; i++) enable(capabilities[i].cap, s->enabled[i]);
    for (int i = 0; i < GL_PASS_PIXEL_STORE; i++) glPixelStorei(pixel_store[i].name, s->pixel_store[i]);
    glDepthFunc((GLenum)s->depth_func);
    glDepthMask(s->depth_mask);
    glPolygonOffset(s->polygon_offset[0], s->polygon_offset[1]);
    glClipControl((GLenum)s->clip_control[0], (GLenum)s->clip_control[1]);
    glPolygonMode(GL_FRONT_AND_BACK, (GLenum)s->polygon_mode[0]);
    glCullFace((GLenum)s->cull_face);
    glFrontFace((GLenum)s->front_face);
    glProvokingVertex((GLenum)s->provoking_vertex);
    glHint(GL_FRAGMENT_SHADER_DERIVATIVE_HINT, (GLenum)s->derivative_hint);
}

void gl_pass_state_save(gl_pass_state *s)
{
    memset(s, 0, sizeof *s);
    save_fixed(s);
    save_indexed(s);
    save_textures(s);
    save_buffers(s);
}

void gl_pass_state_restore(const gl_pass_state *s)
{
    restore_textures(s);
    restore_buffers(s);
    restore_indexed(s);
    restore_fixed(s);
}

void gl_pass_state_defaults(void)
{
    for (int i = 0; i < GL_PASS_CAPABILITIES; i++) enable(capabilities[i].cap, capabilities[i].on);
    for (int i = 0; i < GL_PASS_PIXEL_STORE; i++) glPixelStorei(pixel_store[i].name, pixel_store[i].value);
    int clip_distances = indexed_count(GL_MAX_CLIP_DISTANCES);
    for (int i = 0; i < clip_distances; i++) glDisable(GL_CLIP_DISTANCE0 + (GLenum)i);
    /* unindexed, these set every draw buffer and every viewport */
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glBlendFunc(GL_ONE, GL_ZERO);
    glBlendEquation(GL_FUNC_ADD);
    glDepthRange(0.0, 1.0);
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
    glPolygonOffset(0.0f, 0.0f);
    glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glCullFace(GL_BACK);
    glFrontFace(GL_CCW);
    glProvokingVertex(GL_LAST_VERTEX_CONVENTION);
    glHint(GL_FRAGMENT_SHADER_DERIVATIVE_HINT, GL_DONT_CARE);
    for (GLuint u = 0; u < SSS_GL_PASS_TEXTURE_UNITS; u++) glBindSampler(u, 0);
    glActiveTexture(GL_TEXTURE0);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    glBindBuffer(GL_QUERY_BUFFER, 0);
}
