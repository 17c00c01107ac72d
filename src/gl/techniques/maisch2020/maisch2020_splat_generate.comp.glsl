#version 450 core
// Maisch & Ropinski 2020, section 5: one splat per triangle of the low-resolution splat mesh, deformed by the
// animation like the render mesh (no precomputation), carrying its centre, normal, area and the
// transmitted irradiance F_t E at the centre. Splats are culled here (the paper's geometry shader):
//  - by irradiance (unlit splats add nothing),
//  - by the splitting criteria with the view direction v (Eq. 2 and Eq. 8): the splat is kept when it
//    lies behind x_o, the G-buffer position its centre projects to, ((x_i - x_o) . v < 0) and faces
//    away or grazes (n_i . v < 0.2). Rule 1 keeps the complement of what the screen-space pass sees
//    instead (hidden OR grazing), an option for concave objects.
//  - u_occluded_margin > 0 (a departure, docs/maisch2020.md): also the FRONT-facing part of a triangle
//    that lies more than u_occluded_margin sqrt(area) behind the G-buffer surface, i.e. surface hidden
//    behind another part or object (the face under the glasses, a cheek behind the nose): the camera
//    does not see it, so the screen-space pass cannot gather it (section 5: the splats are for "the
//    parts not visible on screen"). Tested on 16 sub-triangles; the splat is the hidden ones' union.
//    The margin keeps visible surface out: the splat mesh's chords lie a fraction of sqrt(area) off
//    the rendered surface.
//  - u_offscreen (a departure, docs/maisch2020.md): also the front-facing part of a triangle that
//    projects outside the image (off the view frustum's sides): the screen-space pass gathers only
//    surface on the image, so without it the kernel's light from beyond the image's edge is lost, more
//    the more the camera zooms in. Tested on the same 16 sub-triangles; splats whose reach misses the
//    image get an empty quad (maisch2020_splat.vert.glsl).
#include "common.glsl"

layout(local_size_x = 64) in;

struct Splat {
    vec4 centre;     // xyz; w: area
    vec4 normal;     // xyz; w: object id + 1
    vec4 irradiance; // rgb F_t E; w: disc radius sqrt(area / pi) (section 6.3)
};

layout(std430, binding = 4) writeonly buffer SplatBlock { Splat splats[]; };
layout(std430, binding = 5) buffer CommandBlock { uint cmd_count, cmd_instances, cmd_first, cmd_base; };
layout(std430, binding = 6) readonly buffer MeshPos { float mesh_pos[]; };
layout(std430, binding = 7) readonly buffer MeshIdx { uint mesh_idx[]; };
layout(std430, binding = 8) readonly buffer MeshUv { float mesh_uv[]; };

layout(binding = 0) uniform sampler2D g_pos;
layout(binding = 1) uniform sampler2D g_nrm;

uniform int u_object;
uniform uint u_triangles;
uniform uint u_capacity;
uniform int u_cull_rule;
uniform float u_irradiance_cull;
uniform float u_occluded_margin; // 0: off (the paper); in units of sqrt(triangle area)
uniform int u_offscreen;         // 1: splat front-facing surface outside the image too
uniform float u_shadow_offset; // in units of sqrt(triangle area)
uniform float u_grazing_sources; // > 0: Eq. 8's cut-off for splats (the screen pass gathers the rest)
uniform int u_has_uv;          // the splat mesh has texture coordinates

// The G-buffer surface at p's projection: true when there is one, with how far it lies in front of p
// along the view direction (negative: behind p).
bool gbuffer_at(vec3 p, out float in_front)
{
    in_front = 0.0;
    vec4 clip = u_view_proj * vec4(p, 1.0);
    if (!(clip.w > 0.0)) return false;
    vec2 ndc = clip.xy / clip.w;
    if (any(lessThan(ndc, vec2(-1.0))) || any(greaterThanEqual(ndc, vec2(1.0)))) return false;
    ivec2 px = ivec2((ndc * 0.5 + 0.5) * u_viewport.xy);
    if (texelFetch(g_nrm, px, 0).w < 0.5) return false;
    vec3 xo = texelFetch(g_pos, px, 0).xyz;
    in_front = dot(xo - p, normalize(u_camera_pos.xyz - p));
    return true;
}

// Whether p lies in front of the camera but projects outside the image.
bool off_image(vec3 p)
{
    vec4 clip = u_view_proj * vec4(p, 1.0);
    if (!(clip.w > 0.0)) return false;
    vec2 ndc = clip.xy / clip.w;
    return any(lessThan(ndc, vec2(-1.0))) || any(greaterThanEqual(ndc, vec2(1.0)));
}

// Sub-triangle i (0..3) of the midpoint subdivision of (a, b, c): the three corners, then the middle.
void quarter(int i, inout vec3 a, inout vec3 b, inout vec3 c)
{
    vec3 ab = 0.5 * (a + b), bc = 0.5 * (b + c), ca = 0.5 * (c + a);
    if (i == 0) { b = ab; c = ca; }
    else if (i == 1) { a = ab; c = bc; }
    else if (i == 2) { a = ca; b = bc; }
    else { a = bc; b = ca; c = ab; }
}

void main()
{
    uint t = gl_GlobalInvocationID.x;
    if (t >= u_triangles) return;
    Object o = objects[u_object];
    Material m = materials[int(o.anim.y)];
    vec3 p[3];
    vec2 uv = vec2(0.0);
    for (int k = 0; k < 3; k++) {
        uint i = mesh_idx[3u * t + uint(k)];
        if (u_has_uv != 0) uv += vec2(mesh_uv[2u * i], mesh_uv[2u * i + 1u]) / 3.0;
        vec3 op = vec3(mesh_pos[3u * i], mesh_pos[3u * i + 1u], mesh_pos[3u * i + 2u]);
        vec3 dn = vec3(0.0, 1.0, 0.0);
        p[k] = (o.model * vec4(anim_deform(o, op, dn, u_camera_pos.w), 1.0)).xyz;
    }
    vec3 cr = cross(p[1] - p[0], p[2] - p[0]);
    float len = robust_length(cr);
    if (!(len > 0.0)) return;
    vec3 n = cr / len;
    float area = 0.5 * len;
    vec3 c = (p[0] + p[1] + p[2]) / 3.0;

    // Splitting criteria (Eq. 2, Eq. 8) against the G-buffer at the projected centre.
    vec3 v = normalize(u_camera_pos.xyz - c);
    // With grazing_sources the screen-space pass gathers visible pixels down to that n.v: splats with
    // n.v above it would count visible surface twice (a chord of the rim dips behind the G-buffer).
    bool grazing = dot(n, v) < (u_grazing_sources > 0.0 ? min(u_grazing_sources, u_misc.y) : u_misc.y);
    bool hidden = true;
    float in_front; // how far the G-buffer surface lies in front of c (when there is one)
    if (gbuffer_at(c, in_front)) {
        float tol = u_cull_rule == 0 ? 0.0 : sqrt(area);
        hidden = -in_front < -tol; // (x_i - x_o) . v < -tol
    }
    bool keep = u_cull_rule == 0 ? (hidden && grazing) : (hidden || grazing);
    // Front-facing surface hidden behind nearer surface (u_occluded_margin): the triangle is cut into
    // 16 sub-triangles of equal area (two midpoint subdivisions), each hidden or not by the G-buffer at
    // its centroid; the splat becomes the hidden ones' union: their area, the mean of their centroids.
    // (One splat per hidden quarter instead cut the excess next to a thin occluder's edge, where a
    // disc of the hidden part's area reaches past the edge onto visible surface, from 13% to 9.5%
    // (test_maisch_occluded), but cost DSSIM at the bust's self-occlusions: eval_front +1.1e-4.)
    if (!keep && (u_occluded_margin > 0.0 || u_offscreen != 0)) {
        float margin = u_occluded_margin * sqrt(area);
        vec3 sum = vec3(0.0);
        int count = 0;
        for (int i = 0; i < 4; i++)
            for (int j = 0; j < 4; j++) {
                vec3 a = p[0], b = p[1], d = p[2];
                quarter(i, a, b, d);
                quarter(j, a, b, d);
                vec3 q = (a + b + d) / 3.0;
                float dz;
                bool occluded = u_occluded_margin > 0.0 && gbuffer_at(q, dz) && dz > margin;
                if (occluded || (u_offscreen != 0 && off_image(q))) {
                    sum += q;
                    count++;
                }
            }
        if (count == 0) return;
        c = sum / float(count);
        area *= float(count) / 16.0;
        keep = true;
    }
    if (!keep) return;

    // Transmitted irradiance at the centre, shadows included. The centre of a chord triangle lies
    // inside a convex surface; the offset keeps it from shadowing itself.
    vec3 ps = c + n * u_shadow_offset * sqrt(area);
    vec3 et = vec3(0.0);
    for (int i = 0; i < u_counts.y; i++) {
        vec3 l;
        vec3 E = light_irradiance(i, ps, n, l);
        et += (1.0 - fr_dielectric(dot(n, l), 1.0, m.params.x)) * E;
    }
    // Albedo texture: half of it where light enters (sqrt, like the illumination pass), sampled at
    // the centre's texture coordinates.
    if (u_has_uv != 0 && m.params.w >= 0.0) et *= sqrt(textureLod(u_albedo_tex, vec3(uv, m.params.w), 0.0).rgb);
    if (max(et.r, max(et.g, et.b)) <= u_irradiance_cull) return;
    uint slot = atomicAdd(cmd_instances, 1u);
    if (slot >= u_capacity) return;
    splats[slot] = Splat(vec4(c, area), vec4(n, float(u_object + 1)), vec4(et, sqrt(area / PI)));
}
