#version 450 core
// Pass 3 of Maisch & Ropinski 2020: directly reflected radiance and transmitted irradiance F_t E of every visible
// pixel (shadows from pass 2). The albedo texture enters here as sqrt(albedo) (the other half is
// applied at the exit point, Maisch & Ropinski 2020 supplement: texture colour before and after scattering).
#include "common.glsl"

layout(binding = 0) uniform sampler2D g_pos;
layout(binding = 1) uniform sampler2D g_nrm;
layout(binding = 2) uniform sampler2D g_albedo;

layout(location = 0) out vec4 o_irr;  // rgb F_t E sqrt(albedo); w: object id + 1
layout(location = 1) out vec4 o_refl; // rgb reflected radiance

// GGX (Trowbridge-Reitz, alpha = roughness^2) microfacet reflection of the dielectric interface with
// Smith's separable masking; for display only (PBRT comparisons leave specular out).
float ggx_brdf(vec3 n, vec3 v, vec3 l, float roughness, float eta)
{
    float nl = dot(n, l), nv = dot(n, v);
    if (nl <= 0.0 || nv <= 0.0) return 0.0;
    vec3 h = normalize(v + l);
    float a = max(roughness * roughness, 1e-3), a2 = a * a;
    float nh = max(dot(n, h), 0.0);
    float d = nh * nh * (a2 - 1.0) + 1.0;
    float D = a2 / (PI * d * d);
    float gv = 2.0 * nv / (nv + sqrt(a2 + (1.0 - a2) * nv * nv));
    float gl = 2.0 * nl / (nl + sqrt(a2 + (1.0 - a2) * nl * nl));
    float F = fr_dielectric(dot(v, h), 1.0, eta);
    return D * F * gv * gl / (4.0 * nl * nv);
}

layout(binding = 12) uniform sampler2D u_env;
uniform int u_has_env;
uniform float u_env_rotate; // degrees
uniform vec3 u_env_scale;

// Environment radiance seen along world direction d (docs/scene-format.md: +y up, u = 0.5 at -z; the inverse of
// m = (sin t sin p, cos t, -sin t cos p), p = 2 pi (u - 0.5) - rad(rotate_y), t = pi v).
vec3 environment_lod(vec3 d, float lod)
{
    d = normalize(d);
    float th = acos(clamp(d.y, -1.0, 1.0));
    float ph = atan(d.x, -d.z);
    float u = (ph + radians(u_env_rotate)) / (2.0 * PI) + 0.5;
    float v = th / PI;
    return u_env_scale * textureLod(u_env, vec2(fract(u), v), lod).rgb;
}

vec3 environment(vec3 d) { return environment_lod(d, 0.0); }

// Specular reflection of the environment map by the dielectric interface (display only): Fresnel at
// the view angle times the map along the mirror direction, read from a mip level that widens with the
// roughness (a crude prefilter: the box-filtered equirectangular chain, no visibility).
vec3 environment_specular(vec3 n, vec3 v, float roughness, float eta)
{
    float lod = roughness * log2(float(max(textureSize(u_env, 0).x, 1)));
    return fr_dielectric(dot(n, v), 1.0, eta) * environment_lod(reflect(-v, n), lod);
}

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec4 N = texelFetch(g_nrm, px, 0);
    if (N.w < 0.5) {
        // Camera rays that miss see the environment (black without one).
        o_irr = vec4(0.0);
        o_refl = vec4(0.0);
        if (u_has_env != 0) {
            vec2 ndc = (gl_FragCoord.xy * u_viewport.zw) * 2.0 - 1.0;
            vec4 far_p = u_inv_view_proj * vec4(ndc, 1.0, 1.0);
            o_refl = vec4(environment(far_p.xyz / far_p.w - u_camera_pos.xyz), 1.0);
        }
        return;
    }
    vec3 p = texelFetch(g_pos, px, 0).xyz;
    vec3 n = normalize(N.xyz);
    vec3 alb = texelFetch(g_albedo, px, 0).rgb;
    Object o = objects[int(N.w - 0.5)];
    Material m = materials[int(o.anim.y)];
    vec3 v = normalize(u_camera_pos.xyz - p);
    if (m.albedo.w > 1.5) { // an area light's rectangle: its radiance on the emitting side
        o_irr = vec4(0.0, 0.0, 0.0, N.w);
        o_refl = vec4(m.spec.x > 0.5 || dot(n, v) > 0.0 ? m.albedo.rgb : vec3(0.0), 1.0);
        return;
    }
    bool diffuse = m.albedo.w > 0.5;
    float eta = m.params.x;
    vec3 et = vec3(0.0), refl = vec3(0.0);
    for (int i = 0; i < u_counts.y; i++) {
        vec3 l;
        vec3 E = light_irradiance(i, p, n, l);
        if (diffuse) {
            refl += alb / PI * E;
        } else {
            et += (1.0 - fr_dielectric(dot(n, l), 1.0, eta)) * E;
            bool from_env = int(lights[i].position.w) == 2 && lights[i].direction.w > 1.5;
            if (m.spec.x > 0.5 && !from_env) refl += ggx_brdf(n, v, l, m.spec.y, eta) * E;
        }
    }
    if (!diffuse && m.spec.x > 0.5 && u_has_env != 0) refl += environment_specular(n, v, m.spec.y, eta);
    o_irr = vec4(diffuse ? vec3(0.0) : et * sqrt(alb), N.w);
    o_refl = vec4(refl, 1.0);
}
