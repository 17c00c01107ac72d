/* gl/pass_state.h — the caller's GL state around every call of a pass (sss/gl_pass.h): saved, the
 * state the passes assume set, restored (pass_state.c; docs/integration.md lists what is covered). */
#ifndef SSS_GL_PASS_STATE_H
#define SSS_GL_PASS_STATE_H

#include "gl/core/gl_base.h"

#define GL_PASS_TEXTURE_TARGETS 5
#define GL_PASS_GENERIC_BUFFERS 8
#define GL_PASS_CAPABILITIES 23
#define GL_PASS_PIXEL_STORE 24
#define GL_PASS_INDEXED 16 /* draw buffers, viewports and clip distances saved (at most) */
typedef struct gl_pass_state {
    GLint draw_fbo, read_fbo, program, vertex_array;
    GLboolean enabled[GL_PASS_CAPABILITIES], depth_mask;
    GLint depth_func, clip_control[2], polygon_mode[2], cull_face, front_face, provoking_vertex, derivative_hint;
    GLint pixel_store[GL_PASS_PIXEL_STORE];
    GLfloat polygon_offset[2];
    /* indexed state: per draw buffer, per viewport, per clip distance (counts: this GL's, capped) */
    int draw_buffers, viewports, clip_distances;
    GLboolean blend[GL_PASS_INDEXED], color_mask[GL_PASS_INDEXED][4];
    GLint blend_func[GL_PASS_INDEXED][6]; /* src rgb, dst rgb, src alpha, dst alpha, equation rgb, alpha */
    GLboolean scissor[GL_PASS_INDEXED], clip_distance[GL_PASS_INDEXED];
    GLfloat viewport[GL_PASS_INDEXED][4];
    GLdouble depth_range[GL_PASS_INDEXED][2];
    GLint active_texture;
    GLint texture[SSS_GL_PASS_TEXTURE_UNITS][GL_PASS_TEXTURE_TARGETS], sampler[SSS_GL_PASS_TEXTURE_UNITS];
    GLint image[SSS_GL_PASS_IMAGE_UNITS][6]; /* name, level, layered, layer, access, format */
    GLint indexed_buffer[2][SSS_GL_PASS_BUFFER_BINDINGS]; /* uniform, shader storage */
    GLint64 indexed_start[2][SSS_GL_PASS_BUFFER_BINDINGS], indexed_size[2][SSS_GL_PASS_BUFFER_BINDINGS];
    GLint generic_buffer[GL_PASS_GENERIC_BUFFERS];
} gl_pass_state;
void gl_pass_state_save(gl_pass_state *s);
void gl_pass_state_restore(const gl_pass_state *s);
/* The GL state the passes assume (the list in sss/gl_pass.h and docs/integration.md: the GL defaults,
 * no sampler objects, pixel or query buffers), set after saving the caller's. */
void gl_pass_state_defaults(void);

#endif
