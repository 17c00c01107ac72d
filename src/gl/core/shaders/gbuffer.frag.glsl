#version 450 core
// Pass 1 of Maisch & Ropinski 2020 (section 3.3): G-buffer with positions, normals, eta, albedo, the object mask
// (object id) and the projected pixel area.
#include "common.glsl"

uniform int u_object;

in vec3 v_pos;
in vec3 v_nrm;
in vec2 v_uv;

layout(location = 0) out vec4 o_pos;    // xyz world position; w: projected pixel area (SSS sources)
layout(location = 1) out vec4 o_nrm;    // xyz shading normal; w: object id + 1
layout(location = 2) out vec4 o_albedo; // rgb albedo (texture or diffuse reflectance); a: eta

void main()
{
    Object o = objects[u_object];
    Material m = materials[int(o.anim.y)];
    vec3 n = normalize(v_nrm);
    vec3 v = normalize(u_camera_pos.xyz - v_pos);
    bool subsurface = m.albedo.w < 0.5;
    bool diffuse = abs(m.albedo.w - 1.0) < 0.5;
    // Opaque surfaces are shaded on the side they are seen from (PBRT's matte is two-sided).
    if (diffuse && !gl_FrontFacing) n = -n;
    // The surface area one pixel covers: |dp/dx x dp/dy| on the triangle's plane.
    float area = robust_length(cross(dFdx(v_pos), dFdy(v_pos)));
    // Maisch & Ropinski 2020, section 6.2: at grazing angles (n . v < 0.2) the projected area diverges; such pixels
    // leave the screen-space sum (area 0) and are covered by the splats instead (Eq. 8).
    if (!subsurface || dot(n, v) < u_misc.y || isinf(area) || isnan(area)) area = 0.0;
    vec3 albedo = vec3(1.0);
    if (!subsurface) {
        albedo = m.albedo.rgb;
    } else if (m.params.w >= 0.0 && o.anim.w > 0.5) {
        albedo = texture(u_albedo_tex, vec3(v_uv, m.params.w)).rgb;
    }
    o_pos = vec4(v_pos, area);
    o_nrm = vec4(n, float(u_object + 1));
    o_albedo = vec4(albedo, m.params.x);
}
