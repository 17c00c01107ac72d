/* gl/env_cut.h — an environment map as K directional lights by median cut (Debevec 2005, "A Median
 * Cut Algorithm for Light Probe Sampling"). Plain C, no GL: the renderer (lights.c), the unit tests and
 * the env_cut fuzz target call it alike.
 *
 * The map is split recursively into regions of equal energy (solid-angle weighted luminance); each
 * region with energy becomes one directional light at its energy centroid carrying the region's
 * integral of L d(omega). Regions that cannot split (one cell wide and tall) stay whole, so a round may
 * split only some regions: the cut never makes more regions than it was given room for.
 */
#ifndef SSS_GL_ENV_CUT_H
#define SSS_GL_ENV_CUT_H

#include "sss/common.h"

typedef struct gl_env_light {
    double to_light[3]; /* unit vector towards the region's energy centroid */
    double rgb[3];      /* the region's integral of L d(omega) (irradiance at normal incidence) */
} gl_env_light;

/* Environment direction of the scene format (docs/scene-format.md): m = (sin t sin p, cos t,
 * -sin t cos p), p = 2 pi (u - 0.5) - rad(rotate_y), t = pi v (v = 0 the top row). */
void gl_env_direction(double u, double v, double rotate_y, double out[3]);

/* Cuts a w x h map of radiance x cell solid angle (rgb: 3 doubles per cell, row 0 = the top row,
 * finite and >= 0; scaled per channel by scale) into at most max_lights lights, written to lights
 * (room for max_lights) and counted in *count (regions without energy give no light, so *count may be
 * smaller). Fails with SSS_ERROR_INVALID_ARGUMENT on sizes < 1 or max_lights < 1, with
 * SSS_ERROR_OUT_OF_MEMORY when its work buffers (about 40 bytes per cell) cannot be allocated. */
sss_result gl_env_median_cut(const double *rgb, int w, int h, const double scale[3], double rotate_y,
                             int max_lights, gl_env_light *lights, int *count, sss_error *err);

#endif
