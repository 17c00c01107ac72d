#version 450 core
// Maisch & Ropinski 2020, pass 4: one screen-aligned quad per surviving splat, the exact screen bounds of the sphere
// around the splat centre whose radius is the kernel's reach (the radius holding splat_energy of R_d's
// integral, at most the LUT's r_max) plus the disc radius.
#include "common.glsl"

struct Splat {
    vec4 centre;
    vec4 normal;
    vec4 irradiance;
};
layout(std430, binding = 4) readonly buffer SplatBlock { Splat splats[]; };

// The splat and its material's LUT, read once per splat here rather than per fragment (llvmpipe
// gathers an SSBO read lane by lane even when every lane reads the same splat).
flat out vec4 v_centre;     // xyz; w: area
flat out vec4 v_normal;     // xyz; w: object id + 1
flat out vec4 v_irradiance; // rgb F_t E; w: disc radius
flat out vec4 v_lut;        // LutInfo: layer0, rmax, amax, size
flat out vec4 v_lut_scales;
flat out ivec2 v_lut_flags; // LutInfo: levels, sqrt_axes

void main()
{
    Splat s = splats[gl_InstanceID];
    int mat = int(objects[int(s.normal.w - 0.5)].anim.y);
    Material m = materials[mat];
    LutInfo L = lut_info(mat);
    v_centre = s.centre;
    v_normal = s.normal;
    v_irradiance = s.irradiance;
    v_lut = vec4(L.layer0, L.rmax, L.amax, L.size);
    v_lut_scales = L.scales;
    v_lut_flags = ivec2(L.levels, int(L.sqrt_axes));
    float radius = m.spec.w + s.irradiance.w; // the kernel's reach + the disc radius (Eq. 9)
    vec3 cv = (u_view * vec4(s.centre.xyz, 1.0)).xyz;
    vec2 bx = clamp(axis_bounds(cv.x, cv.z, radius, u_proj[0][0]), -1.0, 1.0);
    vec2 by = clamp(axis_bounds(cv.y, cv.z, radius, u_proj[1][1]), -1.0, 1.0);
    vec2 corner = vec2(gl_VertexID & 1, (gl_VertexID >> 1) & 1);
    gl_Position = vec4(mix(bx.x, bx.y, corner.x), mix(by.x, by.y, corner.y), 0.0, 1.0);
}
