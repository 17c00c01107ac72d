#version 450 core
// Shell splatting (Nalbach et al. 2014, "Deep Screen Space"; seed 000, sections 5 and 8), level u_level
// of the camera's receiver pyramid: one screen-aligned quad per splat bounding the sphere of the
// shell's outer radius around the splat centre. Shell l covers world distances [D_l, D_(l+1)) with
// D_0 = 0, D_l = 2^l p / epsilon (p: the world size of a full-resolution pixel at the splat's depth),
// the last shell reaching the kernel's reach (materials' spec.w). No view-based culling.
#include "common.glsl"

struct Splat {
    vec4 centre;     // xyz; w: area
    vec4 normal;     // xyz; w: object id + 1
    vec4 irradiance; // rgb F_t E; w: disc radius
};
layout(std430, binding = 4) readonly buffer SplatBlock { Splat splats[]; };

uniform int u_level;
uniform int u_levels;
uniform float u_epsilon;
uniform uint u_capacity;

flat out vec4 v_centre;   // xyz; w: area
flat out vec4 v_flux;     // rgb F_t E A; w: object id + 1
flat out vec2 v_shell;    // inner and outer radius (world units)
// the material's LUT cascade (common.glsl LutInfo), read once per splat instead of per fragment
flat out vec4 v_lut;      // layer0, r_max, a_max, size
flat out vec4 v_lut_scales;
flat out ivec2 v_lut_mode; // levels, sqrt axes

void main()
{
    v_shell = vec2(0.0);
    v_centre = vec4(0.0);
    v_flux = vec4(0.0);
    v_lut = vec4(0.0);
    v_lut_scales = vec4(0.0);
    v_lut_mode = ivec2(0);
    gl_Position = vec4(2.0, 2.0, 0.0, 1.0); // outside the viewport: the quad is culled
    if (uint(gl_InstanceID) >= u_capacity) return;
    Splat s = splats[gl_InstanceID];
    int mat = int(objects[int(s.normal.w - 0.5)].anim.y);
    Material m = materials[mat];
    float reach = m.spec.w;
    LutInfo L = lut_info(mat);
    v_centre = s.centre;
    v_flux = vec4(s.irradiance.rgb * s.centre.w, s.normal.w);
    v_lut = vec4(L.layer0, L.rmax, L.amax, L.size);
    v_lut_scales = L.scales;
    v_lut_mode = ivec2(L.levels, L.sqrt_axes ? 1 : 0);
    vec3 cv = (u_view * vec4(s.centre.xyz, 1.0)).xyz;
    float px = max(-cv.z, u_misc.w) * u_camera_fwd.w;
    float inner = u_level == 0 ? 0.0 : exp2(float(u_level)) * px / u_epsilon;
    float outer = u_level == u_levels - 1 ? reach : min(exp2(float(u_level + 1)) * px / u_epsilon, reach);
    if (!(outer > inner)) return;
    v_shell = vec2(inner, outer);
    vec2 bx = clamp(axis_bounds(cv.x, cv.z, outer, u_proj[0][0]), -1.0, 1.0);
    vec2 by = clamp(axis_bounds(cv.y, cv.z, outer, u_proj[1][1]), -1.0, 1.0);
    vec2 corner = vec2(gl_VertexID & 1, (gl_VertexID >> 1) & 1);
    gl_Position = vec4(mix(bx.x, bx.y, corner.x), mix(by.x, by.y, corner.y), 0.0, 1.0);
}
