// common.glsl — declarations shared by every shader of the renderer: the frame uniform block, the
// object / material / light records (mirrors gl_base.h), Fresnel, the animation deformation of
// sss/scene.h, the disc-integrated kernel LUT (Maisch & Ropinski 2020, Eq. 5) and light evaluation with shadows.

const float PI = 3.14159265358979;

layout(std140, binding = 0) uniform FrameBlock {
    mat4 u_view;
    mat4 u_proj;
    mat4 u_view_proj;
    mat4 u_inv_view_proj;
    vec4 u_camera_pos;  // xyz; w: time (s)
    vec4 u_camera_fwd;  // xyz; w: pixel size on the image plane at distance 1
    vec4 u_viewport;    // width, height, 1/width, 1/height
    ivec4 u_counts;     // objects, lights, materials, mip levels
    vec4 u_misc;        // x: exposure (stops), y: area cutoff of Eq. 8 (0.2), z: shadow bias (texels), w: near
};

struct Object {
    mat4 model;
    mat4 normal_matrix;
    vec4 bounds_min;  // w: animation type (0 none, 1 twist, 2 bend, 3 wave)
    vec4 bounds_max;  // w: amplitude
    vec4 anim;        // x: period, y: material index, z: subsurface, w: has uv
};

struct Material {
    vec4 albedo;  // rgb; w: 0 subsurface, 1 diffuse
    vec4 params;  // x: eta, y: c = 1 - 2 FM1(1/eta), z: LUT layer, w: albedo texture layer (-1: none)
    vec4 lut;     // x: r_max, y: a_max, z: axes (0 linear, 1 sqrt), w: LUT size
    vec4 spec;    // x: has specular, y: roughness, z: LUT levels, w: splat reach
};

struct Light {
    vec4 position;   // xyz; w: type (0 point, 1 spot, 2 directional, 3 VPL)
    vec4 direction;  // spot axis / direction travelled / VPL normal; w: two-sided (VPL), 2 = from an environment map (directional)
    vec4 color;      // intensity (W/sr), or irradiance at normal incidence (directional)
    vec4 spot;       // x: cos total width, y: cos falloff start, z: shadow kind, w: shadow layer
    mat4 shadow_matrix;
    vec4 shadow;     // x: near, y: far, z: world texel size (at distance 1 unless orthographic), w: ortho
};

layout(std430, binding = 1) readonly buffer ObjectBlock { Object objects[]; };
layout(std430, binding = 2) readonly buffer MaterialBlock { Material materials[]; };
layout(std430, binding = 3) readonly buffer LightBlock { Light lights[]; };

layout(binding = 8) uniform sampler2DArray u_lut;
layout(binding = 9) uniform samplerCubeArrayShadow u_shadow_cube;
layout(binding = 10) uniform sampler2DArrayShadow u_shadow_2d;
layout(binding = 11) uniform sampler2DArray u_albedo_tex;

// ---- Lengths ------------------------------------------------------------------------------------

// |v| also where the sum of squares overflows: a cross product of triangle edges holds squared lengths,
// its squares fourth powers, Inf from edges of ~1.4e9 units on (the world range is 1e18). Rescaled only
// then, so that every smaller length is the same bits as length(v).
float robust_length(vec3 v)
{
    float len = length(v);
    if (!isinf(len)) return len;
    float m = max(abs(v.x), max(abs(v.y), abs(v.z)));
    return m * length(v / m);
}

// ---- Fresnel (PBRT-v3 FrDielectric) -------------------------------------------------------------

float fr_dielectric(float cos_i, float eta_i, float eta_t)
{
    cos_i = clamp(cos_i, -1.0, 1.0);
    if (cos_i <= 0.0) {
        float tmp = eta_i; eta_i = eta_t; eta_t = tmp;
        cos_i = -cos_i;
    }
    float sin_i = sqrt(max(0.0, 1.0 - cos_i * cos_i));
    float sin_t = eta_i / eta_t * sin_i;
    if (sin_t >= 1.0) return 1.0;
    float cos_t = sqrt(max(0.0, 1.0 - sin_t * sin_t));
    float r_parl = (eta_t * cos_i - eta_i * cos_t) / (eta_t * cos_i + eta_i * cos_t);
    float r_perp = (eta_i * cos_i - eta_t * cos_t) / (eta_i * cos_i + eta_t * cos_t);
    return 0.5 * (r_parl * r_parl + r_perp * r_perp);
}

// ---- Animation (sss/scene.h: object space, bounding box of the render mesh at rest) -------------

// Deforms p (and n, by the cofactor of the analytic Jacobian) at time t.
vec3 anim_deform(Object o, vec3 p, inout vec3 n, float t)
{
    int type = int(o.bounds_min.w + 0.5);
    if (type == 0) return p;
    vec3 lo = o.bounds_min.xyz, hi = o.bounds_max.xyz;
    float A = o.bounds_max.w, period = o.anim.x;
    vec3 c = 0.5 * (lo + hi);
    float H = hi.y - lo.y, W = hi.x - lo.x;
    float h = H > 0.0 ? (p.y - lo.y) / H : 0.0;
    float s = sin(2.0 * PI * t / period);
    float rad = A * PI / 180.0;
    vec3 q, a, b, cc, outp;
    if (type == 1) { // twist about the vertical axis through c
        float th = rad * h * s, ct = cos(th), st = sin(th);
        q = p - c;
        outp = vec3(c.x + q.x * ct + q.z * st, p.y, c.z - q.x * st + q.z * ct);
        float th_y = H > 0.0 ? rad * s / H : 0.0;
        a = vec3(ct, 0.0, -st);
        cc = vec3(st, 0.0, ct);
        b = vec3(0.0, 1.0, 0.0) + th_y * vec3(-q.x * st + q.z * ct, 0.0, -q.x * ct - q.z * st);
    } else if (type == 2) { // bend about +z around (c.x, lo.y)
        float ph = rad * h * h * s, cp = cos(ph), sp = sin(ph);
        vec2 q2 = vec2(p.x - c.x, p.y - lo.y);
        outp = vec3(c.x + q2.x * cp - q2.y * sp, lo.y + q2.x * sp + q2.y * cp, p.z);
        float ph_y = H > 0.0 ? 2.0 * rad * s * h / H : 0.0;
        a = vec3(cp, sp, 0.0);
        cc = vec3(0.0, 0.0, 1.0);
        b = vec3(-sp, cp, 0.0) + ph_y * vec3(-q2.x * sp - q2.y * cp, q2.x * cp - q2.y * sp, 0.0);
    } else { // wave travelling along -x
        float u = W > 0.0 ? (p.x - lo.x) / W : 0.0;
        float arg = 2.0 * PI * (u + t / period);
        outp = vec3(p.x, p.y + A * sin(arg), p.z);
        a = vec3(1.0, W > 0.0 ? A * (2.0 * PI / W) * cos(arg) : 0.0, 0.0);
        b = vec3(0.0, 1.0, 0.0);
        cc = vec3(0.0, 0.0, 1.0);
    }
    vec3 cof = cross(b, cc) * n.x + cross(cc, a) * n.y + cross(a, b) * n.z;
    float det = dot(a, cross(b, cc));
    vec3 m = det < 0.0 ? -cof : cof;
    float len = length(m);
    n = len > 0.0 ? m / len : n;
    return outp;
}

// World position and normal of an object-space vertex at time t.
void object_to_world(Object o, vec3 p, vec3 n, float t, out vec3 wp, out vec3 wn)
{
    vec3 dn = n;
    vec3 dp = anim_deform(o, p, dn, t);
    wp = (o.model * vec4(dp, 1.0)).xyz;
    vec3 m = mat3(o.normal_matrix) * dn;
    float len = length(m);
    wn = len > 0.0 ? m / len : vec3(0.0, 1.0, 0.0);
}

// ---- Kernel LUT: R'_d(r, A), the mean of R_d over a disc of area A at distance r (Maisch & Ropinski 2020, Eq. 5) -

layout(std430, binding = 9) readonly buffer LutScaleBlock { float lut_scales[]; };

// A material's LUT cascade, loaded once per pixel or splat (level l: r_max / 16^l, A_max / 256^l).
struct LutInfo {
    float layer0;  // first array layer
    float rmax;    // level 0
    float amax;
    float size;    // texels per axis
    int levels;    // at most 4
    bool sqrt_axes;
    vec4 scales;   // lut_scales of the levels
};

LutInfo lut_info(int mat)
{
    Material m = materials[mat];
    int levels = clamp(int(m.spec.z + 0.5), 1, 4);
    int l0 = int(m.params.z + 0.5);
    vec4 sc = vec4(lut_scales[l0]);
    for (int l = 1; l < levels; l++) sc[l] = lut_scales[l0 + l];
    return LutInfo(m.params.z, m.lut.x, m.lut.y, m.lut.w, levels, m.lut.z > 0.5, sc);
}

vec3 lut_fetch(float layer, float tr, float ta, float size)
{
    vec2 uv = (vec2(tr, ta) * (size - 1.0) + 0.5) / size;
    return textureLod(u_lut, vec3(uv, layer), 0.0).rgb;
}

// Written without early returns and with at most two fetches: llvmpipe runs every side of a branch for
// all lanes of its SIMD group (masked), so each return path's fetches would be paid at every call.
vec3 lut_eval(LutInfo L, float r, float area)
{
    // A disc larger than the table's largest: all of R_d's energy lies inside it, so the mean falls as
    // 1/A (exact when r + r_A exceeds r_max everywhere the kernel is non-zero).
    float scale = 1.0;
    if (area > L.amax) { scale = L.amax / area; area = L.amax; }
    // The finest level of the cascade that holds both r and A: level l needs r <= r_max / 16^l and
    // A <= A_max / 256^l, i.e. max(r / r_max, sqrt(A / A_max)) <= 16^-l.
    float q = max(r / L.rmax, sqrt(area / L.amax));
    int level = q > 0.0 ? min(int(-log2(q) * 0.25), L.levels - 1) : L.levels - 1;
    float f = exp2(-4.0 * float(level));
    float rmax = L.rmax * f, amax = L.amax * f * f;
    float layer = L.layer0 + float(level);
    scale *= L.scales[level];
    float tr = min(r / rmax, 1.0);
    float ta = area / amax;
    if (L.sqrt_axes) { tr = sqrt(tr); ta = sqrt(ta); }
    // ta of the first row above A = 0
    float t1 = 1.0 / (L.size - 1.0);
    // Below the first row, interpolating the mean linearly towards R_d(r) (row 0) overestimates
    // it near R_d's peak by orders of magnitude. There the disc integral grows like r_A (R_d ~ 1/r
    // near 0), so R'(r, A) ~ sqrt(A_1 / A) R'(r, A_1); away from the peak R'(r, A) -> R_d(r).
    bool below_row1 = ta < t1;
    vec3 at_ta = lut_fetch(layer, tr, below_row1 ? 0.0 : ta, L.size); // row 0 below the first row
    // row 1 only below it: a loop, not an if, since llvmpipe leaves a loop when no lane of the SIMD
    // group is in it (an if runs masked), so groups of large areas (outer cells, splats) skip the fetch
    vec3 row1 = vec3(0.0);
    for (int once = int(below_row1); once > 0; once--) row1 = lut_fetch(layer, tr, t1, L.size);
    float ratio = L.sqrt_axes ? t1 / ta : sqrt(t1 / ta); // sqrt(A_1 / A)
    vec3 below = area <= 0.0 ? at_ta : min(ratio * row1, at_ta);
    // beyond the kernel's cut-off radius: 0 (Maisch & Ropinski 2020, section 7.1)
    return r > L.rmax ? vec3(0.0) : scale * (below_row1 ? below : at_ta);
}

vec3 lut_rd(int mat, float r, float area) { return lut_eval(lut_info(mat), r, area); }

// ---- Lights ----------------------------------------------------------------------------------

float spot_falloff(Light L, vec3 w)
{
    float cos_t = dot(normalize(L.direction.xyz), w);
    if (cos_t < L.spot.x) return 0.0;
    if (cos_t >= L.spot.y) return 1.0;
    float d = (cos_t - L.spot.x) / (L.spot.y - L.spot.x);
    return (d * d) * (d * d); // PBRT-v3 SpotLight::Falloff
}

// Visibility of the light from p (1 lit, 0 shadowed); ng: geometric normal facing the light.
float shadow_visibility(Light L, vec3 p, vec3 ng)
{
    int kind = int(L.spot.z + 0.5);
    if (kind == 0) return 1.0;
    float bias = u_misc.z;
    if (kind == 1) {
        vec3 d0 = p - L.position.xyz;
        float texel = length(d0) * L.shadow.z;
        vec3 pb = p + ng * bias * texel;
        vec3 d = pb - L.position.xyz;
        float dist = length(d);
        float ref = (dist - bias * texel) / L.shadow.y;
        return texture(u_shadow_cube, vec4(d, L.spot.w), ref);
    }
    float texel = L.shadow.w > 0.5 ? L.shadow.z : length(p - L.position.xyz) * L.shadow.z;
    vec3 pb = p + ng * bias * texel;
    vec4 clip = L.shadow_matrix * vec4(pb, 1.0);
    if (clip.w <= 0.0) return 1.0;
    vec3 ndc = clip.xyz / clip.w;
    vec2 uv = ndc.xy * 0.5 + 0.5;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return 1.0;
    float ref = ndc.z * 0.5 + 0.5;
    if (ref >= 1.0) return 1.0;
    return texture(u_shadow_2d, vec4(uv, L.spot.w, ref));
}

// Irradiance at p from light L on a surface facing it (no cosine, no shadow): inverse square, spot
// falloff and a virtual light's emission cosine; l receives the direction to the light.
vec3 light_incident(Light L, vec3 p, out vec3 l)
{
    int type = int(L.position.w + 0.5);
    if (type == 2) {
        l = -L.direction.xyz;
        return L.color.rgb;
    }
    vec3 d = L.position.xyz - p;
    float d2 = max(dot(d, d), 1e-20);
    l = d * inversesqrt(d2);
    vec3 E = L.color.rgb / d2;
    if (type == 1) E *= spot_falloff(L, -l);
    if (type == 3) {
        float ce = dot(L.direction.xyz, -l);
        E *= L.direction.w > 0.5 ? abs(ce) : max(ce, 0.0);
    }
    return E;
}

// Irradiance at p (normal n) from light i, shadows included; l receives the direction to the light.
vec3 light_irradiance(int i, vec3 p, vec3 n, out vec3 l)
{
    Light L = lights[i];
    vec3 E = light_incident(L, p, l);
    float cos_l = dot(n, l);
    if (cos_l <= 0.0 || max(E.r, max(E.g, E.b)) <= 0.0) return vec3(0.0);
    return E * cos_l * shadow_visibility(L, p, n);
}

// ---- Display --------------------------------------------------------------------------------

vec3 srgb_encode(vec3 c)
{
    c = clamp(c, 0.0, 1.0);
    return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

// docs/scene-format.md render.exposure: out = srgb(clamp(linear * 2^exposure, 0, 1)).
vec3 tone_map(vec3 linear_rgb)
{
    return srgb_encode(linear_rgb * exp2(u_misc.x));
}

float luminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

// ---- The subsurface integral's constant at the exit point (docs/physics.md §1, Maisch & Ropinski 2020, section 3.1) ---

// c_o = F_t(x_o, w_o) / (pi c), c = 1 - 2 FM1(1/eta), F_t = 1 - FrDielectric(cos theta_o, 1, eta): the
// same factor as the CPU reference, so both images are comparable in absolute terms.
float exit_factor(Material m, vec3 n, vec3 v)
{
    // |n . v|, as the ground truth (ref_render.c): an interpolated normal may face away from the camera
    // on a visible triangle (creases, silhouettes); clamping to grazing made F_t ~ 0 there, i.e. isolated
    // black pixels on lit skin
    float cos_o = abs(dot(n, v));
    float ft = 1.0 - fr_dielectric(max(cos_o, 1e-4), 1.0, m.params.x);
    return ft / (PI * m.params.y);
}

// The exit side of one G-buffer pixel for the techniques' final passes: true on a subsurface object,
// with its material and weight = c_o sqrt(albedo) (the albedo's exit half; Maisch & Ropinski 2020, pass 7), so that
// the pixel shows reflected + weight * (scattered irradiance); false on diffuse objects and background.
bool subsurface_exit(sampler2D g_pos, sampler2D g_nrm, sampler2D g_albedo, ivec2 px, out Material m,
                     out vec3 weight)
{
    vec4 N = texelFetch(g_nrm, px, 0);
    weight = vec3(0.0);
    if (N.w < 0.5) return false;
    m = materials[int(objects[int(N.w - 0.5)].anim.y)];
    if (m.albedo.w > 0.5) return false;
    vec3 v = normalize(u_camera_pos.xyz - texelFetch(g_pos, px, 0).xyz);
    weight = exit_factor(m, normalize(N.xyz), v) * sqrt(texelFetch(g_albedo, px, 0).rgb);
    return true;
}

// ---- Splat bounds (maisch2020's splats, dss/chen2012's shells) --------------------------------------

// NDC interval covered by a circle (centre (a, z) in the plane of one image axis and the view axis,
// camera at the origin looking down -z), or [-1, 1] when the camera is too close.
vec2 axis_bounds(float a, float z, float radius, float scale)
{
    float d2 = a * a + z * z;
    if (-z - radius <= u_misc.w || d2 <= radius * radius) return vec2(-1.0, 1.0);
    float d = sqrt(d2);
    float sin_t = radius / d, cos_t = sqrt(max(0.0, 1.0 - sin_t * sin_t));
    vec2 c = vec2(a, z) / d;
    vec2 t1 = vec2(c.x * cos_t - c.y * sin_t, c.x * sin_t + c.y * cos_t);
    vec2 t2 = vec2(c.x * cos_t + c.y * sin_t, -c.x * sin_t + c.y * cos_t);
    if (t1.y >= 0.0 || t2.y >= 0.0) return vec2(-1.0, 1.0);
    float p1 = scale * t1.x / -t1.y, p2 = scale * t2.x / -t2.y;
    return vec2(min(p1, p2), max(p1, p2));
}
