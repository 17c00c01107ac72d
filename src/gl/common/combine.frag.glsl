#version 450 core
// Maisch & Ropinski 2020, pass 7 (maisch2020; sam without a surface technique): the screen-space sum plus
// the upsampled translucency, each when used (common/resolve.glsl adds the reflected light and c_o
// sqrt(albedo)).
#include "common.glsl"
#include "resolve.glsl"

layout(binding = 4) uniform sampler2D t_screen;
layout(binding = 5) uniform sampler2D t_trans;

uniform int u_use_screen;
uniform int u_use_trans;

vec3 subsurface_light(ivec2 px)
{
    vec3 s = vec3(0.0);
    if (u_use_screen != 0) s += texelFetch(t_screen, px, 0).rgb;
    if (u_use_trans != 0) s += texelFetch(t_trans, px, 0).rgb;
    return s;
}
