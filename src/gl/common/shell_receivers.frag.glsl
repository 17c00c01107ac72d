#version 450 core
// Receivers of the shell-splatting pyramid (dss, chen2012; common/shells.h). A texel of level l
// stands for 2^l x 2^l output pixels, u_divisor = k 2^l render pixels (k = u_base, the SSAA factor).
// Its receiver is the one the k = 1 pyramid takes, the surface point seen at the centre of the output
// pixel at the middle of its block (maisch2020_receivers.frag.glsl: the block's centre pixel), so
// that supersampling keeps the image: for odd k that point is the centre of a render pixel, for even
// k the corner of four, where the receiver is the mean of their positions when the four lie on one
// surface (same object, within a render pixel of their tangent plane), else the first of them on a
// subsurface object. When none of these is a subsurface pixel the first subsurface pixel of the
// block is taken (silhouettes), and the texel marks itself valid in the accumulation target's alpha
// (the upsampling divides by it, so silhouettes do not darken).
// FINE: the render-resolution level (k > 1): every subsurface render pixel is its own receiver, and
// its level-0 receiver (shell_level0.glsl, as the resolve reads it) is recorded in o_link for the fine
// splatting, which replaces that receiver's transport from the nearest splats by the pixel's own.
#include "common.glsl"
#include "shell_level0.glsl"

layout(binding = 0) uniform sampler2D g_pos;
layout(binding = 1) uniform sampler2D g_nrm;

uniform int u_divisor;
uniform int u_base;

layout(location = 0) out vec4 o_receiver; // xyz position; w: object id + 1 (0: none)
layout(location = 1) out vec4 o_accum;    // initial accumulation: (0, 0, 0, valid)

bool is_subsurface(vec4 N)
{
    if (N.w < 0.5) return false;
    return materials[int(objects[int(N.w - 0.5)].anim.y)].albedo.w < 0.5;
}

#ifdef FINE
layout(binding = 2) uniform sampler2D t_recv0; // level 0's receivers
layout(location = 2) out vec4 o_link;          // the level-0 texel standing for this pixel: xy; w: valid

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec4 N = texelFetch(g_nrm, px, 0);
    o_receiver = vec4(0.0);
    o_accum = vec4(0.0);
    o_link = vec4(0.0);
    if (!is_subsurface(N)) return;
    vec3 P = texelFetch(g_pos, px, 0).xyz;
    o_receiver = vec4(P, N.w);
    o_accum = vec4(0.0, 0.0, 0.0, 1.0);
    ivec2 q = level0_texel(t_recv0, u_base, px, P, normalize(N.xyz), N.w);
    if (q.x >= 0) o_link = vec4(vec2(q), 0.0, 1.0);
}
#else
void main()
{
    ivec2 size = textureSize(g_nrm, 0);
    ivec2 base = ivec2(gl_FragCoord.xy) * u_divisor;
    // the middle output pixel of the block (k = 1: its pixel (2^l / 2, 2^l / 2)), its render pixels
    ivec2 mid = base + ((u_divisor / u_base) / 2) * u_base + (u_base - 1) / 2;
    int n = 2 - (u_base & 1); // 1 x 1 (odd k) or 2 x 2 (even k) render pixels around its centre
    vec4 R = vec4(0.0);
    vec3 sum = vec3(0.0);
    vec4 N0 = vec4(0.0);
    int found = 0;
    bool one_surface = true;
    for (int y = 0; y < n; y++)
        for (int x = 0; x < n; x++) {
            ivec2 q = min(mid + ivec2(x, y), size - 1);
            vec4 N = texelFetch(g_nrm, q, 0);
            if (!is_subsurface(N)) {
                one_surface = false;
                continue;
            }
            vec3 P = texelFetch(g_pos, q, 0).xyz;
            if (found == 0) {
                R = vec4(P, N.w);
                N0 = N;
            } else if (abs(N.w - N0.w) > 0.5 ||
                       abs(dot(P - R.xyz, normalize(N0.xyz))) >
                           max(length(P - u_camera_pos.xyz), u_misc.w) * u_camera_fwd.w) {
                one_surface = false;
            }
            sum += P;
            found++;
        }
    if (found == n * n && one_surface) R.xyz = sum / float(found);
    for (int y = 0; y < u_divisor && found == 0; y++)
        for (int x = 0; x < u_divisor && found == 0; x++) {
            ivec2 q = min(base + ivec2(x, y), size - 1);
            vec4 N = texelFetch(g_nrm, q, 0);
            if (is_subsurface(N)) {
                R = vec4(texelFetch(g_pos, q, 0).xyz, N.w);
                found = 1;
            }
        }
    o_receiver = R;
    o_accum = vec4(0.0, 0.0, 0.0, found > 0 ? 1.0 : 0.0);
}
#endif
