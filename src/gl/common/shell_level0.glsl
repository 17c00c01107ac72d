// Level 0 of the shell pyramid (common/shells.h) at k = u_base > 1 render pixels per texel: which
// level-0 receiver stands for render pixel px (position P, normal N, object id + 1). Its own output
// pixel's when that receiver lies on the pixel's surface, else the nearest of the 3 x 3 output pixels
// around whose receiver does (same object, within an output pixel of the pixel's tangent plane), so an
// output pixel that a depth or object edge crosses averages each side's own near field by its
// coverage, and away from edges it is the k = 1 pixel (bilinear upsampling blurred it and mixed both
// sides of an edge). ivec2(-1): none (a sliver of another surface), use the validity-weighted mean.

bool level0_on_surface(sampler2D recv0, ivec2 q, vec3 P, vec3 N, float id, float tol, out float dist2)
{
    dist2 = 0.0;
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, textureSize(recv0, 0)))) return false;
    vec4 R = texelFetch(recv0, q, 0);
    if (abs(R.w - id) > 0.5) return false;
    vec3 d = R.xyz - P;
    dist2 = dot(d, d);
    return abs(dot(d, N)) <= tol;
}

ivec2 level0_texel(sampler2D recv0, int base, ivec2 px, vec3 P, vec3 N, float id)
{
    float tol = max(length(P - u_camera_pos.xyz), u_misc.w) * u_camera_fwd.w * float(base); // an output pixel
    ivec2 own = px / base;
    float d2;
    if (level0_on_surface(recv0, own, P, N, id, tol, d2)) return own;
    ivec2 best = ivec2(-1);
    float best_d2 = 1e38;
    for (int dy = -1; dy <= 1; dy++)
        for (int dx = -1; dx <= 1; dx++)
            if ((dx != 0 || dy != 0) && level0_on_surface(recv0, own + ivec2(dx, dy), P, N, id, tol, d2) &&
                d2 < best_d2) {
                best_d2 = d2;
                best = own + ivec2(dx, dy);
            }
    return best;
}
