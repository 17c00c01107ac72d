#version 450 core
// Shell splatting (Nalbach et al. 2014, "Deep Screen Space"; Maisch & Ropinski 2020, sections 5 and 8), one level of
// the camera's receiver pyramid: one screen-aligned quad per splat bounding the sphere of the shell's
// outer radius around the splat centre. Shell l covers world distances [D_l, D_(l+1)) with D_0 = 0,
// D_l = 2^l p / epsilon (p: the world size of an output pixel, u_base = k render pixels, at the
// splat's depth: the pyramid counts output pixels, so supersampling keeps the shells), the last shell
// reaching the kernel's reach (materials' spec.w); u_shell holds the radii in output pixels
// (common/shells.c, which also sets the render-resolution level's [0, fine_radius)). No view-based
// culling.
#include "common.glsl"

struct Splat {
    vec4 centre;     // xyz; w: area
    vec4 normal;     // xyz; w: object id + 1
    vec4 irradiance; // rgb F_t E; w: disc radius (chen2012), the surfel spacing h (dss_generate.comp.glsl)
};
layout(std430, binding = 4) readonly buffer SplatBlock { Splat splats[]; };

uniform vec2 u_shell; // inner and outer radius in output pixels (common/shells.c: shell_splat)
uniform int u_last;   // the last shell: the outer radius is the kernel's reach
uniform float u_outer0; // level 0's outer radius in output pixels (for the fine level), < 0: the reach
uniform float u_margin; // the fine level: its quad reaches this many output pixels beyond D (shell_splat.frag.glsl)
uniform uint u_capacity;
uniform float u_base; // render pixels per output pixel (the SSAA factor k)
uniform float u_footprint; // dss: f, the footprint's outer radius in surfel spacings; 0: the splat's own disc

flat out vec4 v_centre;   // xyz; w: area
flat out vec4 v_flux;     // rgb F_t E A; w: object id + 1
flat out vec3 v_shell;    // inner and outer radius (world units); z: level 0's outer radius
flat out float v_foot;    // the footprint's outer disc radius f h (world units); 0: one disc of the splat's area
// the material's LUT cascade (common.glsl LutInfo), read once per splat instead of per fragment
flat out vec4 v_lut;      // layer0, r_max, a_max, size
flat out vec4 v_lut_scales;
flat out ivec2 v_lut_mode; // levels, sqrt axes

void main()
{
    v_shell = vec3(0.0);
    v_foot = 0.0;
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
    v_foot = u_footprint * s.irradiance.w; // dss surfels carry their spacing h in irradiance.w
    v_flux = vec4(s.irradiance.rgb * s.centre.w, s.normal.w);
    v_lut = vec4(L.layer0, L.rmax, L.amax, L.size);
    v_lut_scales = L.scales;
    v_lut_mode = ivec2(L.levels, L.sqrt_axes ? 1 : 0);
    vec3 cv = (u_view * vec4(s.centre.xyz, 1.0)).xyz;
    float px = max(-cv.z, u_misc.w) * u_camera_fwd.w * u_base;
    float inner = u_shell.x * px;
    float outer = u_last != 0 ? reach : min(u_shell.y * px, reach);
    if (!(outer > inner)) return;
    v_shell = vec3(inner, outer, u_outer0 < 0.0 ? reach : min(u_outer0 * px, reach));
    float quad = outer + u_margin * px;
    vec2 bx = clamp(axis_bounds(cv.x, cv.z, quad, u_proj[0][0]), -1.0, 1.0);
    vec2 by = clamp(axis_bounds(cv.y, cv.z, quad, u_proj[1][1]), -1.0, 1.0);
    vec2 corner = vec2(gl_VertexID & 1, (gl_VertexID >> 1) & 1);
    gl_Position = vec4(mix(bx.x, bx.y, corner.x), mix(by.x, by.y, corner.y), 0.0, 1.0);
}
