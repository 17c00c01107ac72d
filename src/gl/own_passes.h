/* gl/own_passes.h — the renderer's own frame (renderer.c): its G-buffer and illumination passes, which a
 * pass over a caller's frame (pass.c) takes from the caller instead, and the window's present. */
#ifndef SSS_GL_OWN_PASSES_H
#define SSS_GL_OWN_PASSES_H

#include "gl/runtime.h"

typedef struct gl_own_programs {
    GLuint gbuffer, illumination, present;
} gl_own_programs;

sss_result gl_own_programs_build(gl_own_programs *p, sss_error *err);
void gl_own_programs_free(gl_own_programs *p);
/* Maisch & Ropinski 2020, pass 1: positions + projected pixel area, normals + object id, albedo + eta,
 * depth (timed as "gbuffer"). */
sss_result gl_own_gbuffer(gl_core *core, const gl_own_programs *p, sss_error *err);
/* Pass 3: reflected radiance of the visible surface and transmitted irradiance F_t E (timed as
 * "illumination"). */
sss_result gl_own_illumination(gl_core *core, const gl_own_programs *p, sss_error *err);
/* The output image into the window (a window context only). */
sss_result gl_own_present(const gl_core *core, const gl_own_programs *p, sss_error *err);
/* The G-buffer's object id + 1 (0: background), from the alpha of the normal target, in all three
 * channels. */
sss_result gl_own_read_object_ids(const gl_core *core, sss_image *out, sss_error *err);

#endif
