#version 450 core
// A caller's depth buffer as the position input of a pass (sss/gl_pass.h, `depth`): the world position
// from the inverse of the caller's projection x view, and the surface area one pixel covers, from the
// pixel's solid angle and the distance and normal there (a pinhole pixel at angle theta off the view
// axis spans ps_x ps_y cos^3(theta) steradians, which cover r^2 / |n.v| of surface): differences of
// positions reconstructed from a depth buffer are too coarse for it (a 32-bit depth 1e4 x the near
// plane away holds the distance to 6e-4, a pixel is ~2e-3 of it wide). w = 0 as the G-buffer sets it:
// background, not subsurface, n.v below the technique's grazing cut-off (u_misc.y).
#include "common.glsl"

layout(binding = 0) uniform sampler2D t_depth;
layout(binding = 1) uniform sampler2D g_nrm;

uniform mat4 u_caller_inv_view_proj; // the caller's matrices' (not the frame block's reversed-Z ones)
uniform int u_zero_to_one;           // 1: depth is NDC z (reversed-Z, GL_ZERO_TO_ONE); 0: NDC z = 2 depth - 1
uniform float u_background;          // the far value: 1, or 0 for reversed-Z
uniform vec2 u_pixel;                // pixel width and height on the image plane at distance 1

layout(location = 0) out vec4 o_pos;

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    float d = texelFetch(t_depth, px, 0).r;
    vec4 N = texelFetch(g_nrm, px, 0);
    o_pos = vec4(0.0);
    if (d == u_background || N.w < 0.5) return;
    vec2 ndc = (vec2(px) + 0.5) * u_viewport.zw * 2.0 - 1.0;
    vec4 w = u_caller_inv_view_proj * vec4(ndc, u_zero_to_one != 0 ? d : 2.0 * d - 1.0, 1.0);
    vec3 p = w.xyz / w.w;
    vec3 to_p = p - u_camera_pos.xyz;
    float r = length(to_p);
    vec3 n = normalize(N.xyz);
    vec3 v = -to_p / r;
    float cos_view = dot(-v, normalize(u_camera_fwd.xyz));
    float nv = dot(n, v);
    float area = u_pixel.x * u_pixel.y * cos_view * cos_view * cos_view * r * r / abs(nv);
    Material m = materials[int(objects[int(N.w - 0.5)].anim.y)];
    if (m.albedo.w > 0.5 || nv < u_misc.y || isinf(area) || isnan(area)) area = 0.0;
    o_pos = vec4(p, area);
}
