#version 450 core
// Separable SSS (Jimenez et al. 2019): one 1D pass of one separable term (horizontal, then vertical). The taps'
// offsets are world-space distances projected to the screen at the pixel's depth (the SSSS reference
// code's distanceToProjectionWindow / depth, here exactly: pixels per scene unit = 1 / (pixel size on
// the image plane at distance 1 x depth along the view axis)); weights per channel from the kernel
// block (tech_ssss.h).
//  - depth correction (Eq. 7; SSSS "follow surface"): a tap whose surface lies dz away along the view
//    axis contributes mix(its colour, the centre colour, 1 - e^(-dz^2 / 2 sigma^2)), which keeps the
//    weights' sum (energy); taps on another object or the background take the centre colour;
//  - stochastic rotation (section 6): taps nearer than u_rotate x the kernel's range use filter axes
//    rotated by a per-pixel random angle (the vertical pass the perpendicular one);
//  - masking: pixels whose mask (alpha) is 0 are not subsurface and return at once.
#include "common.glsl"

layout(binding = 0) uniform sampler2D t_src; // rgb value, a: object id + 1 (0: not subsurface)
layout(binding = 1) uniform sampler2D g_pos;

layout(std430, binding = 12) readonly buffer SsssBlock { vec4 sd[]; };

uniform int u_vertical;
uniform int u_term;
uniform float u_rotate;
uniform int u_follow;

layout(location = 0) out vec4 o_value;

float hash(uvec2 p)
{
    uint h = p.x * 1664525u + p.y * 1013904223u + 374761393u;
    h ^= h >> 16; h *= 0x7feb352du;
    h ^= h >> 15; h *= 0x846ca68bu;
    h ^= h >> 16;
    return float(h) * (1.0 / 4294967296.0);
}

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec4 C = texelFetch(t_src, px, 0);
    o_value = vec4(0.0);
    if (C.w < 0.5) return;
    int mat = int(objects[int(C.w - 0.5)].anim.y);
    int base = 1 + mat * (4 + 2 * int(sd[0].x + 0.5));
    vec4 hdr = sd[base + 4 + 2 * u_term];
    vec3 sigma = sd[base + 5 + 2 * u_term].rgb;
    int first = int(hdr.x + 0.5), count = int(hdr.y + 0.5);
    float near_range = u_rotate * hdr.z;
    vec3 P = texelFetch(g_pos, px, 0).xyz;
    float depth = dot(P - u_camera_pos.xyz, u_camera_fwd.xyz);
    float ppu = 1.0 / max(u_camera_fwd.w * depth, 1e-30);
    vec2 axis = u_vertical != 0 ? vec2(0.0, 1.0) : vec2(1.0, 0.0);
    // one angle per pixel for both passes: the rotated frame's two axes (independent angles per pass
    // lost more energy on a small bright dot, -2.6% against -0.6%, test_ssss_props)
    float th = 2.0 * PI * hash(uvec2(px));
    vec2 rot = u_vertical != 0 ? vec2(-sin(th), cos(th)) : vec2(cos(th), sin(th));
    ivec2 size = textureSize(t_src, 0);
    vec2 inv_size = 1.0 / vec2(size);
    vec3 inv2s2 = 1.0 / max(2.0 * sigma * sigma, vec3(1e-30));
    vec3 sum = vec3(0.0);
    for (int k = 0; k < count; k++) {
        vec4 a = sd[first + 2 * k];
        vec3 w = u_vertical != 0 ? sd[first + 2 * k + 1].rgb : a.rgb;
        float off = a.w;
        vec3 col = C.rgb;
        if (off != 0.0) {
            vec2 dir = abs(off) <= near_range ? rot : axis;
            vec2 sp = gl_FragCoord.xy + dir * (off * ppu);
            ivec2 q = ivec2(floor(sp));
            if (all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, size)) &&
                abs(texelFetch(t_src, q, 0).w - C.w) < 0.5) {
                vec3 cs = textureLod(t_src, sp * inv_size, 0.0).rgb;
                if (u_follow != 0) {
                    float dz = dot(texelFetch(g_pos, q, 0).xyz - P, u_camera_fwd.xyz);
                    col = mix(cs, C.rgb, 1.0 - exp(-dz * dz * inv2s2));
                } else {
                    col = cs;
                }
            }
        }
        sum += w * col;
    }
    o_value = vec4(sum, u_vertical != 0 ? 0.0 : C.w);
}
