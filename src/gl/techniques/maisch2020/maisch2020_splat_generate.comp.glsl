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
//    the more the camera zooms in. Tested on the same 16 sub-triangles. A triangle not wholly inside the
//    view is first cut (midpoint subdivision, one splat per piece) until each piece is no wider than a
//    translucency pixel or a 16th of the image (the larger) at its depth, or than u_piece_ratio times
//    its distance from the view:
//    a splat-mesh triangle can be as large as the zoomed view, and one splat for it put its off-image
//    part's area at the mean of its centroids (often on the image: the screen-space part counted that
//    surface too), with F_t E of one point and the self-shadowing offset of the whole triangle (a plane
//    under a close point light: 2.4x the reference). Pieces farther from the view than the kernel's
//    reach are dropped (their quads would be empty: maisch2020_splat.vert.glsl).
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
uniform int u_divisor;         // render pixels per translucency pixel
uniform float u_piece_ratio;   // pieces off the view: largest size over distance from it (0: no pieces)

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

// A lower bound of the distance from p to the view frustum (0 inside): the largest distance outside its
// side planes (each through the camera, containing an image edge).
float outside_view(vec3 p)
{
    vec3 q = (u_view * vec4(p, 1.0)).xyz;
    vec2 t = vec2(1.0 / u_proj[0][0], 1.0 / u_proj[1][1]); // tan of the half field of view
    vec2 out_d = (abs(q.xy) + t * q.z) / sqrt(1.0 + t * t);   // q.z = -depth
    return max(0.0, max(out_d.x, out_d.y));
}

// One splat for the triangle part (a, b, d) of normal n and area `area` (uv: texture coordinates at its
// centroid), by the culling rules above; nothing when they keep none of it.
void splat_part(vec3 a, vec3 b, vec3 d, vec3 n, float area, vec2 uv, Material m)
{
    vec3 p[3] = vec3[3](a, b, d);
    vec3 c = (a + b + d) / 3.0;

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
                vec3 qa = p[0], qb = p[1], qd = p[2];
                quarter(i, qa, qb, qd);
                quarter(j, qa, qb, qd);
                vec3 q = (qa + qb + qd) / 3.0;
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

#define MAX_DEPTH 8 // pieces: at most 4^8 per triangle (256 per edge)

void main()
{
    uint t = gl_GlobalInvocationID.x;
    if (t >= u_triangles) return;
    Object o = objects[u_object];
    Material m = materials[int(o.anim.y)];
    vec3 p[3];
    vec2 uvs[3] = vec2[3](vec2(0.0), vec2(0.0), vec2(0.0));
    bool inside = true; // the triangle lies wholly in the view (convex: its corners do)
    for (int k = 0; k < 3; k++) {
        uint i = mesh_idx[3u * t + uint(k)];
        if (u_has_uv != 0) uvs[k] = vec2(mesh_uv[2u * i], mesh_uv[2u * i + 1u]);
        vec3 op = vec3(mesh_pos[3u * i], mesh_pos[3u * i + 1u], mesh_pos[3u * i + 2u]);
        vec3 dn = vec3(0.0, 1.0, 0.0);
        p[k] = (o.model * vec4(anim_deform(o, op, dn, u_camera_pos.w), 1.0)).xyz;
        inside = inside && outside_view(p[k]) == 0.0;
    }
    vec3 cr = cross(p[1] - p[0], p[2] - p[0]);
    float len = robust_length(cr);
    if (!(len > 0.0)) return;
    vec3 n = cr / len;
    float area = 0.5 * len;
    if (u_offscreen == 0 || !(u_piece_ratio > 0.0) || inside) {
        splat_part(p[0], p[1], p[2], n, area, (uvs[0] + uvs[1] + uvs[2]) / 3.0, m);
        return;
    }
    // Off the view (partly or wholly): depth-first over the midpoint subdivision, pieces as barycentric
    // corners (b, c weights; a = 1 - b - c) so that positions and texture coordinates follow.
    float edge = max(length(p[1] - p[0]), max(length(p[2] - p[1]), length(p[0] - p[2])));
    vec2 stack[3 * (3 * MAX_DEPTH + 1)];
    int level[3 * MAX_DEPTH + 1];
    stack[0] = vec2(0.0), stack[1] = vec2(1.0, 0.0), stack[2] = vec2(0.0, 1.0);
    level[0] = 0;
    int top = 1;
    while (top > 0) {
        top--;
        vec2 w[3] = vec2[3](stack[3 * top], stack[3 * top + 1], stack[3 * top + 2]);
        int l = level[top];
        vec3 q[3];
        bool in_view = true;
        for (int k = 0; k < 3; k++) {
            q[k] = p[0] + w[k].x * (p[1] - p[0]) + w[k].y * (p[2] - p[0]);
            in_view = in_view && outside_view(q[k]) == 0.0;
        }
        vec3 centre = (q[0] + q[1] + q[2]) / 3.0;
        float size = edge / float(1 << l), a = area / float(1 << (2 * l));
        float dist = max(outside_view(centre) - size, 0.0); // to the view, from the piece's nearest point
        if (dist > m.spec.w + sqrt(a / PI)) continue; // beyond the reach of every receiver
        // the smallest piece: a translucency pixel, and a 16th of the image (finer pieces along the
        // image's edge changed no image at 256 x 256 but made a 384 x 384 bust 9x the splats)
        float depth = max(-(u_view * vec4(centre, 1.0)).z, u_misc.w);
        float smallest = max(float(u_divisor), max(u_viewport.x, u_viewport.y) / 16.0) * u_camera_fwd.w * depth;
        if (!in_view && l < MAX_DEPTH && size > max(smallest, u_piece_ratio * dist)) {
            vec2 ab = 0.5 * (w[0] + w[1]), bc = 0.5 * (w[1] + w[2]), ca = 0.5 * (w[2] + w[0]);
            vec2 kids[12] = vec2[12](w[0], ab, ca, ab, w[1], bc, ca, bc, w[2], bc, ca, ab);
            for (int k = 0; k < 4; k++) {
                stack[3 * top] = kids[3 * k], stack[3 * top + 1] = kids[3 * k + 1], stack[3 * top + 2] = kids[3 * k + 2];
                level[top] = l + 1;
                top++;
            }
            continue;
        }
        vec2 wc = (w[0] + w[1] + w[2]) / 3.0;
        vec2 uv = uvs[0] + wc.x * (uvs[1] - uvs[0]) + wc.y * (uvs[2] - uvs[0]);
        splat_part(q[0], q[1], q[2], n, a, uv, m);
    }
}
