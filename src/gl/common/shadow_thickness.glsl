// The thickness light crosses to reach a point, from the light's shadow map (common/): the distance
// from the first surface the map sees on the light's ray to the point, shrunk along -n by the shadow
// bias (Jimenez et al. 2010, as the SSSS reference code; HDRP's "thick object" transmission). Used by
// ssss (ssss_prepare.frag.glsl) and burley (burley_prepare.frag.glsl). The including shader includes
// common.glsl first; the shadow maps are read without comparison at units 6 (cube maps) and 7 (2D),
// through sampler objects that turn the comparison off.

layout(binding = 6) uniform samplerCubeArray t_cube_raw;  // the cube shadow maps without comparison
layout(binding = 7) uniform sampler2DArray t_2d_raw;      // the 2D shadow maps without comparison

// Thickness crossed by light L to reach p (shrunk along -n); < 0 when the map cannot tell.
float shadow_thickness(Light L, vec3 p, vec3 n)
{
    int kind = int(L.spot.z + 0.5);
    if (kind == 0) return -1.0;
    float bias = u_misc.z;
    if (kind == 1) {
        float texel = length(p - L.position.xyz) * L.shadow.z;
        vec3 d = p - n * bias * texel - L.position.xyz;
        float occ = texture(t_cube_raw, vec4(d, L.spot.w)).r * L.shadow.y;
        return max(length(d) - occ, 0.0);
    }
    float texel = L.shadow.w > 0.5 ? L.shadow.z : length(p - L.position.xyz) * L.shadow.z;
    vec3 ps = p - n * bias * texel;
    vec4 clip = L.shadow_matrix * vec4(ps, 1.0);
    if (clip.w <= 0.0) return -1.0;
    vec3 ndc = clip.xyz / clip.w;
    vec2 uv = ndc.xy * 0.5 + 0.5;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return -1.0;
    float zocc = texture(t_2d_raw, vec3(uv, L.spot.w)).r * 2.0 - 1.0;
    if (zocc >= ndc.z) return 0.0;
    // the occluder on the same light ray, back in world space
    vec4 w = inverse(L.shadow_matrix) * vec4(ndc.xy, zocc, 1.0);
    return length(ps - w.xyz / w.w);
}
