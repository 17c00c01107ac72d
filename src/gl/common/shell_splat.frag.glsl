#version 450 core
// Shell splatting, one level: light transport from a splat to the receiver of this texel,
// F_t E A R_d(|x_i - x_o|) (or the disc-integrated R'_d(r, A) of Maisch & Ropinski 2020, Eq. 5 with
// u_preintegrated), for receivers on the splat's object whose distance lies in this level's shell.
// Additive blending accumulates all splats (no depth test).
// FINE, the render-resolution level (k > 1; common/shells.h): level 0 already holds every splat
// within its shell at the level-0 receiver R_o that stands for this pixel x (r_link), so a splat c
// near x moves part of its transport from R_o to x itself: w(|x - c|) K(|x - c|) - w(|R_o - c|)
// K(|R_o - c|), w = 1 - smoothstep(0, D, .) (v_shell.y = D). The output pixel's render pixels then
// sample the sharp part of the transport each at its own point (the antialiasing). The same weight on
// both sides keeps the mean (over a uniform surface the two terms integrate alike: the plane's
// energy; weighting R_o's term by w(|x - c|) gave +2 .. +4.5%); a weight falling smoothly over all of
// [0, D] leaves no ring around a splat: a hard split ([0, D) at x, [D, ...) at R_o) counted some
// splats twice and others never, and a taper over [D/2, D] still showed rings around the sparse,
// large splats of eval_twist (their difference is ~ |x - R_o|^2 w'' K, w'' 6x smaller here). The quad
// reaches beyond D by the farthest a render pixel's centre lies from its output pixel's,
// 0.71 (k - 1) / k output pixels (u_margin), so it covers every pixel whose R_o is within D of c
// while x is not (a pixel that takes a neighbour's R_o at an edge and is left out keeps level 0's
// value for that splat).
#include "common.glsl"

layout(binding = 0) uniform sampler2D r_receiver; // xyz; w: object id + 1
#ifdef FINE
layout(binding = 1) uniform sampler2D r_link;     // level-0 texel of this pixel, xy; w: valid
layout(binding = 2) uniform sampler2D r_recv0;    // level 0's receivers
#endif

uniform int u_preintegrated;

flat in vec4 v_centre;
flat in vec4 v_flux;
flat in vec3 v_shell; // inner, outer radius; z: level 0's outer radius (FINE)
flat in float v_foot; // the footprint's outer disc radius (dss; world units), 0: one disc of the splat's area
flat in vec4 v_lut;
flat in vec4 v_lut_scales;
flat in ivec2 v_lut_mode;
layout(location = 0) out vec4 o_accum;

// The kernel of a splat of area `area` at distance r (0: R_d at its centre). dss (v_foot > 0): the
// surfels of a triangle lie on a lattice of spacing h, and a disc of a surfel's own area does not tile
// the surface (up to 2 discs cover a point, none between them), so with kernels narrower than h
// (Skin1's blue: about a pixel on the heads, surfels 2-4 pixels) the sum printed the lattice, and on
// thin triangles, whose area is small against h, stripes across them. The footprint is instead the
// mean of three discs of radii 0.5, 0.75 and 1 times f h (v_foot = f h): a tapered profile whose
// Fourier transform stays below 0.031 beyond the lattice's lowest frequency, 2 pi / h (one disc of
// radius h: 0.067, two of 0.7 h and h: 0.080; docs/dss.md). Each disc keeps R_d's energy (the mean of
// R_d over a disc, integrated over the plane, is R_d's integral: the plane's c_o F_t E rho_eff).
// Beyond 2 f h the three means differ from the mean over the mean area only in the a^4 term of the
// disc average R + a^2/8 lap R + a^4/192 lap^2 R: one lookup there.
vec3 kernel(LutInfo L, float r, float area)
{
    if (!(v_foot > 0.0)) return lut_eval(L, r, area);
    float a2 = PI * v_foot * v_foot, a1 = 0.5625 * a2, a0 = 0.25 * a2;
    if (r > 2.0 * v_foot) return lut_eval(L, r, (a0 + a1 + a2) / 3.0);
    return (lut_eval(L, r, a0) + lut_eval(L, r, a1) + lut_eval(L, r, a2)) / 3.0;
}

void main()
{
    vec4 R = texelFetch(r_receiver, ivec2(gl_FragCoord.xy), 0);
    if (R.w != v_flux.w) discard;
    float r = length(R.xyz - v_centre.xyz);
    LutInfo L = LutInfo(v_lut.x, v_lut.y, v_lut.z, v_lut.w, v_lut_mode.x, v_lut_mode.y != 0, v_lut_scales);
    float area = u_preintegrated != 0 ? v_centre.w : 0.0;
    vec3 k;
#ifdef FINE // a program of its own: llvmpipe pays for both sides of a branch on a uniform
    {
        vec4 link = texelFetch(r_link, ivec2(gl_FragCoord.xy), 0);
        if (link.w < 0.5) discard; // no level-0 receiver stands for this pixel (the resolve interpolates)
        float ro = length(texelFetch(r_recv0, ivec2(link.xy), 0).xyz - v_centre.xyz);
        float wx = 1.0 - smoothstep(0.0, v_shell.y, r);
        float wo = ro < v_shell.z ? 1.0 - smoothstep(0.0, v_shell.y, ro) : 0.0; // level 0 counted it
        if (wx <= 0.0 && wo <= 0.0) discard;
        k = (wx > 0.0 ? wx * kernel(L, r, area) : vec3(0.0)) - (wo > 0.0 ? wo * kernel(L, ro, area) : vec3(0.0));
    }
#else
    if (r < v_shell.x || r >= v_shell.y) discard;
    k = kernel(L, r, area);
#endif
    o_accum = vec4(v_flux.rgb * k, 0.0);
}
