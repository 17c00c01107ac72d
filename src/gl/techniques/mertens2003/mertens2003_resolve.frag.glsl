#version 450 core
// Mertens et al. 2003, sections 6.1 and 3: the interleaved pattern x pattern block is recombined by a box blur
// over the pixels of the same object whose normals agree (a discontinuity-aware blur: the block's
// pixels used disjoint strata of the sample sets), then L = reflected + c_o sqrt(albedo) B(x_o),
// c_o = F_t(x_o, w_o) / (pi c) (Eq. 3 with docs/physics.md §1's normalisation).
#include "common.glsl"

layout(binding = 0) uniform sampler2D g_pos;
layout(binding = 1) uniform sampler2D g_nrm;
layout(binding = 2) uniform sampler2D g_albedo;
layout(binding = 3) uniform sampler2D t_refl;
layout(binding = 4) uniform sampler2D t_est;

uniform int u_pattern;
uniform int u_blur;
uniform float u_blur_normal;

layout(location = 0) out vec4 o_color;

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec3 refl = texelFetch(t_refl, px, 0).rgb;
    o_color = vec4(refl, 1.0);
    Material m;
    vec3 weight;
    if (!subsurface_exit(g_pos, g_nrm, g_albedo, px, m, weight)) return;
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
    o_color = vec4(refl + weight * s, 1.0);
}
