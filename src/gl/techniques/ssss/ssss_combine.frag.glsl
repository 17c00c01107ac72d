#version 450 core
// Separable SSS (Jimenez et al. 2019), last pass: reflected light + c_o sqrt(albedo) x multiplier x the sum of
// the separable terms, c_o = F_t(x_o, w_o) / (pi c) (docs/physics.md §1); the multiplier is the profile's total
// reflectance for kernels whose weights sum to 1 (Eq. 5: A_p = a_p a_p / ||R_d||_1). Pixels outside
// every subsurface object (mask 0) keep the reflected light unchanged.
#include "common.glsl"

layout(binding = 0) uniform sampler2D g_pos;
layout(binding = 1) uniform sampler2D g_nrm;
layout(binding = 2) uniform sampler2D g_albedo;
layout(binding = 3) uniform sampler2D t_refl;
layout(binding = 4) uniform sampler2D t_sum;
layout(binding = 5) uniform sampler2D t_mask;

layout(std430, binding = 12) readonly buffer SsssBlock { vec4 sd[]; };

layout(location = 0) out vec4 o_color;

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec3 refl = texelFetch(t_refl, px, 0).rgb;
    o_color = vec4(refl, 1.0);
    float id = texelFetch(t_mask, px, 0).w;
    if (id < 0.5) return;
    int mat = int(objects[int(id - 0.5)].anim.y);
    Material m = materials[mat];
    vec3 mult = sd[1 + mat * (4 + 2 * int(sd[0].x + 0.5))].rgb;
    vec3 p = texelFetch(g_pos, px, 0).xyz;
    vec3 n = normalize(texelFetch(g_nrm, px, 0).xyz);
    vec3 v = normalize(u_camera_pos.xyz - p);
    vec3 alb = texelFetch(g_albedo, px, 0).rgb;
    vec3 s = max(texelFetch(t_sum, px, 0).rgb, vec3(0.0)); // rank-N sums may dip below 0
    o_color = vec4(refl + exit_factor(m, n, v) * sqrt(alb) * mult * s, 1.0);
}
