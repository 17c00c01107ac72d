#version 450 core
// Low-resolution receivers of the translucency pass (Maisch & Ropinski 2020, section 5: a quarter of the
// resolution). Each low-resolution pixel takes the full-resolution G-buffer pixel at the centre of its
// block, or the first subsurface pixel in the block when the centre is not one, and marks itself valid
// in the accumulation target's alpha (the upsampling divides by it, so silhouettes do not darken).
#include "common.glsl"

layout(binding = 0) uniform sampler2D g_pos;
layout(binding = 1) uniform sampler2D g_nrm;

uniform int u_divisor;

layout(location = 0) out vec4 o_receiver; // xyz position; w: object id + 1 (0: none)
layout(location = 1) out vec4 o_accum;    // initial accumulation: (0, 0, 0, valid)

bool is_subsurface(vec4 N)
{
    if (N.w < 0.5) return false;
    return materials[int(objects[int(N.w - 0.5)].anim.y)].albedo.w < 0.5;
}

void main()
{
    ivec2 base = ivec2(gl_FragCoord.xy) * u_divisor;
    ivec2 size = textureSize(g_nrm, 0);
    ivec2 centre = min(base + u_divisor / 2, size - 1);
    ivec2 pick = ivec2(-1);
    if (is_subsurface(texelFetch(g_nrm, centre, 0))) pick = centre;
    for (int y = 0; y < u_divisor && pick.x < 0; y++)
        for (int x = 0; x < u_divisor && pick.x < 0; x++) {
            ivec2 q = min(base + ivec2(x, y), size - 1);
            if (is_subsurface(texelFetch(g_nrm, q, 0))) pick = q;
        }
    if (pick.x < 0) {
        o_receiver = vec4(0.0);
        o_accum = vec4(0.0);
        return;
    }
    o_receiver = vec4(texelFetch(g_pos, pick, 0).xyz, texelFetch(g_nrm, pick, 0).w);
    o_accum = vec4(0.0, 0.0, 0.0, 1.0);
}
