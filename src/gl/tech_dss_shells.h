/* gl/tech_dss_shells.h — multi-resolution additive splatting into the camera view ("shell
 * splatting", Nalbach et al. 2014), shared by dss and chen2012.
 *
 * The camera's receivers live in a pyramid of `levels` G-buffers: level l is (W / 2^l) x (H / 2^l),
 * each texel one representative receiver of its 2^l x 2^l block (receivers.frag.glsl of maisch2020).
 * A splat is drawn once per level; level l only takes the receivers whose world distance d from the
 * splat lies in its shell [D_l, D_(l+1)), with D_0 = 0, D_l = 2^l p / epsilon and the last shell
 * reaching the kernel's reach (the radius holding splat_energy of R_d). p is the world size of one
 * full-resolution pixel at the splat's depth, so a level-l receiver is never larger than epsilon
 * times its distance to the splat: pixels near a splat get detailed transport, far ones a coarse one
 * (seed 000, section 5). The resolve pass upsamples every level bilinearly (normalised by the
 * receivers' validity so silhouettes do not darken), sums them and applies c_o sqrt(albedo).
 *
 * Splat records are maisch2020's (48 bytes): centre + area, normal + object id + 1, F_t E + disc
 * radius; the draw count is the instance count of a DrawArraysIndirect command (4, n, 0, 0). */
#ifndef SSS_GL_TECH_DSS_SHELLS_H
#define SSS_GL_TECH_DSS_SHELLS_H

#include "gl/gl_internal.h"

#define SHELL_MAX_LEVELS 4
#define SHELL_SPLAT_BYTES 48

typedef struct shell_targets {
    int levels;
    int w[SHELL_MAX_LEVELS], h[SHELL_MAX_LEVELS];
    GLuint recv[SHELL_MAX_LEVELS], accum[SHELL_MAX_LEVELS];
    GLuint fbo_recv[SHELL_MAX_LEVELS], fbo_accum[SHELL_MAX_LEVELS];
    GLuint prog_recv, prog_splat, prog_resolve;
    size_t bytes;
    int frame_w, frame_h;
} shell_targets;

sss_result shell_create(shell_targets *s, sss_error *err);
/* (Re)creates the pyramid when the level count or the frame size changed. */
sss_result shell_resize(sss_gl_renderer *r, shell_targets *s, int levels, sss_error *err);
void shell_free(shell_targets *s);

/* Receivers of every level; clears the accumulation targets. */
void shell_receivers(sss_gl_renderer *r, shell_targets *s);
/* Additive splatting of the splats counted in cmd (at most capacity of them) into every level. */
void shell_splat(sss_gl_renderer *r, shell_targets *s, GLuint splats, GLuint cmd, unsigned capacity,
                 double epsilon, int preintegrated);
/* Upsampling + sum + exit factor + reflected light into frame.final. */
void shell_resolve(sss_gl_renderer *r, shell_targets *s);

/* Splats the last frame drew (min(count, capacity)); 0 before the first frame. */
unsigned shell_splat_count(GLuint cmd, unsigned capacity);

#endif
