#version 450 core
// Splat selection from the irradiance buffer of one light (Chen et al. 2012, as Maisch & Ropinski 2020, section 8
// configures it: 2048^2 texels, 3 mip levels): one splat per texel of the level chosen for its region,
// the coarsest level whose texel is (a) at most u_texel_fraction of the splat's required radius (the
// kernel's reach, the radius holding splat_energy of R_d) wide and (b) homogeneous: all four children
// cover the same object and lie within one texel width of the parent's tangent plane (no depth
// discontinuity). Level 0 texels always qualify. One thread per texel of the coarsest level u_top
// descends the hierarchy until its texels qualify.
// Mip texels hold area-weighted sums (mip_reduce.comp.glsl): position, F_t E and normal are the means
// over the texel's surface, the area their sum.
#include "common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

struct Splat {
    vec4 centre;     // xyz; w: area
    vec4 normal;     // xyz; w: object id + 1
    vec4 irradiance; // rgb F_t E; w: disc radius sqrt(area / pi)
};
layout(std430, binding = 4) writeonly buffer SplatBlock { Splat splats[]; };
layout(std430, binding = 5) buffer CommandBlock { uint cmd_count, cmd_instances, cmd_first, cmd_base; };

layout(binding = 0) uniform sampler2D t_pos; // level 0: (p, area); levels >= 1: (sum a p, sum a)
layout(binding = 1) uniform sampler2D t_irr; // level 0: (F_t E, id + 1); >= 1: (sum a F_t E, sum a id)
layout(binding = 2) uniform sampler2D t_nrm; // level 0: (n, id + 1); >= 1: (sum a n, sum a id)

uniform int u_top;
uniform int u_size; // texels per side of level 0
uniform float u_texel_fraction;
uniform float u_irradiance_cull;
uniform uint u_capacity;

// Level sizes come from u_size: textureSize() with a non-constant level returned wrong sizes on
// llvmpipe (Mesa 22.3) here, which clamped children into the wrong column and dropped or doubled
// whole blocks of splats.
ivec2 level_size(int l) { return ivec2(max(u_size >> l, 1)); }

struct Texel {
    vec3 p, e, n;
    float a, id;
};

bool fetch(ivec2 q, int l, out Texel T)
{
    vec4 P = texelFetch(t_pos, q, l);
    vec4 I = texelFetch(t_irr, q, l);
    vec4 N = texelFetch(t_nrm, q, l);
    T.a = P.w;
    if (!(P.w > 0.0)) return false;
    float m = l == 0 ? 1.0 : 1.0 / P.w;
    T.p = P.xyz * m;
    T.e = I.rgb * m;
    T.n = N.xyz;
    float nl = length(T.n);
    T.n = nl > 0.0 ? T.n / nl : vec3(0.0, 0.0, 1.0);
    T.id = l == 0 ? I.w : floor(I.w * m + 0.5);
    return T.id > 0.5;
}

bool acceptable(ivec2 q, int l, Texel T)
{
    if (l == 0) return true;
    float reach = materials[int(objects[int(T.id - 0.5)].anim.y)].spec.w;
    float width = sqrt(T.a);
    bool ok = width <= u_texel_fraction * reach;
    ivec2 size = level_size(l - 1);
    for (int k = 0; k < 4; k++) {
        ivec2 c = min(2 * q + ivec2(k & 1, k >> 1), size - 1);
        Texel C;
        bool valid = fetch(c, l - 1, C);
        ok = ok && valid && C.id == T.id && abs(dot(C.p - T.p, T.n)) <= width;
    }
    return ok;
}

void emit(Texel T)
{
    if (max(T.e.r, max(T.e.g, T.e.b)) <= u_irradiance_cull) return;
    uint slot = atomicAdd(cmd_instances, 1u);
    if (slot >= u_capacity) return;
    splats[slot] = Splat(vec4(T.p, T.a), vec4(T.n, T.id), vec4(T.e, sqrt(T.a / PI)));
}

void main()
{
    ivec2 q0 = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(q0, level_size(u_top)))) return;
    // depth-first descent from a texel of the coarsest level with an explicit stack (at most 4
    // levels: 1 + 3 * 3 entries)
    ivec3 stack[16];
    int top = 0;
    stack[top++] = ivec3(q0, u_top);
    while (top > 0) {
        ivec3 e = stack[--top];
        Texel T;
        if (!fetch(e.xy, e.z, T)) continue;
        if (acceptable(e.xy, e.z, T)) {
            emit(T);
            continue;
        }
        ivec2 cs = level_size(e.z - 1);
        for (int k = 0; k < 4; k++) {
            ivec2 c = 2 * e.xy + ivec2(k & 1, k >> 1);
            if (all(lessThan(c, cs)) && top < 16) stack[top++] = ivec3(c, e.z - 1);
        }
    }
}
