/* gl/common/tsm.h — light-view G-buffers ("translucent shadow maps", Dachsbacher & Stamminger
 * 2003) shared by chen2012 (its irradiance buffer, Maisch & Ropinski 2020, section 8) and mertens2003 (the light-view
 * irradiance image of Mertens et al. 2003, section 7.1).
 *
 * One view per light: an orthographic box for directional lights, a perspective frustum from the
 * light's position aimed at the bounding sphere of the subsurface objects for point, spot and virtual
 * (area-light) lights. A light inside that sphere gets a 150-degree frustum aimed at its centre, which
 * misses what lies behind it (documented limit). Every object is rasterised (diffuse ones occlude);
 * the targets follow the conventions of the camera G-buffer so mip_reduce.comp.glsl reduces them:
 *   pos: RGBA32F xyz world position, w the surface area of the texel (0: not subsurface),
 *   irr: RGBA32F rgb F_t E of this one light with sqrt(albedo), w object id + 1,
 *   nrm: RGBA32F xyz shading normal, w object id + 1. */
#ifndef SSS_GL_COMMON_TSM_H
#define SSS_GL_COMMON_TSM_H

#include "gl/technique.h"

typedef struct tsm_bounds {
    double centre[3], radius;           /* bounding sphere of the subsurface objects (animation padded) */
    double scene_centre[3], scene_radius; /* of everything (occluders included) */
    int any;                            /* 0: no subsurface object */
} tsm_bounds;

void tsm_bounds_compute(const gl_tech_ctx *c, tsm_bounds *out);

/* World -> clip matrix (column-major, standard depth range) of light `light`'s view. Returns 0 when
 * the light cannot light any subsurface object (no bounds). */
int tsm_light_matrix(const gl_tech_ctx *c, const tsm_bounds *b, int light, float vp[16]);

sss_result tsm_program(GLuint *prog, sss_error *err);

/* Renders light `light` into fbo (3 colour attachments as above + a depth attachment) of size^2. */
void tsm_render(const gl_tech_ctx *c, GLuint prog, GLuint fbo, int size, int light, const float vp[16]);

#endif
