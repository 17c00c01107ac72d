#version 450 core
// maisch2020, grazing_sources (a departure, docs/maisch2020.md): gives the visible pixels that Eq. 8
// (Maisch & Ropinski 2020, section 6.2) takes out of the screen-space sum, n.v below grazing_cutoff, their projected
// area back in level 0 of the position chain, before the mip chain is rebuilt from it. They are
// surface the camera sees; the splats are for what it does not see (section 5), and with this their
// Eq. 8 cut-off is grazing_sources instead (maisch2020_splat_generate.comp.glsl), so no surface is in both parts.
// The area is w^2 / |n.v|, w^2 the pixel's area across the view ray: what the G-buffer's
// |dp/dx x dp/dy| is on the pixel's plane, from the shading normal (interpolated normals of a smooth
// mesh; the triangle's plane at a silhouette is where the area diverges). Pixels steeper than
// grazing_sources keep area 0. The diverging 1/|n.v| of the steepest ones is bounded again where the
// screen-space pass cuts a full-resolution sample into pieces (footprint_split).
#include "common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(rgba32f, binding = 0) uniform image2D g_pos; // level 0: xyz position, w area
layout(binding = 1) uniform sampler2D g_nrm;

uniform float u_grazing_sources;

void main()
{
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(px, imageSize(g_pos)))) return;
    vec4 N = texelFetch(g_nrm, px, 0);
    if (N.w < 0.5) return;
    if (materials[int(objects[int(N.w - 0.5)].anim.y)].albedo.w > 0.5) return; // subsurface only
    vec4 P = imageLoad(g_pos, px);
    if (P.w > 0.0) return;
    vec3 d = P.xyz - u_camera_pos.xyz;
    float dist = length(d);
    float c = abs(dot(normalize(N.xyz), -d / max(dist, 1e-30)));
    if (!(c >= u_grazing_sources) || !(c < u_misc.y)) return;
    // a pixel subtends (pixel size at distance 1)^2 cos^3(alpha) sr, alpha its angle off the axis:
    // at distance dist = depth / cos(alpha) that is w^2 = (pixel size depth)^2 / cos(alpha) across the ray
    float depth = max(dot(d, u_camera_fwd.xyz), u_misc.w);
    float w = u_camera_fwd.w * depth;
    float a = w * w * (dist / depth) / c;
    if (!(a > 0.0) || isinf(a)) return;
    imageStore(g_pos, px, vec4(P.xyz, a));
}
