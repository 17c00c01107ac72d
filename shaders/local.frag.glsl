#version 450 core
// Technique "local": the limit of a vanishing scattering distance. A subsurface pixel shows
// c_o F_t E(x_o) rho_eff, rho_eff = the plane integral of R_d (the material's total diffuse reflectance):
// no light crosses between points. A baseline and a check of the shared passes.
#include "common.glsl"

layout(binding = 0) uniform sampler2D g_pos;
layout(binding = 1) uniform sampler2D g_nrm;
layout(binding = 2) uniform sampler2D g_albedo;
layout(binding = 3) uniform sampler2D t_irr;
layout(binding = 4) uniform sampler2D t_refl;

layout(location = 0) out vec4 o_color;

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec3 refl = texelFetch(t_refl, px, 0).rgb;
    vec4 N = texelFetch(g_nrm, px, 0);
    o_color = vec4(refl, 1.0);
    if (N.w < 0.5) return;
    Material m = materials[int(objects[int(N.w - 0.5)].anim.y)];
    if (m.albedo.w > 0.5) return;
    vec3 p = texelFetch(g_pos, px, 0).xyz;
    vec3 v = normalize(u_camera_pos.xyz - p);
    vec3 alb = texelFetch(g_albedo, px, 0).rgb;
    vec3 et = texelFetch(t_irr, px, 0).rgb;
    o_color = vec4(refl + exit_factor(m, normalize(N.xyz), v) * sqrt(alb) * et * m.albedo.rgb, 1.0);
}
