/* gl/gl_test.h — internal, for the tests only (declared nowhere public, not exported): what a renderer
 * holds, to feed its frame into a pass or to read its technique's state. */
#ifndef SSS_GL_TEST_H
#define SSS_GL_TEST_H

#include "gl/core/gl_core.h"

/* The renderer's core: its frame targets, camera of the last frame, scene. */
const gl_core *gl_test_renderer_core(const sss_gl_renderer *r);
/* The renderer's technique state (its technique's state struct), NULL before creation. */
void *gl_test_renderer_state(const sss_gl_renderer *r);

#endif
