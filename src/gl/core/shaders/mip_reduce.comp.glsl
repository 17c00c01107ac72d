#version 450 core
// Mip chains of pass 3 (Maisch & Ropinski 2020, section 3.3): one level from the previous one. Each texel keeps the
// object that covers most of its footprint (by projected area) and, over that object's children,
// sums of area-weighted quantities: pos = (sum a p, sum a), irr = (sum a F_tE, sum a id)
// (nrm = (sum a n, sum a id)). Levels >= 1 are stored PREMULTIPLIED like this, so bilinear filtering
// within a level stays a proper area-weighted mean (divide by the filtered area) and background
// texels (a = 0) drop out; level 0 is the plain G-buffer (p, a) and (F_tE, id).
// Summing keeps irradiance * area = the footprint's flux, which the screen-space kernel integrates
// (Eq. 6); a plain box filter of means would dilute it with background texels at silhouettes.
// Odd sizes: a level is floor(size / 2) texels, so the last texel of a row or column takes the odd
// child too and covers [d 2^l, base size) of level 0, up to twice the nominal 2^l pixels. Sums are
// therefore stored normalised to the nominal footprint (sum * 4^l / pixels covered): every texel,
// folded or not, is a density times 4^l, which is what the screen-space pass scales to its cells
// (w^2 / 4^l). Power-of-two sizes never fold, so there this is exactly the plain sum.
layout(local_size_x = 8, local_size_y = 8) in;

layout(rgba32f, binding = 0) readonly uniform image2D src_pos;
layout(rgba32f, binding = 1) readonly uniform image2D src_irr;
layout(rgba32f, binding = 2) writeonly uniform image2D dst_pos;
layout(rgba32f, binding = 3) writeonly uniform image2D dst_irr;
#ifdef WITH_NORMALS
layout(rgba32f, binding = 4) readonly uniform image2D src_nrm;
layout(rgba32f, binding = 5) writeonly uniform image2D dst_nrm;
#endif

uniform int u_src_premultiplied;
uniform int u_dst_level;    // level written; the source is u_dst_level - 1
uniform ivec2 u_base_size;  // level-0 size: the folded last texels reach it

// Level-0 pixels covered by texel t of a level of the given size (each axis).
ivec2 footprint(ivec2 t, int level, ivec2 size)
{
    ivec2 nominal = ivec2(1 << level);
    return mix(nominal, u_base_size - t * nominal, equal(t, size - 1));
}

void main()
{
    ivec2 dst_size = imageSize(dst_pos), src_size = imageSize(src_pos);
    ivec2 d = ivec2(gl_GlobalInvocationID.xy);
    if (d.x >= dst_size.x || d.y >= dst_size.y) return;
    // Children: 2x2, plus the odd last row/column of the source folded into the last texel.
    ivec2 lo = 2 * d;
    ivec2 hi = min(2 * d + 1, src_size - 1);
    if (d.x == dst_size.x - 1) hi.x = src_size.x - 1;
    if (d.y == dst_size.y - 1) hi.y = src_size.y - 1;
    ivec2 fd = footprint(d, u_dst_level, dst_size);
    float dst_pixels = float(fd.x * fd.y);
    float ids[9];
    float areas[9];
    int n = 0;
    for (int y = lo.y; y <= hi.y; y++)
        for (int x = lo.x; x <= hi.x; x++) {
            float a = imageLoad(src_pos, ivec2(x, y)).w;
            float id = imageLoad(src_irr, ivec2(x, y)).w;
            if (a <= 0.0) continue;
            if (u_src_premultiplied != 0) id = floor(id / a + 0.5); // mixed texels were never written
            if (id < 0.5) continue;
            int k = 0;
            while (k < n && ids[k] != id) k++;
            if (k == n) { ids[n] = id; areas[n] = 0.0; n++; }
            ivec2 fc = footprint(ivec2(x, y), u_dst_level - 1, src_size);
            areas[k] += a * float(fc.x * fc.y); // normalised sums -> real area
        }
    if (n == 0) {
        imageStore(dst_pos, d, vec4(0.0));
        imageStore(dst_irr, d, vec4(0.0));
#ifdef WITH_NORMALS
        imageStore(dst_nrm, d, vec4(0.0));
#endif
        return;
    }
    int best = 0;
    for (int k = 1; k < n; k++)
        if (areas[k] > areas[best]) best = k;
    float id = ids[best];
    vec3 sp = vec3(0.0), se = vec3(0.0), sn = vec3(0.0);
    float sa = 0.0;
    for (int y = lo.y; y <= hi.y; y++)
        for (int x = lo.x; x <= hi.x; x++) {
            vec4 P = imageLoad(src_pos, ivec2(x, y));
            vec4 E = imageLoad(src_irr, ivec2(x, y));
            if (P.w <= 0.0) continue;
            float m = 1.0; // premultiplies level 0
            float cid = E.w;
            if (u_src_premultiplied != 0) { m = 1.0 / P.w; cid = floor(E.w / P.w + 0.5); }
            if (cid != id) continue;
            // child's share of the normalised sum: 4 * its pixels / the texel's pixels (= 1 unless folded)
            ivec2 fc = footprint(ivec2(x, y), u_dst_level - 1, src_size);
            float wgt = 4.0 * float(fc.x * fc.y) / dst_pixels;
            sa += wgt * P.w;
            sp += wgt * P.w * m * P.xyz;
            se += wgt * P.w * m * E.rgb;
#ifdef WITH_NORMALS
            sn += wgt * P.w * m * imageLoad(src_nrm, ivec2(x, y)).xyz;
#endif
        }
    imageStore(dst_pos, d, vec4(sp, sa));
    imageStore(dst_irr, d, vec4(se, sa * id));
#ifdef WITH_NORMALS
    imageStore(dst_nrm, d, vec4(sn, sa * id));
#endif
}
