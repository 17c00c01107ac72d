#version 450 core
// Deep Screen Space surfels (Nalbach et al. 2014, as Maisch & Ropinski 2020, section 5 describes it): every triangle
// of the (low-resolution) splat mesh, deformed by the animation like the render mesh, is subdivided
// into nt^2 similar sub-triangles, nt chosen from the camera distance and the triangle's size so that
// a surfel spans about u_surfel_pixels pixels (DSS tessellates by projected size, independently of the
// orientation and of occlusion), capped at u_max_tess (the hardware tessellation limit is 64). This
// compute pass replaces the tessellation shader. Each surfel carries its centre, normal, area and the
// transmitted irradiance F_t E at the centre (shadow maps; sqrt(albedo) at entry). Only irradiance
// culling: no view-based culling (Maisch & Ropinski 2020, section 8).
//
// Each surfel also carries the lattice's spacing h = the sub-triangles' longest edge, from which the
// splatting sizes its footprint (footprint, shell_splat.frag.glsl): its own area is small against h on
// thin triangles, and a disc of that area left the lattice in the image.
//
// Surface snapping (u_snap > 0): the sub-surfels lie on the chords of the coarse splat mesh, which on
// the 4096-triangle head lie 0.25 mm (median) to 1.6 mm (99th percentile) from the rendered surface,
// while Skin1's blue and green kernels fall off within 0.7 and 1.4 mm (1/sigma_tr): a receiver 1 mm
// above its surfels loses most of its short-range blue and green light, which showed as saturated
// orange patches the shape of splat triangles. DSS proper tessellates the rendered geometry itself, so
// a surfel that the camera sees (the G-buffer at its projection holds the same object, with a normal
// within 60 degrees of the chord's, within u_snap sqrt(triangle area) along the chord normal) is moved
// along that normal onto the G-buffer pixel's tangent plane and takes that pixel's F_t E sqrt(albedo)
// (the illumination pass: the same light_irradiance at the true position and shading normal). The
// normal test keeps the inner wall of a hollow shell (facing away from the outer wall above it) and
// every back-facing surfel where it is; hidden surfels (back side, off screen) stay on the chords,
// where their distance to the receivers is large compared with the chord error.
#include "common.glsl"

layout(local_size_x = 64) in;

struct Splat {
    vec4 centre;     // xyz; w: area
    vec4 normal;     // xyz; w: object id + 1
    vec4 irradiance; // rgb F_t E; w: the spacing h of the surfels (their footprint: shell_splat.frag.glsl)
};

layout(std430, binding = 4) writeonly buffer SplatBlock { Splat splats[]; };
layout(std430, binding = 5) buffer CommandBlock { uint cmd_count, cmd_instances, cmd_first, cmd_base; };
layout(std430, binding = 6) readonly buffer MeshPos { float mesh_pos[]; };
layout(std430, binding = 7) readonly buffer MeshIdx { uint mesh_idx[]; };
layout(std430, binding = 8) readonly buffer MeshUv { float mesh_uv[]; };

uniform int u_object;
uniform uint u_triangles;
uniform uint u_capacity;
uniform float u_irradiance_cull;
uniform float u_shadow_offset; // in units of sqrt(triangle area)
uniform float u_surfel_pixels;
uniform int u_max_tess;
uniform int u_has_uv;
uniform float u_snap; // tolerance of the surface snapping in sqrt(triangle area); 0: off

layout(binding = 0) uniform sampler2D g_pos;
layout(binding = 1) uniform sampler2D g_nrm;
layout(binding = 2) uniform sampler2D t_irr; // F_t E sqrt(albedo) of the visible pixels

// The surfel x (chord normal n) moved onto the visible surface: true with x updated and et its F_t E
// sqrt(albedo) when the camera sees it (see the header), else false and x unchanged.
bool snap_to_surface(inout vec3 x, vec3 n, float tol, out vec3 et)
{
    et = vec3(0.0);
    vec4 clip = u_view_proj * vec4(x, 1.0);
    if (!(clip.w > 0.0)) return false;
    vec2 ndc = clip.xy / clip.w;
    if (any(lessThan(ndc, vec2(-1.0))) || any(greaterThanEqual(ndc, vec2(1.0)))) return false;
    ivec2 px = ivec2((ndc * 0.5 + 0.5) * u_viewport.xy);
    vec4 G = texelFetch(g_nrm, px, 0);
    if (abs(G.w - float(u_object + 1)) > 0.5) return false;
    vec3 ng = normalize(G.xyz);
    float c = dot(n, ng);
    if (!(c > 0.5)) return false;
    float t = dot(texelFetch(g_pos, px, 0).xyz - x, ng) / c; // along n onto the pixel's tangent plane
    if (!(abs(t) <= tol)) return false;
    x += t * n;
    et = texelFetch(t_irr, px, 0).rgb;
    return true;
}

void main()
{
    uint t = gl_GlobalInvocationID.x;
    if (t >= u_triangles) return;
    Object o = objects[u_object];
    Material m = materials[int(o.anim.y)];
    vec3 p[3];
    vec2 uv[3];
    for (int k = 0; k < 3; k++) {
        uint i = mesh_idx[3u * t + uint(k)];
        uv[k] = u_has_uv != 0 ? vec2(mesh_uv[2u * i], mesh_uv[2u * i + 1u]) : vec2(0.0);
        vec3 op = vec3(mesh_pos[3u * i], mesh_pos[3u * i + 1u], mesh_pos[3u * i + 2u]);
        vec3 dn = vec3(0.0, 1.0, 0.0);
        p[k] = (o.model * vec4(anim_deform(o, op, dn, u_camera_pos.w), 1.0)).xyz;
    }
    vec3 e1 = p[1] - p[0], e2 = p[2] - p[0];
    vec3 cr = cross(e1, e2);
    float len = robust_length(cr);
    if (!(len > 0.0) || isinf(len)) return;
    vec3 n = cr / len;
    float area = 0.5 * len;
    vec3 c = (p[0] + p[1] + p[2]) / 3.0;
    float pixel = max(length(c - u_camera_pos.xyz), u_misc.w) * u_camera_fwd.w;
    float edge = max(length(e1), max(length(e2), length(p[2] - p[1])));
    int nt = clamp(int(ceil(edge / (pixel * u_surfel_pixels))), 1, u_max_tess);
    float sub_area = area / float(nt * nt);
    float spacing = edge / float(nt); // the sub-triangles' longest edge
    // the sub-surfels of a chord triangle lie inside a convex surface: lift the shadow lookups
    vec3 lift = n * u_shadow_offset * sqrt(area);
    bool textured = u_has_uv != 0 && m.params.w >= 0.0;
    bool snap = u_snap > 0.0;
    float tol = u_snap * sqrt(area);
    float inv = 1.0 / (3.0 * float(nt));
    for (int i = 0; i < nt; i++)
        for (int j = 0; j < nt - i; j++)
            for (int up = 0; up < 2; up++) {
                if (up == 1 && j >= nt - i - 1) continue;
                // centroid of the sub-triangle in the barycentric lattice: (i,j),(i+1,j),(i,j+1) for
                // the upright ones, (i+1,j),(i,j+1),(i+1,j+1) for the inverted ones
                vec2 ab = (up == 0 ? vec2(3 * i + 1, 3 * j + 1) : vec2(3 * i + 2, 3 * j + 2)) * inv;
                vec3 x = p[0] + ab.x * e1 + ab.y * e2;
                vec3 et;
                if (!(snap && snap_to_surface(x, n, tol, et))) {
                    et = vec3(0.0);
                    for (int li = 0; li < u_counts.y; li++) {
                        vec3 l;
                        vec3 E = light_irradiance(li, x + lift, n, l);
                        et += (1.0 - fr_dielectric(dot(n, l), 1.0, m.params.x)) * E;
                    }
                    if (textured) {
                        vec2 tc = uv[0] + ab.x * (uv[1] - uv[0]) + ab.y * (uv[2] - uv[0]);
                        et *= sqrt(textureLod(u_albedo_tex, vec3(tc, m.params.w), 0.0).rgb);
                    }
                }
                if (max(et.r, max(et.g, et.b)) <= u_irradiance_cull) continue;
                uint slot = atomicAdd(cmd_instances, 1u);
                if (slot >= u_capacity) continue;
                splats[slot] = Splat(vec4(x, sub_area), vec4(n, float(u_object + 1)), vec4(et, spacing));
            }
}
