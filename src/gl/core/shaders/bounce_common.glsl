// bounce_common.glsl — the interreflection stage's records and its gather (interreflection.c,
// docs/interreflection.md). Include after common.glsl.

// A triangle of an object's surface in object space: a.w object index, b.w first triangle of the
// object, c.w the object's triangle count; n the object-space face normal.
struct BounceTriangle {
    vec4 a, b, c, n;
};

// A lit source: centroid and world area, normal, and (rgb) the diffuse exitance albedo E, or the
// subsurface entering irradiance F_t E: from the lights (direct) and with the bounces so far (value).
struct BounceSource {
    vec4 pos;    // xyz; w: area
    vec4 nrm;    // xyz; w: 1 subsurface, 0 diffuse
    vec4 value;  // rgb
    vec4 direct; // rgb
};

// A virtual point light: its disc (centre, area, normal) and flux M A (rgb).
struct BounceLight {
    vec4 pos;    // xyz; w: area
    vec4 nrm;    // xyz
    vec4 flux;   // rgb
};

layout(std430, binding = 10) readonly buffer BounceTriangles { BounceTriangle bounce_tris[]; };
#ifdef BOUNCE_WRITES_LIGHTS
layout(std430, binding = 12) writeonly buffer BounceLights { BounceLight bounce_vpls[]; };
#else
layout(std430, binding = 12) readonly buffer BounceLights { BounceLight bounce_vpls[]; };
#endif

uniform uint u_count;

// Irradiance at x (normal n) from every virtual light: the radiance M / pi of a Lambertian disc of area
// A, cos_i cos_j A / (d^2 + A / pi) — the on-axis irradiance of that disc, exact where the receiver
// touches the source and 1/d^2 far from it. No visibility (docs/interreflection.md). Pairs whose
// cosines multiply to 1e-6 or less exchange nothing: on a convex object that is rounding at the edges
// between facets, and so one convex surface stays exactly as without the stage.
#ifndef BOUNCE_WRITES_LIGHTS
vec3 bounce_irradiance(vec3 x, vec3 n)
{
    vec3 E = vec3(0.0);
    for (uint j = 0u; j < u_count; j++) {
        BounceLight L = bounce_vpls[j];
        vec3 d = L.pos.xyz - x;
        float d2 = dot(d, d);
        float ci = dot(n, d), cj = -dot(L.nrm.xyz, d); // cosines times d
        float cc = ci * cj / d2; // cos_i cos_j
        if (ci > 0.0 && cj > 0.0 && cc > 1e-6) E += L.flux.rgb * cc / (d2 + L.pos.w / PI);
    }
    return E / PI;
}
#endif
