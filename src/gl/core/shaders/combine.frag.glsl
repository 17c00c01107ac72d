#version 450 core
// Maisch & Ropinski 2020, pass 7: reflected light + c_o sqrt(albedo) (screen-space sum + upsampled translucency),
// c_o = F_t(x_o, w_o) / (pi c) (docs/physics.md §1). Linear output; tone mapping happens on display/writing
// (docs/scene-format.md exposure rule, common.glsl tone_map).
#include "common.glsl"

layout(binding = 0) uniform sampler2D g_pos;
layout(binding = 1) uniform sampler2D g_nrm;
layout(binding = 2) uniform sampler2D g_albedo;
layout(binding = 3) uniform sampler2D t_refl;
layout(binding = 4) uniform sampler2D t_screen;
layout(binding = 5) uniform sampler2D t_trans;

uniform int u_use_screen;
uniform int u_use_trans;

layout(location = 0) out vec4 o_color;

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec3 refl = texelFetch(t_refl, px, 0).rgb;
    o_color = vec4(refl, 1.0);
    Material m;
    vec3 weight;
    if (!subsurface_exit(g_pos, g_nrm, g_albedo, px, m, weight)) return;
    vec3 s = vec3(0.0);
    if (u_use_screen != 0) s += texelFetch(t_screen, px, 0).rgb;
    if (u_use_trans != 0) s += texelFetch(t_trans, px, 0).rgb;
    o_color = vec4(refl + weight * s, 1.0);
}
