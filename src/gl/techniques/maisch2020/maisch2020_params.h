/* gl/techniques/maisch2020/maisch2020_params.h — the parameters of Maisch & Ropinski 2020, one row each
 * (technique.h: X(name, type, default, min, max, doc)), composed into maisch2020's table and into that of
 * `screen`, its screen-space part alone (techniques/screen), which runs maisch2020 with them. */
#ifndef SSS_GL_MAISCH2020_PARAMS_H
#define SSS_GL_MAISCH2020_PARAMS_H

#include "gl/technique.h"

#define M20_N(X) X(n, SSS_GL_PARAM_INT, 2, 0, 32, "inner kernel of (2n+1)^2 full-resolution samples (Maisch & Ropinski 2020, 4.2)")
#define M20_NL(X) X(n_l, SSS_GL_PARAM_INT, 5, 3, 33, "layer width in samples: 4(n_l - 1) samples per layer (Eq. 7)")
#define M20_LAYERS(X) X(layers, SSS_GL_PARAM_INT, 10, 0, 64, "outer layers of the screen-space pattern (4.2: 10)")
#define M20_BRIGHTENING(X) \
    X(brightening, SSS_GL_PARAM_BOOL, 0, 0, 1, "multiply layer i by sqrt(i) (section 6.1; the paper: 1)")
#define M20_PREINTEGRATED(X)                                                                                      \
    X(preintegrated, SSS_GL_PARAM_BOOL, 1, 0, 1,                                                                  \
      "1: disc-integrated kernel R'_d(r, A) (Eq. 5-6); 0: naive centre sample R_d(r) (Fig. 2)")
#define M20_SCREEN_SPACE(X) X(screen_space, SSS_GL_PARAM_BOOL, 1, 0, 1, "include the screen-space part (section 4)")
#define M20_TRANSLUCENCY(X) \
    X(translucency, SSS_GL_PARAM_BOOL, 1, 0, 1, "include the splatted translucency (section 5)")
#define M20_DIVISOR(X)                                                                                            \
    X(translucency_divisor, SSS_GL_PARAM_INT, 4, 1, 16,                                                           \
      "translucency at width/d x height/d (section 5: a quarter of the resolution)")
#define M20_GRAZING(X)                                                                                            \
    X(grazing_cutoff, SSS_GL_PARAM_FLOAT, 0.2, 0, 1,                                                              \
      "n.v below which pixels leave the screen-space sum (and maisch2020 keeps their splats; Eq. 8, 6.2)")
#define M20_CULL_RULE(X)                                                                                          \
    X(cull_rule, SSS_GL_PARAM_INT, 0, 0, 1, "splats kept: 0 behind x_o AND n.v < cutoff (Eq. 2 and 8); 1: behind OR grazing")
#define M20_IRRADIANCE_CULL(X)                                                                                    \
    X(irradiance_cull, SSS_GL_PARAM_FLOAT, 0, 0, 1e30,                                                            \
      "splats whose largest F_t E channel is at most this are culled (section 5)")
#define M20_DISC(X)                                                                                               \
    X(disc_adjust, SSS_GL_PARAM_INT, 2, 0, 2,                                                                     \
      "splat distance: 1 from the disc-adjusted position x'_i (Eq. 9); 0 from the centre x_i; "                   \
      "2 Eq. 9 + disc radius (the coplanar disc whose nearest point is x'_i)")
#define M20_BICUBIC(X)                                                                                            \
    X(bicubic, SSS_GL_PARAM_BOOL, 1, 0, 1, "bicubic B-spline upsampling (Sigg & Hadwiger, 4 taps); 0: bilinear")
#define M20_SHADOW_OFFSET(X)                                                                                      \
    X(splat_shadow_offset, SSS_GL_PARAM_FLOAT, 0.5, 0, 10,                                                        \
      "splat irradiance looked up this many sqrt(area) above the splat (self-shadowing)")
#define M20_FILTERED(X)                                                                                           \
    X(filtered_layers, SSS_GL_PARAM_INT, 1, 0, 2,                                                                 \
      "outer samples: 1 bilinear within their mip level; 2 the same, but texels whose mean positions "            \
      "disagree (two surfaces) each at their own position; 0 texelFetch (blocky copies)")
#define M20_SPLAT_PREINTEGRATED(X)                                                                                \
    X(splat_preintegrated, SSS_GL_PARAM_BOOL, 1, 0, 1,                                                            \
      "splats read R'_d(r', A) (1, Maisch & Ropinski 2020) or R_d(r') at the disc-adjusted distance")
#define M20_SCREEN_BOUND(X)                                                                                       \
    X(layer_distance_bound, SSS_GL_PARAM_BOOL, 1, 0, 1,                                                           \
      "outer samples at least d_(i-1)/2 pixels (at their depth) from x_o, where their cell lies")
#define M20_OCCLUDED(X)                                                                                           \
    X(occluded_margin, SSS_GL_PARAM_FLOAT, 3, 0, 100,                                                             \
      "also splat front-facing triangles more than this many sqrt(area) behind the visible surface "              \
      "(hidden by another part or object); 0: off (the paper: back-facing only)")
#define M20_SPLIT(X)                                                                                              \
    X(footprint_split, SSS_GL_PARAM_INT, 8, 1, 64,                                                                \
      "samples seen obliquely (a pixel at n.v = c; a cell whose area is e x its face-on area) count as "          \
      "round(min(1/c or e, this)) pieces along their foreshortened axis, the strip capped at this many "          \
      "widths; 1: one disc per sample (the paper, Eq. 6)")
#define M20_GRAZING_SOURCES(X)                                                                                    \
    X(grazing_sources, SSS_GL_PARAM_FLOAT, 0.05, 0, 1,                                                            \
      "visible pixels with this <= |n.v| < grazing_cutoff stay in the screen-space sum (area w^2/|n.v|, mips "    \
      "rebuilt; maisch2020's splats then need n.v below this instead); 0: off (the paper, Eq. 8)")
#define M20_SUPPORT_CUTOFF(X)                                                                                     \
    X(support_cutoff, SSS_GL_PARAM_BOOL, 1, 0, 1,                                                                 \
      "skip outer layers wholly beyond the kernel's support r_max at the pixel's depth (exact: "                  \
      "their samples add 0; needs layer_distance_bound); 0: read every layer")
#define M20_OFFSCREEN(X)                                                                                          \
    X(offscreen_splats, SSS_GL_PARAM_BOOL, 1, 0, 1,                                                               \
      "also splat surface outside the view (front-facing parts off the image, which neither part "                \
      "gathers otherwise: colour drifts under zoom); 0: off (the paper: the back side only)")
#define M20_LAYERS_TO_REACH(X)                                                                                    \
    X(layers_to_reach, SSS_GL_PARAM_BOOL, 1, 0, 1,                                                                \
      "continue the pattern past `layers` until it covers the image or (support_cutoff) the kernel's support, "   \
      "at most 64 layers: a close object's kernel reaches farther; 0: exactly `layers` (the paper)")
#define M20_LAYER_SPLIT(X)                                                                                        \
    X(layer_split, SSS_GL_PARAM_INT, 8, 1, 64,                                                                    \
      "most pieces per oblique outer-layer cell (e x its face-on area), at most footprint_split: the split loop " \
      "runs to the largest count among neighbouring pixels; 1: one disc per cell (the outer layers' cost halves)")
#define M20_OUTER_DIVISOR(X)                                                                                      \
    X(outer_divisor, SSS_GL_PARAM_INT, 4, 1, 4,                                                                   \
      "outer layers evaluated once per d x d block of pixels and upsampled (object- and depth-aware; pixels no "  \
      "block matches evaluate them); the inner (2n+1)^2 block stays per pixel; 1: every pixel (the paper)")

/* maisch2020's table, in its published order. */
#define MAISCH2020_PARAMS(X)                                                                                      \
    M20_N(X) M20_NL(X) M20_LAYERS(X) M20_BRIGHTENING(X) M20_PREINTEGRATED(X) M20_SCREEN_SPACE(X)                  \
    M20_TRANSLUCENCY(X) M20_DIVISOR(X) M20_GRAZING(X) M20_CULL_RULE(X) M20_IRRADIANCE_CULL(X) M20_DISC(X)         \
    M20_BICUBIC(X) M20_SHADOW_OFFSET(X) M20_FILTERED(X) M20_SPLAT_PREINTEGRATED(X) M20_SCREEN_BOUND(X)            \
    M20_OCCLUDED(X) M20_SPLIT(X) M20_GRAZING_SOURCES(X) M20_SUPPORT_CUTOFF(X) M20_OFFSCREEN(X)                    \
    M20_LAYERS_TO_REACH(X) M20_LAYER_SPLIT(X) M20_OUTER_DIVISOR(X)

/* The screen-space part's (techniques/screen): the rows above that its pattern reads. */
#define MAISCH2020_SCREEN_PARAMS(X)                                                                               \
    M20_N(X) M20_NL(X) M20_LAYERS(X) M20_BRIGHTENING(X) M20_PREINTEGRATED(X) M20_GRAZING(X) M20_FILTERED(X)       \
    M20_SCREEN_BOUND(X) M20_SPLIT(X) M20_GRAZING_SOURCES(X) M20_SUPPORT_CUTOFF(X) M20_LAYERS_TO_REACH(X)          \
    M20_LAYER_SPLIT(X) M20_OUTER_DIVISOR(X)

GL_PARAM_STRUCT(maisch2020_params, MAISCH2020_PARAMS);

extern const gl_technique gl_technique_maisch2020;

#endif
