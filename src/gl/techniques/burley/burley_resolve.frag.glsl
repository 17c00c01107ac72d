#version 450 core
// burley, pass 3: reflected light + c_o sqrt(albedo) x the scattered light (common/resolve.glsl).
#include "common.glsl"
#include "resolve.glsl"

layout(binding = 4) uniform sampler2D t_scatter; // rgb: A int R^ E dA (burley_scatter.frag.glsl)

vec3 subsurface_light(ivec2 px) { return texelFetch(t_scatter, px, 0).rgb; }
