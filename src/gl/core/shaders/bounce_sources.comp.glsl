#version 450 core
// Interreflection stage, step 1 (interreflection.c): every source triangle at the frame's time
// (animation as the render mesh), lit by the scene's lights through the shadow maps. Diffuse sources
// keep their exitance albedo E; subsurface ones the irradiance that enters, F_t E, which step 2 scatters.
#include "common.glsl"
#include "bounce_common.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = 11) writeonly buffer BounceSources { BounceSource bounce_sources[]; };

void main()
{
    uint j = gl_GlobalInvocationID.x;
    if (j >= u_count) return;
    BounceTriangle t = bounce_tris[j];
    Object o = objects[int(t.a.w + 0.5)];
    Material m = materials[int(o.anim.y)];
    float time = u_camera_pos.w;
    vec3 x, n, w0, w1, w2, unused;
    object_to_world(o, (t.a.xyz + t.b.xyz + t.c.xyz) / 3.0, t.n.xyz, time, x, n);
    object_to_world(o, t.a.xyz, t.n.xyz, time, w0, unused);
    object_to_world(o, t.b.xyz, t.n.xyz, time, w1, unused);
    object_to_world(o, t.c.xyz, t.n.xyz, time, w2, unused);
    float area = 0.5 * robust_length(cross(w1 - w0, w2 - w0));
    bool diffuse = m.albedo.w > 0.5;
    // a simplified subsurface surface lies inside the rendered one: lift its shadow lookups (as dss)
    vec3 lift = diffuse ? vec3(0.0) : n * 0.5 * sqrt(area);
    vec3 value = vec3(0.0);
    for (int li = 0; li < u_counts.y; li++) {
        vec3 l;
        vec3 E = light_irradiance(li, x + lift, n, l);
        value += diffuse ? E : (1.0 - fr_dielectric(dot(n, l), 1.0, m.params.x)) * E;
    }
    if (diffuse) value *= m.albedo.rgb;
    if (m.albedo.w > 1.5 || !(area > 0.0) || isinf(area)) value = vec3(0.0); // emitters, degenerate
    bounce_sources[j] = BounceSource(vec4(x, area), vec4(n, diffuse ? 0.0 : 1.0), vec4(value, 0.0), vec4(value, 0.0));
}
