#version 450 core
// Mertens et al. 2003, sections 6.1 and 3: the interleaved pattern x pattern block is recombined by a box blur
// over the pixels of the same object whose normals agree (a discontinuity-aware blur: the block's
// pixels used disjoint strata of the sample sets), then L = reflected + c_o sqrt(albedo) B(x_o)
// (Eq. 3 with docs/physics.md §1's normalisation; common/resolve.glsl).
#include "common.glsl"
#include "resolve.glsl"

layout(binding = 4) uniform sampler2D t_est;

uniform int u_pattern;
uniform int u_blur;
uniform float u_blur_normal;

vec3 subsurface_light(ivec2 px)
{
    vec4 N = texelFetch(g_nrm, px, 0); // the blur keeps to this object and normal
    vec3 n = normalize(N.xyz);
    vec3 s = texelFetch(t_est, px, 0).rgb;
    if (u_blur != 0 && u_pattern > 1) {
        // the pattern x pattern window holding this pixel's block cells once each
        ivec2 size = textureSize(t_est, 0);
        int lo = -(u_pattern / 2);
        vec3 acc = vec3(0.0);
        float w = 0.0;
        for (int dy = lo; dy < lo + u_pattern; dy++)
            for (int dx = lo; dx < lo + u_pattern; dx++) {
                ivec2 q = px + ivec2(dx, dy);
                if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
                vec4 NQ = texelFetch(g_nrm, q, 0);
                if (NQ.w != N.w || dot(normalize(NQ.xyz), n) < u_blur_normal) continue;
                vec4 E = texelFetch(t_est, q, 0);
                if (E.a < 0.5) continue;
                acc += E.rgb;
                w += 1.0;
            }
        if (w > 0.0) s = acc / w;
    }
    return s;
}
