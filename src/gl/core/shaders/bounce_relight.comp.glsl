#version 450 core
// Interreflection stage, a further bounce (interreflection.c, interreflection_bounces > 1): every source
// lit again by the lights and by the virtual lights of the bounce before (bounce_irradiance), entering
// a subsurface source with the transmittance of a diffuse field, reflected by a diffuse one.
#include "common.glsl"
#include "bounce_common.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = 11) buffer BounceSources { BounceSource bounce_sources[]; };
layout(std430, binding = 13) readonly buffer BounceTransmit { float bounce_transmit[]; };

void main()
{
    uint j = gl_GlobalInvocationID.x;
    if (j >= u_count) return;
    BounceSource s = bounce_sources[j];
    int mi = int(objects[int(bounce_tris[j].a.w + 0.5)].anim.y);
    Material m = materials[mi];
    vec3 E = bounce_irradiance(s.pos.xyz, s.nrm.xyz);
    vec3 add = s.nrm.w > 0.5 ? bounce_transmit[mi] * E : m.albedo.rgb * E;
    if (m.albedo.w > 1.5) add = vec3(0.0);
    bounce_sources[j].value = vec4(s.direct.rgb + add, 0.0);
}
