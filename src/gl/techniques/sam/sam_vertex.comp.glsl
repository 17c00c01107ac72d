#version 450 core
// Technique "sam" (Maisch & Ropinski 2017): the per-vertex compute passes of one subsurface object, selected by PASS:
//   0 deform     world position and normal of every vertex at time t (animation + transform)
//   1 fan area   F'_i of Eq. 16 from the incident triangles at the deformed positions
//   2 update     section 3.4: each back-side link moves to the one-ring neighbour (or stays) with the
//                largest F'_j R_d(|v_j - v_o|) among those passing Eq. 13-14 (src/sam/sam_update.c)
//   3 light      L_d(v) = sum over lights F_t(n . l) E sqrt(albedo): every light type, shared shadow maps
//   4 transfer   Eq. 12 with the form factors (static) or Eq. 15's K' F' R_d (deforming), blended in time
//                with the previous frame by Eq. 17-18
// Passes 0, 1 and 3 run on the vertex set bound at 10, 11, 17-19: the render mesh, or the back-side
// mesh of section 4.4 (a lower-tessellation mesh whose vertices are the sources of Eq. 12). Passes 2 and
// 4 run on the render mesh's vertices (receivers, geom) and read the sources at 20-21 (sgeom, stopo:
// the back-side mesh's, or the render mesh's own when the map has none).
#include "common.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = 10) readonly buffer TopoBlock { uint topo[]; };   // adjacency | incidence | indices
layout(std430, binding = 11) buffer GeomBlock { vec4 geom[]; };            // 2 per vertex: (pos, F'), (normal, 0)
layout(std430, binding = 12) buffer LinkBlock { uint links[]; };           // n per vertex; 0xffffffff: none
layout(std430, binding = 13) readonly buffer CoefBlock { float coef[]; };  // 3 per link: K (static) or K'
layout(std430, binding = 14) buffer LightBlockV { vec4 ld[]; };            // L_d per vertex
layout(std430, binding = 15) buffer TransBlock { vec4 trans[]; };          // translucency per vertex
layout(std430, binding = 16) readonly buffer RdBlock { float rdtab[]; };   // R_d rgb at r_max (j / (N-1))^2
layout(std430, binding = 17) readonly buffer PosBlock { float opos[]; };   // object space
layout(std430, binding = 18) readonly buffer NrmBlock { float onrm[]; };
layout(std430, binding = 19) readonly buffer UvBlock { float ouv[]; };
layout(std430, binding = 20) readonly buffer SrcGeomBlock { vec4 sgeom[]; }; // sources: (pos, F'), (normal, 0)
layout(std430, binding = 21) readonly buffer SrcTopoBlock { uint stopo[]; };  // sources: adjacency offsets | list

uniform uint u_vertices;
uniform uint u_n;
uniform int u_object;
uniform uint u_adj_list, u_inc_off, u_inc_list, u_idx; // section offsets in topo[] (adjacency offsets at 0)
uniform float u_rd_rmax;
uniform int u_rd_size;
uniform int u_deforming; // 1: approximate form factors of Eq. 15 and criteria per frame
uniform float u_alpha;   // Eq. 18 (1 on the first frame)
uniform int u_has_uv;
uniform uint u_src_adj_list; // offset of the sources' adjacency list in stopo[]
uniform int u_same;          // 1: the sources are the receivers (no back-side mesh): no self links

const uint NONE = 0xffffffffu;

vec3 rd(float r)
{
    if (!(r < u_rd_rmax)) return vec3(0.0);
    float x = sqrt(max(r, 0.0) / u_rd_rmax) * float(u_rd_size - 1);
    int j = min(int(x), u_rd_size - 2);
    float f = x - float(j);
    vec3 a = vec3(rdtab[3 * j], rdtab[3 * j + 1], rdtab[3 * j + 2]);
    vec3 b = vec3(rdtab[3 * j + 3], rdtab[3 * j + 4], rdtab[3 * j + 5]);
    return mix(a, b, f);
}

vec3 pos(uint v) { return geom[2u * v].xyz; }
vec3 nrm(uint v) { return geom[2u * v + 1u].xyz; }
vec3 spos(uint i) { return sgeom[2u * i].xyz; }
vec3 snrm(uint i) { return sgeom[2u * i + 1u].xyz; }
float sarea(uint i) { return sgeom[2u * i].w; }

// Eq. 13 and 14: source i against receiver o
bool is_back(uint o, uint i)
{
    vec3 no = nrm(o);
    return dot(spos(i) - pos(o), no) < 0.0 && dot(snrm(i), no) < 0.0;
}

float score(uint o, uint j)
{
    if (!is_back(o, j)) return -1.0;
    vec3 k = rd(distance(spos(j), pos(o)));
    return sarea(j) * (k.r + k.g + k.b);
}

void main()
{
    uint v = gl_GlobalInvocationID.x;
    if (v >= u_vertices) return;
#if PASS == 0
    Object o = objects[u_object];
    vec3 p = vec3(opos[3u * v], opos[3u * v + 1u], opos[3u * v + 2u]);
    vec3 n = vec3(onrm[3u * v], onrm[3u * v + 1u], onrm[3u * v + 2u]);
    vec3 wp, wn;
    object_to_world(o, p, n, u_camera_pos.w, wp, wn);
    geom[2u * v] = vec4(wp, geom[2u * v].w);
    geom[2u * v + 1u] = vec4(wn, 0.0);
#elif PASS == 1
    float a = 0.0;
    for (uint e = topo[u_inc_off + v]; e < topo[u_inc_off + v + 1u]; e++) {
        uint t = topo[u_inc_list + e];
        vec3 p0 = pos(topo[u_idx + 3u * t]), p1 = pos(topo[u_idx + 3u * t + 1u]), p2 = pos(topo[u_idx + 3u * t + 2u]);
        a += robust_length(cross(p1 - p0, p2 - p0)) / 6.0; // Eq. 16
    }
    geom[2u * v].w = a;
#elif PASS == 2
    for (uint k = 0u; k < u_n; k++) {
        uint b = links[v * u_n + k];
        if (b == NONE) continue;
        uint best = b;
        float best_s = score(v, b);
        for (uint e = stopo[b]; e < stopo[b + 1u]; e++) {
            uint j = stopo[u_src_adj_list + e];
            bool taken = u_same != 0 && j == v;
            for (uint q = 0u; q < u_n && !taken; q++) taken = links[v * u_n + q] == j;
            if (taken) continue;
            float s = score(v, j);
            if (s > best_s) {
                best_s = s;
                best = j;
            }
        }
        links[v * u_n + k] = best;
    }
#elif PASS == 3
    Material m = materials[int(objects[u_object].anim.y)];
    vec3 p = pos(v), n = nrm(v);
    vec3 e = vec3(0.0);
    for (int i = 0; i < u_counts.y; i++) {
        vec3 l;
        vec3 E = light_irradiance(i, p, n, l);
        e += (1.0 - fr_dielectric(dot(n, l), 1.0, m.params.x)) * E;
    }
    // the albedo texture enters at the entry point as sqrt (illumination.frag.glsl)
    if (u_has_uv != 0 && m.params.w >= 0.0)
        e *= sqrt(textureLod(u_albedo_tex, vec3(ouv[2u * v], ouv[2u * v + 1u], m.params.w), 0.0).rgb);
    ld[v] = vec4(e, 0.0);
#else
    vec3 t = vec3(0.0);
    for (uint k = 0u; k < u_n; k++) {
        uint s = v * u_n + k, b = links[s];
        if (b == NONE) continue;
        vec3 c = vec3(coef[3u * s], coef[3u * s + 1u], coef[3u * s + 2u]);
        if (u_deforming != 0) {
            if (!is_back(v, b)) continue; // a link that no longer passes Eq. 13-14 contributes nothing
            c *= sarea(b) * rd(distance(spos(b), pos(v))); // Eq. 15: K = K' F'_i R_d(|v_i - v_o|)
        }
        t += ld[b].rgb * c; // Eq. 12
    }
    // Eq. 17: blend with the previous frame's value (alpha = 1 - (1e-10)^dt, 1 on the first frame)
    vec3 prev = trans[v].rgb;
    trans[v] = vec4(mix(prev, t, u_alpha), 1.0);
#endif
}
