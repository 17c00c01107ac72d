#version 450 core
// Seed 000, pass 4: one screen-aligned quad per surviving splat, the exact screen bounds of the sphere
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
