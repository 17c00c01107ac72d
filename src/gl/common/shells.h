/* gl/common/shells.h — multi-resolution additive splatting into the camera view ("shell
 * splatting", Nalbach et al. 2014), shared by dss and chen2012.
 *
 * The camera's receivers live in a pyramid of `levels` G-buffers: level l is (W / 2^l) x (H / 2^l) of
 * the OUTPUT size W x H, each texel one representative receiver of its block of k 2^l x k 2^l render
 * pixels (k: the SSAA factor, gl_tech_ctx.supersample; shell_receivers.frag.glsl). A splat is drawn
 * once per level; level l only takes the receivers whose world distance d from the splat lies in its
 * shell [D_l, D_(l+1)), with D_0 = 0, D_l = 2^l p / epsilon and the last shell reaching the kernel's
 * reach (the radius holding splat_energy of R_d). p is the world size of one output pixel (k render
 * pixels) at the splat's depth, so a level-l receiver is never larger than epsilon times its distance
 * to the splat: pixels near a splat get detailed transport, far ones a coarse one (Maisch & Ropinski 2020, section
 * 5). Counting the pyramid in output pixels makes `levels` and `epsilon` mean the same at every k:
 * supersampling gives the k = 1 image antialiased at the k = 1 splatting work (a pyramid starting at
 * the render pixel gave every shell texels 1/k as wide, another image and more work;
 * docs/supersampling.md).
 * The resolve pass upsamples levels >= 1 bilinearly (normalised by the receivers' validity so
 * silhouettes do not darken), sums them and applies c_o sqrt(albedo). Level 0 is read per pixel at
 * k = 1; at k > 1 its receivers are the k = 1 ones (the surface point at the centre of the output
 * pixel: shell_receivers.frag.glsl) and every render pixel takes the one of its own output pixel, or
 * of the neighbouring one on its surface where a depth or object edge crosses its output pixel
 * (shell_resolve.frag.glsl): away from edges the image is the k = 1 image (the plane: to 2e-5), at
 * edges each side's near field weighted by its coverage.
 * With k > 1 one more level at the render resolution (SHELL_FINE) samples the sharpest part of the
 * transport per render pixel: where a narrow kernel (Skin1's blue: under a pixel) is sampled once per
 * output pixel, the splats' lattice shows as moire, which supersampling should average away. For a
 * render pixel x, every splat c within fine_radius D output pixels adds w(|x - c|) K(|x - c|) -
 * w(|R_o - c|) K(|R_o - c|), R_o the level-0 receiver standing for x, w = 1 - smoothstep(0, D, .):
 * level 0 keeps its whole shell, each splat counts once per pixel on average (the mean is kept) and
 * nothing jumps around a splat (a split [0, D) here / [D, 2 / epsilon) in level 0, measured at x and
 * at R_o, counted some splats twice and others never: rings around the sparse splats of eval_twist).
 * It costs quads of radius D + 0.75 (k - 1) / k output pixels per splat (eval_backlit +5%, eval_front
 * +10% splatting fragments for D = 2.5; shell_splat.frag.glsl).
 *
 * Splat records are maisch2020's (48 bytes): centre + area, normal + object id + 1, F_t E + disc
 * radius (chen2012) or the surfel lattice's spacing h (dss, whose footprint it sizes); the draw count is the instance count of a DrawArraysIndirect command (4, n, 0, 0). */
#ifndef SSS_GL_COMMON_SHELLS_H
#define SSS_GL_COMMON_SHELLS_H

#include "gl/technique.h"

#define SHELL_MAX_LEVELS 4
#define SHELL_FINE SHELL_MAX_LEVELS /* index of the render-resolution level (k > 1, fine_radius > 0) */
#define SHELL_SPLAT_BYTES 48

typedef struct shell_targets {
    int levels;
    int w[SHELL_MAX_LEVELS + 1], h[SHELL_MAX_LEVELS + 1];
    GLuint recv[SHELL_MAX_LEVELS + 1], accum[SHELL_MAX_LEVELS + 1];
    GLuint fbo_recv[SHELL_MAX_LEVELS + 1], fbo_accum[SHELL_MAX_LEVELS + 1];
    GLuint link;                /* SHELL_FINE: each render pixel's level-0 texel (shell_receivers.frag.glsl) */
    GLuint prog_recv, prog_recv_fine, prog_splat, prog_splat_fine, prog_resolve;
    size_t bytes;
    int frame_w, frame_h, base; /* base: render pixels per level-0 texel side, the SSAA factor k */
    int fine;                   /* the render-resolution level SHELL_FINE exists */
    double fine_radius;         /* its radius D in output pixels (<= level 0's 2 / epsilon) */
    float footprint;            /* dss: the surfels' footprint, f in units of their spacing h (shell_splat.frag.glsl,
                                 * docs/dss.md); 0 (chen2012): one disc of the splat's area */
    GLuint query;               /* fragment shader invocations of the splatting (0: not supported) */
    int query_pending;
} shell_targets;

sss_result shell_create(shell_targets *s, sss_error *err);
/* (Re)creates the pyramid when the level count, the frame size or the SSAA factor changed; with
 * k > 1 and fine_radius > 0 also the render-resolution level for receivers within fine_radius output
 * pixels of a splat. */
sss_result shell_resize(const gl_tech_ctx *c, shell_targets *s, int levels, double fine_radius, sss_error *err);
void shell_free(shell_targets *s);

/* Receivers of every level; clears the accumulation targets. */
void shell_receivers(const gl_tech_ctx *c, shell_targets *s);
/* Additive splatting of the splats counted in cmd (at most capacity of them) into every level. */
void shell_splat(const gl_tech_ctx *c, shell_targets *s, GLuint splats, GLuint cmd, unsigned capacity,
                 double epsilon, int preintegrated);
/* Upsampling + sum + exit factor + reflected light into frame.final. */
void shell_resolve(const gl_tech_ctx *c, shell_targets *s);

/* Splats the last frame drew (min(count, capacity)); 0 before the first frame. */
unsigned shell_splat_count(GLuint cmd, unsigned capacity);

/* The splatting work of the last frame: fragment shader invocations of shell_splat over all levels
 * (a pipeline-statistics query; waits for it). -1 when the GL cannot count them or before the first
 * frame. For tests and benchmarks: the work must not grow with supersampling. */
long long shell_splat_fragments(shell_targets *s);
#endif
