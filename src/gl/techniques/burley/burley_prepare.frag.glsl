#version 450 core
// burley, pass 1: the signal the scatter pass integrates (Golubev 2018's irradiance buffer, which
// "includes transmitted light"). Subsurface pixels get the transmitted irradiance F_t E sqrt(albedo) of
// the shared illumination pass plus, with u_mode, the light crossing thin parts from behind, with the
// profile's transmittance T(t) = A/4 (e^(-t/d) + 3 e^(-t/(3d))) (Christensen & Burley 2015; HDRP's
// ComputeTransmittanceDisney): thick (1), t from the light's shadow map (shadow_thickness.glsl); thin (2),
// t = u_thickness and the light's shadow test on the back side. The back side's cosine is wrapped by
// u_wrap, (-n.l + w) / (1 + w)^2 (HDRP's ComputeWrappedDiffuseLighting), and the entry Fresnel
// transmittance is taken at that cosine. The transmitted light enters as T / A: the scatter pass
// multiplies by A. Alpha: object id + 1 on subsurface pixels, 0 elsewhere (the scatter pass skips those).
#include "common.glsl"
#include "shadow_thickness.glsl"

layout(binding = 0) uniform sampler2D g_pos;
layout(binding = 1) uniform sampler2D g_nrm;
layout(binding = 2) uniform sampler2D g_albedo;
layout(binding = 3) uniform sampler2D t_irr;

layout(std430, binding = 12) readonly buffer BurleyBlock { vec4 bd[]; };

uniform int u_mode;        // 0 off, 1 thick, 2 thin
uniform float u_thickness; // thin: scene units
uniform float u_wrap;

layout(location = 0) out vec4 o_value;

// The light behind p (normal n) through a slab of the thickness the mode gives, per unit of A.
vec3 transmitted(int mat, vec3 p, vec3 n)
{
    vec3 invd = bd[3 * mat + 1].rgb;
    float eta = materials[mat].params.x;
    vec3 sum = vec3(0.0);
    for (int i = 0; i < u_counts.y; i++) {
        Light L = lights[i];
        vec3 l;
        vec3 E = light_incident(L, p, l);
        float c = clamp((dot(l, -n) + u_wrap) / ((1.0 + u_wrap) * (1.0 + u_wrap)), 0.0, 1.0);
        if (c <= 0.0 || max(E.r, max(E.g, E.b)) <= 0.0) continue;
        float t = u_thickness;
        if (u_mode == 1) {
            t = shadow_thickness(L, p, n);
            if (t < 0.0) continue;
        } else {
            E *= shadow_visibility(L, p - n * t, -n);
        }
        vec3 e = exp(-t * invd / 3.0);
        vec3 T = 0.25 * (e * e * e + 3.0 * e); // T(t) / A
        sum += (1.0 - fr_dielectric(c, 1.0, eta)) * c * E * T;
    }
    return sum;
}

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec4 N = texelFetch(g_nrm, px, 0);
    o_value = vec4(0.0);
    if (N.w < 0.5) return;
    int mat = int(objects[int(N.w - 0.5)].anim.y);
    if (materials[mat].albedo.w > 0.5 || bd[3 * mat].w < 0.5) return;
    vec3 value = texelFetch(t_irr, px, 0).rgb;
    if (u_mode != 0) {
        vec3 tr = transmitted(mat, texelFetch(g_pos, px, 0).xyz, normalize(N.xyz));
        value += tr * sqrt(texelFetch(g_albedo, px, 0).rgb);
    }
    o_value = vec4(value, N.w);
}
