#version 450 core
// Separable SSS (Jimenez et al. 2019), first pass: the signal the 1D passes convolve. Subsurface pixels get the
// transmitted irradiance F_t E sqrt(albedo) of the shared illumination pass plus, with u_transmittance,
// the light crossing thin parts from behind (Jimenez et al. 2010, as the SSSS reference code:
// thickness s = distance from the first surface the light's shadow map sees to the point shrunk along
// -n, profile T(s) = R_d integrated over the plane at depth s, cosine term saturate(0.3 + dot(l, -n))).
// Alpha is the object mask: object id + 1 on subsurface pixels, 0 elsewhere (the passes skip those).
#include "common.glsl"

layout(binding = 0) uniform sampler2D g_pos;
layout(binding = 1) uniform sampler2D g_nrm;
layout(binding = 2) uniform sampler2D g_albedo;
layout(binding = 3) uniform sampler2D t_irr;
layout(binding = 5) uniform sampler2D t_trans;            // T(s) / T(0), one row per material
layout(binding = 6) uniform samplerCubeArray t_cube_raw;  // the cube shadow maps without comparison
layout(binding = 7) uniform sampler2DArray t_2d_raw;      // the 2D shadow maps without comparison

layout(std430, binding = 12) readonly buffer SsssBlock { vec4 sd[]; };

uniform int u_transmittance;

layout(location = 0) out vec4 o_value;

// Thickness crossed by light i to reach p (shrunk along -n); < 0 when the map cannot tell.
float thickness(Light L, vec3 p, vec3 n)
{
    int kind = int(L.spot.z + 0.5);
    if (kind == 0) return -1.0;
    float bias = u_misc.z;
    if (kind == 1) {
        float texel = length(p - L.position.xyz) * L.shadow.z;
        vec3 d = p - n * bias * texel - L.position.xyz;
        float occ = texture(t_cube_raw, vec4(d, L.spot.w)).r * L.shadow.y;
        return max(length(d) - occ, 0.0);
    }
    float texel = L.shadow.w > 0.5 ? L.shadow.z : length(p - L.position.xyz) * L.shadow.z;
    vec3 ps = p - n * bias * texel;
    vec4 clip = L.shadow_matrix * vec4(ps, 1.0);
    if (clip.w <= 0.0) return -1.0;
    vec3 ndc = clip.xyz / clip.w;
    vec2 uv = ndc.xy * 0.5 + 0.5;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return -1.0;
    float zocc = texture(t_2d_raw, vec3(uv, L.spot.w)).r * 2.0 - 1.0;
    if (zocc >= ndc.z) return 0.0;
    // the occluder on the same light ray, back in world space
    vec4 w = inverse(L.shadow_matrix) * vec4(ndc.xy, zocc, 1.0);
    return length(ps - w.xyz / w.w);
}

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec4 N = texelFetch(g_nrm, px, 0);
    o_value = vec4(0.0);
    if (N.w < 0.5) return;
    int mat = int(objects[int(N.w - 0.5)].anim.y);
    if (materials[mat].albedo.w > 0.5) return;
    int base = 1 + mat * (4 + 2 * int(sd[0].x + 0.5));
    if (sd[base].w < 0.5) return;
    vec3 value = texelFetch(t_irr, px, 0).rgb;
    if (u_transmittance != 0) {
        vec3 p = texelFetch(g_pos, px, 0).xyz;
        vec3 n = normalize(N.xyz);
        float row = sd[base + 1].w, smax = sd[base + 2].x;
        float eta = materials[mat].params.x;
        vec3 tr = vec3(0.0);
        for (int i = 0; i < u_counts.y; i++) {
            Light L = lights[i];
            vec3 l;
            vec3 E = light_incident(L, p, l);
            float c = clamp(0.3 + dot(l, -n), 0.0, 1.0); // SSSS reference: the back's cosine
            if (c <= 0.0 || max(E.r, max(E.g, E.b)) <= 0.0) continue;
            float s = thickness(L, p, n);
            if (s < 0.0 || s >= smax) continue;
            float u = (s / smax * float(SSSS_TRANS_SIZE - 1) + 0.5) / float(SSSS_TRANS_SIZE);
            vec3 T = textureLod(t_trans, vec2(u, (row + 0.5) / float(textureSize(t_trans, 0).y)), 0.0).rgb;
            tr += (1.0 - fr_dielectric(c, 1.0, eta)) * c * E * T;
        }
        value += tr * sd[base + 1].rgb * sqrt(texelFetch(g_albedo, px, 0).rgb);
    }
    o_value = vec4(value, N.w);
}
