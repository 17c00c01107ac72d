#version 450 core
// Technique "sam": adds c_o sqrt(albedo) L~_o- (Maisch & Ropinski 2017, Eq. 12 interpolated per pixel) to the frame of
// the surface technique (blended additively into frame.final), c_o = F_t(x_o, w_o) / (pi c) as in
// combine.frag.glsl, so the translucency is in the same absolute units as the reference (docs/physics.md §1).
#include "common.glsl"

layout(binding = 0) uniform sampler2D g_pos;
layout(binding = 1) uniform sampler2D g_nrm;
layout(binding = 2) uniform sampler2D g_albedo;
layout(binding = 3) uniform sampler2D t_trans;

layout(location = 0) out vec4 o_color;

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec4 N = texelFetch(g_nrm, px, 0);
    o_color = vec4(0.0);
    if (N.w < 0.5) return;
    Material m = materials[int(objects[int(N.w - 0.5)].anim.y)];
    if (m.albedo.w > 0.5) return;
    vec3 p = texelFetch(g_pos, px, 0).xyz;
    vec3 v = normalize(u_camera_pos.xyz - p);
    vec3 alb = texelFetch(g_albedo, px, 0).rgb;
    o_color = vec4(exit_factor(m, normalize(N.xyz), v) * sqrt(alb) * texelFetch(t_trans, px, 0).rgb, 0.0);
}
