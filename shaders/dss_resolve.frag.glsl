#version 450 core
// Resolve of the shell splatting (dss, chen2012): every level of the receiver pyramid upsampled
// bilinearly (normalised by the filtered validity in alpha, so silhouettes do not darken) and summed,
// then reflected light + c_o sqrt(albedo) * sum, c_o = F_t(x_o, w_o) / (pi c) (FACTS.md 1).
#include "common.glsl"

layout(binding = 0) uniform sampler2D g_pos;
layout(binding = 1) uniform sampler2D g_nrm;
layout(binding = 2) uniform sampler2D g_albedo;
layout(binding = 3) uniform sampler2D t_refl;
layout(binding = 4) uniform sampler2D t_level0;
layout(binding = 5) uniform sampler2D t_level1;
layout(binding = 6) uniform sampler2D t_level2;
layout(binding = 7) uniform sampler2D t_level3;

uniform int u_levels;

layout(location = 0) out vec4 o_color;

vec3 upsampled(sampler2D t, int level)
{
    // texel i of level l covers full-resolution pixels [i 2^l, (i + 1) 2^l)
    vec2 uv = gl_FragCoord.xy / (exp2(float(level)) * vec2(textureSize(t, 0)));
    vec4 v = textureLod(t, uv, 0.0);
    return v.a > 1e-3 ? v.rgb / v.a : vec3(0.0);
}

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec3 refl = texelFetch(t_refl, px, 0).rgb;
    o_color = vec4(refl, 1.0);
    Material m;
    vec3 weight;
    if (!subsurface_exit(g_pos, g_nrm, g_albedo, px, m, weight)) return;
    vec3 s = texelFetch(t_level0, px, 0).rgb;
    if (u_levels > 1) s += upsampled(t_level1, 1);
    if (u_levels > 2) s += upsampled(t_level2, 2);
    if (u_levels > 3) s += upsampled(t_level3, 3);
    o_color = vec4(refl + weight * s, 1.0);
}
