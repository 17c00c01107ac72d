#version 450 core
// Resolve of the shell splatting (dss, chen2012; common/shells.h): every level of the receiver
// pyramid upsampled bilinearly (normalised by the filtered validity in alpha, so silhouettes do not
// darken) and summed (common/resolve.glsl adds the reflected light and c_o sqrt(albedo)). Level l's texels are u_base 2^l render pixels wide (u_base: the SSAA factor k).
// Level 0 holds the near field, the sharpest part of the transport, and is not interpolated: at k = 1
// it is read per pixel; at k > 1 a render pixel takes the level-0 value of one receiver on its surface
// (shell_level0.glsl). With u_fine the render-resolution level adds, per render pixel, its own transport
// from the nearest splats in place of that receiver's (shell_splat.frag.glsl).
#include "common.glsl"
#include "resolve.glsl"
#include "shell_level0.glsl"

layout(binding = 4) uniform sampler2D t_level0;
layout(binding = 5) uniform sampler2D t_level1;
layout(binding = 6) uniform sampler2D t_level2;
layout(binding = 7) uniform sampler2D t_level3;
layout(binding = 8) uniform sampler2D t_recv0; // level 0's receivers: xyz; w: object id + 1
layout(binding = 9) uniform sampler2D t_fine;  // the render-resolution level (u_fine)
layout(binding = 10) uniform sampler2D t_link; // its level-0 texel per render pixel: xy; w: valid

uniform int u_levels;
uniform int u_base;
uniform int u_fine;

vec3 upsampled(sampler2D t, int level)
{
    // texel i of level l covers render pixels [i k 2^l, (i + 1) k 2^l)
    vec2 uv = gl_FragCoord.xy / (float(u_base) * exp2(float(level)) * vec2(textureSize(t, 0)));
    vec4 v = textureLod(t, uv, 0.0);
    return v.a > 1e-3 ? v.rgb / v.a : vec3(0.0);
}

vec3 level0(ivec2 px, vec3 P, vec3 N, float id)
{
    if (u_base == 1) return texelFetch(t_level0, px, 0).rgb;
    ivec2 q;
    if (u_fine != 0) {
        vec4 link = texelFetch(t_link, px, 0); // chosen by the fine level's receivers pass
        q = link.w > 0.5 ? ivec2(link.xy) : ivec2(-1);
    } else {
        q = level0_texel(t_recv0, u_base, px, P, N, id);
    }
    return q.x >= 0 ? texelFetch(t_level0, q, 0).rgb : upsampled(t_level0, 0);
}

vec3 subsurface_light(ivec2 px)
{
    vec4 N = texelFetch(g_nrm, px, 0);
    vec3 s = level0(px, texelFetch(g_pos, px, 0).xyz, normalize(N.xyz), N.w);
    if (u_fine != 0) s += texelFetch(t_fine, px, 0).rgb;
    if (u_levels > 1) s += upsampled(t_level1, 1);
    if (u_levels > 2) s += upsampled(t_level2, 2);
    if (u_levels > 3) s += upsampled(t_level3, 3);
    return s;
}
