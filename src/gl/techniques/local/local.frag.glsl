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
    o_color = vec4(refl, 1.0);
    Material m;
    vec3 weight;
    if (!subsurface_exit(g_pos, g_nrm, g_albedo, px, m, weight)) return;
    vec3 et = texelFetch(t_irr, px, 0).rgb;
    o_color = vec4(refl + weight * et * m.albedo.rgb, 1.0);
}
