#version 450 core
// Interreflection stage, step 2 (interreflection.c): each source's flux. Diffuse: albedo E A. Subsurface:
// the light that entered anywhere on the same object and leaves here, M_j = sum_k F_t E_k A_k
// R'_d(|x_j - x_k|, A_k) (the disc mean of the kernel LUT, Maisch & Ropinski 2020, Eq. 5; k = j takes
// the part that stays within its own disc), times A_j.
#include "common.glsl"
#define BOUNCE_WRITES_LIGHTS 1
#include "bounce_common.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = 11) readonly buffer BounceSources { BounceSource bounce_sources[]; };

void main()
{
    uint j = gl_GlobalInvocationID.x;
    if (j >= u_count) return;
    BounceSource s = bounce_sources[j];
    vec3 M = s.value.rgb;
    if (s.nrm.w > 0.5) {
        BounceTriangle t = bounce_tris[j];
        LutInfo L = lut_info(int(objects[int(t.a.w + 0.5)].anim.y));
        uint first = uint(t.b.w + 0.5), count = uint(t.c.w + 0.5);
        M = vec3(0.0);
        for (uint k = first; k < first + count; k++) {
            BounceSource q = bounce_sources[k];
            M += q.value.rgb * q.pos.w * lut_eval(L, distance(s.pos.xyz, q.pos.xyz), q.pos.w);
        }
    }
    bounce_vpls[j] = BounceLight(s.pos, vec4(s.nrm.xyz, 0.0), vec4(M * s.pos.w, 0.0));
}
