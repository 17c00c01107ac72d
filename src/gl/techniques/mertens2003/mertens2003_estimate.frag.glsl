#version 450 core
// Mertens et al. 2003: B(x_o) = integral of E(x_i) R_d(|x_i - x_o|) dA (Eq. 4) in image space. Samples p' lie in
// the tangent plane of x_o (section 5); their radii come from four techniques combined by the balance
// heuristic (section 6.1): importance sampling of R_d(r) 2 pi r / rho for each colour channel (section
// 4; tabulated exact quantiles, tech_mertens2003.h) and uniform samples over a disc of radius R'. Each
// sample adds f(p') / D(p'), D = sum over techniques of N_m p_m(p') (area densities in the tangent
// plane; the single-technique case is Eq. 9's rho / N * R_d(r_i) / R_d(r'_i)), f = R_d(|p - x_o|) E(p)
// [J] with p the surface point the camera sees through p' and J = |dA_p / dA_p'| of the projection.
// Interleaved sampling: pixel (x, y) uses the strata k P + cell of each technique, cell = its place in
// the pattern x pattern block (P cells), so a block covers all strata once.
// Section 7.1: each light-view image is looked up too; its surface point counts when the camera does
// not see it (back sides, off-screen parts), so camera and light images partition the lit surface.
// For these lookups the same (r', phi) is placed in the plane through x_o facing the light instead of
// the tangent plane: the light's ray through p' then meets the surface at p with
// |p - x_o|^2 = r'^2 + t^2 (t along the ray), so R_d(r) <= R_d(r') and the weights stay bounded (in
// the tangent plane a thin part seen through its back gives r << r' and rare huge weights).
// The exit factor c_o is applied by mertens2003_resolve.frag.glsl.
#include "common.glsl"

layout(binding = 0) uniform sampler2D g_pos;        // xyz; w: projected area
layout(binding = 1) uniform sampler2D g_nrm;        // xyz; w: object id + 1
layout(binding = 2) uniform sampler2D t_irr;        // rgb F_t E sqrt(albedo); w: object id + 1
layout(binding = 3) uniform sampler2DArray l_pos;   // light views: xyz; w: texel area
layout(binding = 4) uniform sampler2DArray l_irr;   // rgb F_t E of that light; w: object id + 1
layout(binding = 5) uniform sampler2DArray l_nrm;   // normal

layout(std430, binding = 10) readonly buffer MertensTables { float tables[]; };

uniform int u_samples;
uniform int u_uniform;
uniform float u_uniform_radius;
uniform int u_pattern;
uniform int u_jacobian;
uniform int u_renormalize;
uniform int u_jitter;
uniform uint u_seed;
uniform int u_views;
uniform mat4 u_view_vp[4];
uniform int u_view_light[4];

layout(location = 0) out vec4 o_est;

// layout of tech_mertens2003.h
const int T = 1024;
const int G = 2048;
const int RADII_AT = 4;
const int GUIDE_AT = RADII_AT + 3 * (T + 1);
const int STRIDE = GUIDE_AT + 3 * G;
const float JACOBIAN_MAX = 10.0;

uint hash(uint x)
{
    x ^= x >> 16; x *= 0x7feb352du;
    x ^= x >> 15; x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}
float rnd(uint a, uint b) { return float(hash(a ^ hash(b + 0x9e3779b9u)) >> 8) * (1.0 / 16777216.0); }

// density per unit length of channel c's tabulated distribution at r (0 outside [0, r_T))
float table_pdf(int base, int c, float r)
{
    float rt = tables[base + c];
    if (!(rt > 0.0) || r < 0.0 || r >= rt) return 0.0;
    int g = min(int(sqrt(r / rt) * float(G)), G - 1);
    int s = int(tables[base + GUIDE_AT + c * G + g]);
    int rb = base + RADII_AT + c * (T + 1);
    while (s > 0 && r < tables[rb + s]) s--;
    while (s < T - 1 && r >= tables[rb + s + 1]) s++;
    return 1.0 / (float(T) * (tables[rb + s + 1] - tables[rb + s]));
}

// |dA_p / dA_p'| for a projection from centre e (Mertens et al. 2003, section 5): equal solid angles give
// dA_p cos(a) / d^2 = dA_p' cos(a') / d'^2. (The paper prints the inverse ratio in its integral.)
float jacobian_point(vec3 e, vec3 p, vec3 np, vec3 pp, vec3 no)
{
    vec3 a = e - p, b = e - pp;
    float d2 = dot(a, a), dp2 = dot(b, b);
    float ca = abs(dot(np, a)) * inversesqrt(d2), cb = abs(dot(no, b)) * inversesqrt(dp2);
    return min(ca > 0.0 ? cb / ca * d2 / dp2 : JACOBIAN_MAX, JACOBIAN_MAX);
}

// The surface point p the ray o + s dir meets: on the tangent plane (x_q, n_q) of the texel it falls
// in, kept within `reach` of x_q (grazing rays: the texel centre). The texel centre itself would put
// every sample closer than half a texel at r = 0, where R_d peaks (PBD: ~1/r): on a flat plane that
// overestimated B(x_o) 30x; the plane makes the estimate exact there (r = r').
vec3 on_surface(vec3 o, vec3 dir, vec3 xq, vec3 nq, float reach)
{
    float den = dot(dir, nq);
    if (abs(den) <= 1e-6 * length(dir)) return xq;
    vec3 x = o + dot(xq - o, nq) / den * dir;
    vec3 d = x - xq;
    float l = length(d);
    return l <= reach ? x : xq + d * (reach / l);
}

// Twice the surface size of a camera pixel at x (normal n), for on_surface.
float pixel_size(vec3 x, vec3 n)
{
    vec3 v = u_camera_pos.xyz - x;
    float dist = length(v);
    return 2.0 * dist * u_camera_fwd.w / max(abs(dot(n, v)) / dist, 0.2);
}

// Does the camera see the surface point x (of object id)? Then the camera image counts it.
bool camera_sees(vec3 x, vec3 n, float id, float texel)
{
    vec4 clip = u_view_proj * vec4(x, 1.0);
    if (clip.w <= 0.0) return false;
    vec2 ndc = clip.xy / clip.w;
    if (any(lessThan(ndc, vec2(-1.0))) || any(greaterThanEqual(ndc, vec2(1.0)))) return false;
    ivec2 q = ivec2((ndc * 0.5 + 0.5) * u_viewport.xy);
    vec4 N = texelFetch(g_nrm, q, 0);
    if (N.w != id) return false;
    // the two sides of a thin part lie within a pixel of each other: their normals tell them apart
    vec3 ng = normalize(N.xyz);
    if (dot(ng, n) < 0.5) return false;
    vec3 g = texelFetch(g_pos, q, 0).xyz;
    vec3 v = u_camera_pos.xyz - g;
    float dist = length(v);
    float cos_v = max(abs(dot(ng, v / dist)), 0.2);
    float tol = 2.0 * (dist * u_camera_fwd.w / cos_v + texel);
    return length(g - x) <= tol;
}

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    o_est = vec4(0.0);
    vec4 N = texelFetch(g_nrm, px, 0);
    if (N.w < 0.5) return;
    int mat = int(objects[int(N.w - 0.5)].anim.y);
    Material m = materials[mat];
    if (m.albedo.w > 0.5) return;
    float id = N.w;
    vec3 xo = texelFetch(g_pos, px, 0).xyz;
    vec3 no = normalize(N.xyz);
    vec3 t1 = normalize(cross(no, abs(no.x) < 0.6 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0)));
    vec3 t2 = cross(no, t1);
    LutInfo L = lut_info(mat);
    int base = mat * STRIDE;
    float ru = u_uniform_radius * m.spec.w;
    // samples per technique: importance samples go round-robin over the channels with a profile
    int nc[3];
    int live = 0;
    for (int c = 0; c < 3; c++) live += tables[base + c] > 0.0 ? 1 : 0;
    int k3 = 0;
    for (int c = 0; c < 3; c++) {
        nc[c] = 0;
        if (tables[base + c] > 0.0) {
            nc[c] = live > 0 ? (u_samples - k3 + live - 1) / live : 0;
            k3++;
        }
    }
    int nu = ru > 0.0 ? u_uniform : 0;
    int P = u_pattern * u_pattern;
    int cell = (px.x % u_pattern) + u_pattern * (px.y % u_pattern);
    int cell_a = (cell * (u_pattern + 1)) % P; // another permutation of the cells for the angles
    uint pix = uint(px.x) * 73856093u ^ uint(px.y) * 19349663u;
    float rot = u_jitter != 0 ? rnd(pix, u_seed * 2654435761u) : 0.0;
    vec3 cam_sum = vec3(0.0), light_sum = vec3(0.0);
    int total = 0, valid = 0;
    for (int tech = 0; tech < 4; tech++) {
        int n = tech < 3 ? nc[tech] : nu;
        for (int k = 0; k < n; k++) {
            uint sid = u_seed * 7919u + uint(tech * 65536 + k) * 2u;
            float xr = u_jitter != 0 ? rnd(pix, sid) : 0.5;
            float xa = u_jitter != 0 ? rnd(pix, sid + 1u) : 0.5;
            float strata = float(n * P);
            float u = (float(k * P + cell) + xr) / strata;
            float ua = fract((float(k * P + cell_a) + xa) / strata + rot);
            float rp, own = 0.0;
            if (tech < 3) {
                // section 4: r' from channel tech's tabulated exact quantiles
                float x = u * float(T);
                int seg = clamp(int(x), 0, T - 1);
                int rb = base + RADII_AT + tech * (T + 1);
                float r0 = tables[rb + seg], r1 = tables[rb + seg + 1];
                rp = r0 + (x - float(seg)) * (r1 - r0);
                own = 1.0 / (float(T) * (r1 - r0));
            } else {
                rp = ru * sqrt(u);
            }
            if (!(rp > 0.0)) continue;
            // balance heuristic: the combined area density of all techniques at r'
            float D = 0.0;
            for (int c = 0; c < 3; c++)
                if (nc[c] > 0) D += float(nc[c]) * (c == tech ? own : table_pdf(base, c, rp)) / (2.0 * PI * rp);
            if (rp < ru) D += float(nu) / (PI * ru * ru);
            if (!(D > 0.0) || isinf(D)) continue;
            total++;
            float phi = 2.0 * PI * ua;
            vec3 pp = xo + rp * (cos(phi) * t1 + sin(phi) * t2);
            // the camera's irradiance image (section 5)
            vec4 clip = u_view_proj * vec4(pp, 1.0);
            if (clip.w > 0.0) {
                vec2 ndc = clip.xy / clip.w;
                if (all(greaterThanEqual(ndc, vec2(-1.0))) && all(lessThan(ndc, vec2(1.0)))) {
                    ivec2 q = ivec2((ndc * 0.5 + 0.5) * u_viewport.xy);
                    vec4 I = texelFetch(t_irr, q, 0);
                    if (I.w == id) {
                        valid++;
                        vec3 np = normalize(texelFetch(g_nrm, q, 0).xyz);
                        vec3 p = on_surface(u_camera_pos.xyz, pp - u_camera_pos.xyz, texelFetch(g_pos, q, 0).xyz, np,
                                            pixel_size(texelFetch(g_pos, q, 0).xyz, np));
                        float J = 1.0;
                        if (u_jacobian != 0) J = jacobian_point(u_camera_pos.xyz, p, np, pp, no);
                        cam_sum += lut_eval(L, length(p - xo), 0.0) * I.rgb * (J / D);
                    }
                }
            }
            // the lights' irradiance images (section 7.1)
            for (int v = 0; v < u_views; v++) {
                Light li = lights[u_view_light[v]];
                bool directional = int(li.position.w + 0.5) == 2;
                vec3 ld = directional ? -li.direction.xyz : li.position.xyz - xo; // towards the light
                ld = normalize(ld);
                vec3 s1 = normalize(cross(ld, abs(ld.x) < 0.6 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0)));
                vec3 s2 = cross(ld, s1);
                vec3 pl = xo + rp * (cos(phi) * s1 + sin(phi) * s2);
                vec4 lc = u_view_vp[v] * vec4(pl, 1.0);
                if (lc.w <= 0.0) continue;
                vec2 lndc = lc.xy / lc.w;
                if (any(lessThan(lndc, vec2(-1.0))) || any(greaterThanEqual(lndc, vec2(1.0)))) continue;
                ivec3 lt = ivec3(ivec2((lndc * 0.5 + 0.5) * vec2(textureSize(l_pos, 0).xy)), v);
                vec4 LI = texelFetch(l_irr, lt, 0);
                vec4 LP = texelFetch(l_pos, lt, 0);
                if (LI.w != id || !(LP.w > 0.0)) continue;
                vec3 npl = normalize(texelFetch(l_nrm, lt, 0).xyz);
                vec3 pls = directional ? on_surface(pl, ld, LP.xyz, npl, 2.0 * sqrt(LP.w))
                                       : on_surface(li.position.xyz, pl - li.position.xyz, LP.xyz, npl, 2.0 * sqrt(LP.w));
                if (camera_sees(pls, npl, id, sqrt(LP.w))) continue;
                // always with the Jacobian: the plane facing the light is no approximation of the lit
                // surface (whose irradiance falls with cos), unlike the tangent plane in section 6.2
                float J = 1.0;
                {
                    if (directional) {
                        float cb = abs(dot(npl, ld));
                        J = min(cb > 0.0 ? 1.0 / cb : JACOBIAN_MAX, JACOBIAN_MAX);
                    } else {
                        J = jacobian_point(li.position.xyz, pls, npl, pl, ld);
                    }
                }
                light_sum += lut_eval(L, length(pls - xo), 0.0) * LI.rgb * (J / D);
            }
        }
    }
    // section 6.2: samples that missed the object in the camera image are discounted
    if (u_renormalize != 0 && valid > 0) cam_sum *= float(total) / float(valid);
    vec3 est = cam_sum + light_sum;
    if (any(isnan(est)) || any(isinf(est))) est = vec3(0.0);
    o_est = vec4(est, 1.0);
}
