#version 450 core
// Light-view G-buffer of one light (Dachsbacher & Stamminger 2003; the irradiance buffer of Chen et
// al. 2012 and the light-view irradiance image of Mertens et al. 2003, section 7.1): world position and the
// surface area the texel covers, transmitted irradiance F_t E of this light with sqrt(albedo) at entry
// (as the camera's illumination pass), and the normal. Texels of opaque objects occlude (depth test)
// but carry no area, so the reductions and the splat selection skip them.
#include "common.glsl"

uniform int u_object;
uniform int u_light;

in vec3 v_pos;
in vec3 v_nrm;
in vec2 v_uv;

layout(location = 0) out vec4 o_pos; // xyz; w: surface area of the texel (0: not subsurface)
layout(location = 1) out vec4 o_irr; // rgb F_t E sqrt(albedo); w: object id + 1
layout(location = 2) out vec4 o_nrm; // xyz normal; w: object id + 1

void main()
{
    Object o = objects[u_object];
    Material m = materials[int(o.anim.y)];
    vec3 n = normalize(v_nrm);
    float id = float(u_object + 1);
    // |dp/dx x dp/dy|: the surface area behind one texel (large at grazing light, where E is small)
    float area = robust_length(cross(dFdx(v_pos), dFdy(v_pos)));
    bool subsurface = m.albedo.w < 0.5;
    vec3 et = vec3(0.0);
    if (subsurface) {
        vec3 l;
        vec3 E = light_irradiance(u_light, v_pos, n, l);
        et = (1.0 - fr_dielectric(dot(n, l), 1.0, m.params.x)) * E;
        if (m.params.w >= 0.0 && o.anim.w > 0.5) et *= sqrt(texture(u_albedo_tex, vec3(v_uv, m.params.w)).rgb);
    }
    if (!subsurface || isinf(area) || isnan(area) || any(isnan(et)) || any(isinf(et))) {
        area = 0.0;
        et = vec3(0.0);
    }
    o_pos = vec4(v_pos, area);
    o_irr = vec4(et, id);
    o_nrm = vec4(n, id);
}
