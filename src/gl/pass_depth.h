/* gl/pass_depth.h — a caller's depth buffer as a pass's position input (sss/gl_pass.h, `depth`): the
 * world positions and pixel areas reconstructed into a texture the pass owns (pass_depth.frag.glsl). */
#ifndef SSS_GL_PASS_DEPTH_H
#define SSS_GL_PASS_DEPTH_H

#include "gl/core/gl_core.h"

typedef struct gl_pass_depth {
    GLuint prog, position, fbo;
    int width, height, levels;
} gl_pass_depth;

/* The position texture for width x height with `levels` mip levels (made again when they change). */
sss_result gl_pass_depth_prepare(gl_pass_depth *d, int width, int height, int levels, sss_error *err);
/* Fills level 0 from `depth` with the caller's view and proj (column-major); the frame block is bound
 * (gl_runtime_frame_begin). Timed as "position_from_depth". */
sss_result gl_pass_depth_resolve(gl_pass_depth *d, gl_core *core, GLuint depth, GLuint normal, const float view[16],
                                 const float proj[16], sss_error *err);
void gl_pass_depth_free(gl_pass_depth *d);

#endif
