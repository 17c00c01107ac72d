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

flat out int v_splat;

void main()
{
    Splat s = splats[gl_InstanceID];
    v_splat = gl_InstanceID;
    Material m = materials[int(objects[int(s.normal.w - 0.5)].anim.y)];
    float radius = m.spec.w + s.irradiance.w; // the kernel's reach + the disc radius (Eq. 9)
    vec3 cv = (u_view * vec4(s.centre.xyz, 1.0)).xyz;
    vec2 bx = clamp(axis_bounds(cv.x, cv.z, radius, u_proj[0][0]), -1.0, 1.0);
    vec2 by = clamp(axis_bounds(cv.y, cv.z, radius, u_proj[1][1]), -1.0, 1.0);
    vec2 corner = vec2(gl_VertexID & 1, (gl_VertexID >> 1) & 1);
    gl_Position = vec4(mix(bx.x, bx.y, corner.x), mix(by.x, by.y, corner.y), 0.0, 1.0);
}
