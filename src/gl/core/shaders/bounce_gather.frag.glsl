#version 450 core
// Interreflection stage, step 3 (interreflection.c): the one-bounce irradiance at the centre pixel of
// every stride x stride block of the G-buffer (bounce_apply.frag.glsl upsamples it).
#include "common.glsl"
#include "bounce_common.glsl"

layout(binding = 0) uniform sampler2D g_pos;
layout(binding = 1) uniform sampler2D g_nrm;
uniform int u_stride;

layout(location = 0) out vec4 o_bounce; // rgb E; w: 1 where a surface was gathered
layout(location = 1) out vec4 o_plane;  // the gathered point's tangent plane: normal, dot(normal, point)

void main()
{
    ivec2 px = min(ivec2(gl_FragCoord.xy) * u_stride + u_stride / 2, ivec2(u_viewport.xy) - 1);
    vec4 N = texelFetch(g_nrm, px, 0);
    o_bounce = vec4(0.0);
    o_plane = vec4(0.0);
    if (N.w < 0.5) return;
    vec3 x = texelFetch(g_pos, px, 0).xyz, n = normalize(N.xyz);
    o_bounce = vec4(bounce_irradiance(x, n), 1.0);
    o_plane = vec4(n, dot(n, x));
}
