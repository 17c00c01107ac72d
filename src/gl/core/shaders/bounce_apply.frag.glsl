#version 450 core
// Interreflection stage, step 4 (interreflection.c): the gathered irradiance at each pixel from the
// four nearest gathered block centres, weighted by the pixel's distance from their tangent planes and
// by normal (a joint bilateral upsampling); where none of them lies on the pixel's surface (silhouettes,
// thin parts) the pixel gathers its own. Added (blending) to the illumination pass's targets: a
// subsurface receiver's irradiance enters like the lights' (transmittance 1 - 2 FM1(eta) of a diffuse
// field, sqrt(albedo) at entry), a diffuse one reflects albedo / pi of it.
#include "common.glsl"
#include "bounce_common.glsl"

layout(binding = 0) uniform sampler2D g_pos;
layout(binding = 1) uniform sampler2D g_nrm;
layout(binding = 2) uniform sampler2D g_albedo;
layout(binding = 3) uniform sampler2D t_bounce;
layout(binding = 4) uniform sampler2D t_plane; // the gathered points' tangent planes (bounce_gather)
layout(std430, binding = 13) readonly buffer BounceTransmit { float bounce_transmit[]; };
uniform int u_stride;

layout(location = 0) out vec4 o_irr;
layout(location = 1) out vec4 o_refl;

vec3 upsampled(ivec2 px, vec3 x, vec3 n)
{
    ivec2 size = textureSize(t_bounce, 0);
    vec2 f = (vec2(px) - float(u_stride / 2)) / float(u_stride);
    ivec2 base = ivec2(floor(f));
    vec2 t = f - vec2(base);
    // the plane tolerance: two blocks' width in world units at this depth
    float tol = 2.0 * float(u_stride) * max(distance(x, u_camera_pos.xyz), u_misc.w) * u_camera_fwd.w;
    vec3 sum = vec3(0.0);
    float wsum = 0.0;
    for (int k = 0; k < 4; k++) {
        ivec2 o = ivec2(k & 1, k >> 1);
        ivec2 lp = clamp(base + o, ivec2(0), size - 1);
        vec4 B = texelFetch(t_bounce, lp, 0), P = texelFetch(t_plane, lp, 0);
        float plane = abs(dot(P.xyz, x) - P.w); // the pixel's distance from the gathered point's plane
        float cn = dot(n, P.xyz);
        float bil = (o.x == 1 ? t.x : 1.0 - t.x) * (o.y == 1 ? t.y : 1.0 - t.y) + 1e-3;
        float w = B.w > 0.5 && cn > 0.8 && plane < tol ? bil * (cn - 0.8) * (1.0 - plane / tol) : 0.0;
        sum += w * B.rgb;
        wsum += w;
    }
    return wsum > 0.0 ? sum / wsum : bounce_irradiance(x, n);
}

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec4 N = texelFetch(g_nrm, px, 0);
    o_irr = vec4(0.0);
    o_refl = vec4(0.0);
    if (N.w < 0.5) return;
    int mi = int(objects[int(N.w - 0.5)].anim.y);
    Material m = materials[mi];
    if (m.albedo.w > 1.5) return; // an area light's rectangle
    vec3 x = texelFetch(g_pos, px, 0).xyz, n = normalize(N.xyz);
    vec3 E = upsampled(px, x, n);
    vec3 alb = texelFetch(g_albedo, px, 0).rgb;
    if (m.albedo.w > 0.5) o_refl.rgb = alb / PI * E;
    else o_irr.rgb = bounce_transmit[mi] * E * sqrt(alb);
}
