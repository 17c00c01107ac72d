#version 450 core
// Maisch & Ropinski 2020, pass 6: screen-space subsurface scattering with the layered pattern of section 4.2.
//  - inner kernel: (2n + 1)^2 samples at full resolution, one per pixel;
//  - layer i = 1..L: a grid of n_l x n_l cells of width w_i = d_(i-1) / (n_l - 2) pixels whose outer
//    ring of 4 (n_l - 1) cells are the samples, at p_i(s) = (s - (n_l - 1) / 2) w_i (Eq. 7),
//    d_0 = 2n + 1, d_i = d_(i-1) n_l / (n_l - 2); each sample reads the mip level nearest to its
//    footprint (one explicit level, never trilinear: GL-NOTES.md), where mip texels hold area-
//    weighted sums of position and irradiance over one object and the summed projected area; the
//    fetch is bilinear within the level (FILTERED_LAYERS 1; 2: the same, per texel across depth gaps;
//    0: texelFetch, which snaps samples to the level's texel grid and shows the
//    blocky copies of section 4.1); mip texels are sums
//    normalised to 4^l pixels (mip_reduce.comp.glsl), so w^2 / 4^l scales any texel to a cell;
//  - each sample adds F_t E A R'_d(|x_i - x_o|, A) (Eq. 6) with world-space distances, A the sample's
//    surface area (the mip texel's area scaled to the cell), times sqrt(i) for layer i (section 6.1);
//    with FOOTPRINT_SPLIT (u_split > 1: footprint_split, a departure: docs/maisch2020.md) an
//    obliquely seen full-resolution sample is a strip, not a disc, and is cut into near-square pieces
//    along it (oblique_pixel); FOOTPRINT_SPLIT 2 (layer_split > 1) cuts the outer cells too (cell);
//  - supersampling (u_supersample = k): the pattern's sizes count output pixels, k render pixels each,
//    so layer i covers the same part of the image (and gets the same sqrt(i)) at every k: the inner
//    kernel is the square of (2n + 1) output pixels, every render pixel in it one sample (the ones its
//    edge cuts, for even k, with the covered fraction), and d_0 = k (2n + 1) render pixels.
// The sum is written without the exit factor c_o, which the combination pass applies.
// FILTERED_LAYERS (filtered_layers) and FOOTPRINT_SPLIT (footprint_split > 1, layer_split > 1) are compiled in
// (tech_maisch2020.c): llvmpipe runs every side of a branch for all lanes, masked, so a branch on a
// uniform costs the untaken side too (PER_TEXEL_READS alone once doubled the pass).
// OUTER_PASS (outer_divisor > 1, a departure: docs/maisch2020.md): the outer layers' sum integrates the
// kernel over cells of 2^i pixels and varies smoothly over a surface, so 1 evaluates it alone once per
// block of u_outer_divisor^2 pixels (at the block's mean pixel and position, one object), and 2 is the
// full-resolution pass: the inner block per pixel plus the blocks' sums, upsampled with weights that
// keep only blocks of the pixel's object near its tangent plane (pixels with none evaluate it exactly).
#include "common.glsl"
#ifndef FILTERED_LAYERS // without defines: the technique's defaults
#define FILTERED_LAYERS 1
#endif
#ifndef FOOTPRINT_SPLIT
#define FOOTPRINT_SPLIT 2
#endif
#ifndef OUTER_PASS
#define OUTER_PASS 0 // 0: the whole pattern per pixel
#endif

layout(binding = 0) uniform sampler2D t_pos; // mips: xyz, w area
layout(binding = 1) uniform sampler2D t_irr; // mips: rgb F_t E, w object id + 1
layout(binding = 2) uniform sampler2D t_nrm; // level 0 only: xyz shading normal

uniform int u_n;
uniform int u_nl;
uniform int u_layers;
uniform int u_brightening;
uniform int u_preintegrated;
uniform int u_screen_bound;
uniform int u_support_cutoff; // skip layers past r_max (exact; needs u_screen_bound)
uniform int u_layers_to_reach; // layers past u_layers until the image (or r_max) ends the pattern
uniform int u_supersample;
uniform int u_split; // footprint_split: most pieces per oblique full-resolution sample (<= 1: one disc)
uniform int u_layer_split; // min(layer_split, footprint_split): most pieces per oblique outer cell
uniform int u_outer_divisor; // OUTER_PASS 1, 2: render pixels per side of a block

layout(location = 0) out vec4 o_sum; // OUTER_PASS 1: rgb the block's outer sum, w its object id + 1
#if OUTER_PASS == 1
layout(location = 1) out vec4 o_block_pos; // xyz the block's mean position (where its sum was evaluated)
#elif OUTER_PASS == 2
layout(binding = 3) uniform sampler2D t_outer;     // OUTER_PASS 1's o_sum
layout(binding = 4) uniform sampler2D t_outer_pos; // OUTER_PASS 1's o_block_pos
#endif

// Texel coordinate (texel centres at k + 0.5) of the level-0 position sp in a level of `size` texels
// of `texel` pixels. A level has floor(size / 2) texels, so its last texel also covers the odd
// remainder up to size0 (mip_reduce.comp.glsl); between the centres of the last two texels the
// coordinate follows their footprints' centres, so a folded texel is read where its pixels are.
vec2 level_coord(vec2 sp, float texel, ivec2 size, ivec2 size0)
{
    vec2 last = vec2(size) - 1.0;
    vec2 c_prev = (last - 0.5) * texel;               // centre of the second-to-last texel
    vec2 c_last = 0.5 * (last * texel + vec2(size0)); // centre of the last texel's footprint
    vec2 folded = last - 0.5 + (sp - c_prev) / max(c_last - c_prev, vec2(1e-6));
    return mix(sp / texel, folded, greaterThan(sp, c_prev));
}

// Whether a (premultiplied) mip texel holds surface of object id: some area, and an area-weighted id
// equal to it (mip_reduce keeps one object per texel; a filtered read may mix two).
bool same_object(vec4 P, vec4 I, float id)
{
    return P.w > 0.0 && abs(I.w / P.w - id) <= 0.01;
}

// One outer sample: F_t E A R'_d(r, A) (Eq. 6) for a patch of area a (already scaled to the cell)
// with mean position pos and mean irradiance irr. The cell lies outside the previous layer's square
// (Chebyshev distance >= d_(i-1) / 2 pixels), so its points, and their mean, are at least that far
// from x_o's view ray: d_(i-1) / 2 pixels at the mean's depth. A bilinear read of a coarse level also
// averages texels overlapping the inner region, whose mean may come too close (bright blobs on
// curved surfaces at coarse levels); the bound keeps the cell where it is.
vec3 cell(LutInfo L, vec3 xo, vec3 pos, vec3 irr, float a, float d_prev, float cell_px)
{
    float depth = max(dot(pos - u_camera_pos.xyz, u_camera_fwd.xyz), u_misc.w);
    float r_min = u_screen_bound != 0 ? 0.5 * d_prev * depth * u_camera_fwd.w : 0.0;
#if FOOTPRINT_SPLIT == 2
    // An obliquely seen cell is a strip too (oblique_pixel): its area a over its face-on area
    // (cell_px pixels at its depth) is its elongation, along the surface's tangent toward the
    // viewer, which for a steep strip is nearly the view ray v; one disc of area a would reach
    // x_o's kernel peak from beside it (a sphere's rim: +20-35% with grazing_sources). m = 1 is the
    // one disc (Eq. 6), evaluated by the same loop: llvmpipe would run both sides of a branch.
    float wf2 = cell_px * depth * depth * u_camera_fwd.w * u_camera_fwd.w;
    float e = min(a / max(wf2, 1e-30), float(u_layer_split));
    int m = max(int(e + 0.5), 1);
    float ae = m > 1 ? min(a, float(u_layer_split) * wf2) : a;
    float len = sqrt(ae * e);
    vec3 v = normalize(u_camera_pos.xyz - pos);
    float ap = ae / float(m);
    vec3 s = vec3(0.0);
    for (int k = 0; k < m; k++) {
        float o = ((float(k) + 0.5) / float(m) - 0.5) * len;
        s += lut_eval(L, max(length(m > 1 ? pos + o * v - xo : pos - xo), r_min), u_preintegrated != 0 ? ap : 0.0);
    }
    return irr * ap * s;
#else
    float r = max(length(pos - xo), r_min);
    return irr * a * lut_eval(L, r, u_preintegrated != 0 ? a : 0.0);
#endif
}

// A full-resolution sample's patch seen at n.v = c is a w x w/c strip on the surface (w^2 = a c, its
// face-on footprint), long along t, the tangent toward the viewer. One disc of its area (Eq. 6) is far
// wider than the strip across it: at grazing angles the discs of neighbouring pixels overlap x_o's
// kernel peak and a short kernel is counted several times (a sphere's rim with grazing_sources: +100-200%;
// the paper's pixels at n.v 0.2-0.3: +35-91%). Instead the strip is cut into m ~ 1/c near-square pieces along t, each a disc of
// a / m at its own distance. The strip's length is capped at u_split widths: a pixel at a curved
// silhouette covers only ~sqrt(2 R / w) widths of surface (R the curvature radius), not the
// unbounded w / c of its tangent plane.
vec3 oblique_pixel(LutInfo L, vec3 xo, vec3 p, vec3 n, float a)
{
    vec3 v = normalize(u_camera_pos.xyz - p);
    float nv = dot(n, v);
    float c = abs(nv);
    float e = min(1.0 / max(c, 1e-6), float(u_split)); // elongation of the (capped) strip
    int m = max(int(e + 0.5), 1);
    // m = 1: one disc of area a at p (Eq. 6), by the same loop (llvmpipe would run both branches)
    float ae = m > 1 ? a * min(1.0, c * float(u_split)) : a; // area of the capped strip
    float len = sqrt(ae * e);                                 // its length: w e, w^2 = ae / e
    vec3 t = normalize(v - nv * n);                           // NaN where n = v, which m = 1 leaves unused
    float ap = ae / float(m);
    vec3 s = vec3(0.0);
    for (int k = 0; k < m; k++) {
        float o = ((float(k) + 0.5) / float(m) - 0.5) * len;
        s += lut_eval(L, length(m > 1 ? p + o * t - xo : p - xo), u_preintegrated != 0 ? ap : 0.0);
    }
    return ap * s;
}

// The inner kernel: the (2n + 1)^2 full-resolution samples around pixel px (one per render pixel;
// with supersampling the square of 2n + 1 output pixels).
vec3 inner_sum(LutInfo L, vec3 xo, float id, ivec2 px, ivec2 size0, float h)
{
    vec3 sum = vec3(0.0);
    int reach = int(ceil(h - 0.5));
    for (int dy = -reach; dy <= reach; dy++)
        for (int dx = -reach; dx <= reach; dx++) {
            ivec2 q = px + ivec2(dx, dy);
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size0))) continue;
            vec4 P = texelFetch(t_pos, q, 0);
            vec4 I = texelFetch(t_irr, q, 0);
            if (I.w != id || P.w <= 0.0) continue;
            // the fraction of the render pixel inside the square (1 but at its edge for even k)
            float a = P.w * clamp(h + 0.5 - float(abs(dx)), 0.0, 1.0) * clamp(h + 0.5 - float(abs(dy)), 0.0, 1.0);
#if FOOTPRINT_SPLIT
            sum += I.rgb * oblique_pixel(L, xo, P.xyz, texelFetch(t_nrm, q, 0).xyz, a);
#else
            float r = length(P.xyz - xo);
            sum += I.rgb * a * lut_eval(L, r, u_preintegrated != 0 ? a : 0.0);
#endif
        }
    return sum;
}

// The outer layers around the level-0 position `centre` (pixels) for a receiver at xo.
vec3 outer_sum(LutInfo L, vec3 xo, float id, vec2 centre, ivec2 size0, float h)
{
    vec3 sum = vec3(0.0);
    float d_prev = 2.0 * h;
    float grow = float(u_nl) / float(u_nl - 2);
    int max_level = u_counts.w - 1;
    float z_o = dot(xo - u_camera_pos.xyz, u_camera_fwd.xyz);
    // layers_to_reach: the paper's ten layers span 826 pixels; a close object's kernel reaches farther
    // (issue 15), so the pattern goes on until its previous square covers the image (the ring would
    // lie wholly outside it) or, with support_cutoff, past r_max.
    vec2 to_edge = max(centre, vec2(size0) - centre);
    int layers = u_layers_to_reach != 0 && u_layers > 0 ? 64 : u_layers; // layers = 0: the inner kernel alone
    for (int i = 1; i <= layers; i++) {
        if (i > u_layers && 0.5 * d_prev >= max(to_edge.x, to_edge.y)) break;
        float w = d_prev / float(u_nl - 2);
        if (u_support_cutoff != 0 && u_screen_bound != 0) {
            // Layers beyond the kernel's support add exactly nothing (lut_eval is 0 past r_max): with
            // the distance bound a cell at depth z is at least k z from x_o (k: d_prev / 2 pixels at
            // unit depth) and at least |z - z_o| - c z (its oblique pieces reach c z along the view
            // ray), so every r >= k z_o / (1 + k + c), which grows with the layer: the first layer
            // past r_max ends the pattern. A far object's pixels skip most layers.
            float k = 0.5 * d_prev * u_camera_fwd.w;
            float c = FOOTPRINT_SPLIT == 2 ? 0.5 * float(u_layer_split) * w * u_camera_fwd.w : 0.0;
            if (k * z_o / (1.0 + k + c) > L.rmax) break;
        }
        int level = clamp(int(floor(log2(w) + 0.5)), 0, max_level);
        float texel = exp2(float(level));
        float area_scale = (w * w) / (texel * texel);
        float bright = u_brightening != 0 ? sqrt(float(i)) : 1.0;
        // GL's level size rule from level 0: llvmpipe's textureSize(sampler, lod) returns wrong sizes
        // when lanes of a SIMD group disagree on lod (masked lanes included), which showed as seams.
        ivec2 size = max(size0 >> level, ivec2(1));
        vec3 layer_sum = vec3(0.0);
        int side = u_nl - 1;
        for (int k = 0; k < 4 * side; k++) {
                // the outer ring of the n_l x n_l grid, walked clockwise: 4 (n_l - 1) cells
                int j = k % side, e = k / side;
                ivec2 st = e == 0 ? ivec2(j, 0) : e == 1 ? ivec2(side, j) : e == 2 ? ivec2(side - j, side)
                                                                                  : ivec2(0, side - j);
                vec2 off = (vec2(st) - 0.5 * float(side)) * w;
                vec2 sp = centre + off; // sample position in level-0 pixels
                // The sample stands for a w x w cell; clipped to the image, it keeps the covered
                // fraction and is read at the clipped cell's centre. Switching a wide sample off
                // when its centre leaves the image put seams at the image's thirds and halves.
                vec2 lo = max(sp - 0.5 * w, vec2(0.0)), hi = min(sp + 0.5 * w, vec2(size0));
                if (any(lessThanEqual(hi, lo))) continue;
                float cover = (hi.x - lo.x) * (hi.y - lo.y) / (w * w);
                float to_cell = area_scale * cover; // a texel's area -> this sample's
                float cell_px = w * w * cover;      // the cell's pixels (face-on area at its depth)
                sp = 0.5 * (lo + hi);
                // level 0 reads the pixel under the sample; coarser levels their mean (below). The level
                // is the layer's, the same at every pixel: a loop of one or no pass (llvmpipe runs an
                // if's body masked, but leaves a loop no lane is in) skips the fetches at coarse levels.
                bool full_res = level == 0;
                vec4 P_full = vec4(0.0), I_full = vec4(0.0);
                for (int once = int(full_res); once > 0; once--) {
                    P_full = texelFetch(t_pos, ivec2(sp), 0);
                    I_full = texelFetch(t_irr, ivec2(sp), 0);
                }
#if FILTERED_LAYERS == 2
                if (full_res) {
                    if (I_full.w != id || P_full.w <= 0.0) continue;
                    layer_sum += cell(L, xo, P_full.xyz, I_full.rgb, P_full.w * to_cell, d_prev, cell_px);
                } else {
                    // Bilinear weights on the four texels. Where their mean positions agree (each
                    // within its own size, sqrt(area), of the weighted mean: one surface) the weighted
                    // sums make one sample, as the filtered read does; where they do not (two surfaces
                    // at different depths, a chin over a neck) each texel's patch is evaluated at its
                    // own mean position instead of at a mean in between, where no surface is.
                    // (Evaluating every texel on its own measured the same DSSIM within 2e-4.)
                    vec2 t = level_coord(sp, texel, size, size0) - 0.5;
                    ivec2 t0 = ivec2(floor(t));
                    vec2 f = t - vec2(t0);
                    vec4 Pk[4], Ik[4];
                    float wk[4];
                    vec4 Pf = vec4(0.0), If = vec4(0.0);
                    for (int c = 0; c < 4; c++) {
                        ivec2 o = ivec2(c & 1, c >> 1);
                        ivec2 q = clamp(t0 + o, ivec2(0), size - 1);
                        wk[c] = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
                        Pk[c] = texelFetch(t_pos, q, level);
                        Ik[c] = texelFetch(t_irr, q, level);
                        if (!same_object(Pk[c], Ik[c], id)) wk[c] = 0.0;
                        Pf += wk[c] * Pk[c];
                        If += wk[c] * Ik[c];
                    }
                    if (Pf.w <= 0.0) continue;
                    vec3 mean = Pf.xyz / Pf.w;
                    bool one_surface = true;
                    for (int c = 0; c < 4; c++)
                        if (wk[c] > 0.0 && distance(Pk[c].xyz / Pk[c].w, mean) > sqrt(Pk[c].w)) one_surface = false;
                    if (one_surface) {
                        layer_sum += cell(L, xo, mean, If.rgb / Pf.w, Pf.w * to_cell, d_prev, cell_px);
                    } else {
                        for (int c = 0; c < 4; c++)
                            if (wk[c] > 0.0)
                                layer_sum += wk[c] * cell(L, xo, Pk[c].xyz / Pk[c].w, Ik[c].rgb / Pk[c].w,
                                                          Pk[c].w * to_cell, d_prev, cell_px);
                    }
                }
#else
#if FILTERED_LAYERS == 1
                // bilinear within the level: premultiplied sums, so the filtered means are
                // area-weighted and background texels drop out
                vec2 uv = level_coord(sp, texel, size, size0) / vec2(size);
                vec4 P = textureLod(t_pos, uv, float(level)), I = textureLod(t_irr, uv, float(level));
#else
                ivec2 q = min(ivec2(floor(level_coord(sp, texel, size, size0))), size - 1);
                vec4 P = texelFetch(t_pos, q, level), I = texelFetch(t_irr, q, level);
#endif
                // one cell() for both reads: llvmpipe would evaluate each side of a branch
                bool found = full_res ? I_full.w == id && P_full.w > 0.0 : same_object(P, I, id);
                if (!found) continue;
                vec3 pos = full_res ? P_full.xyz : P.xyz / P.w;
                vec3 irr = full_res ? I_full.rgb : I.rgb / P.w;
                float area = (full_res ? P_full.w : P.w) * to_cell;
                layer_sum += cell(L, xo, pos, irr, area, d_prev, cell_px);
#endif
            }
        sum += bright * layer_sum;
        d_prev *= grow;
    }
    return sum;
}

#if OUTER_PASS == 1
// One block of u_outer_divisor^2 render pixels: the outer layers at the mean pixel and mean position of
// its pixels of one subsurface object (the first one found), clipped to the image at odd sizes.
void main()
{
    int d = u_outer_divisor;
    ivec2 base = ivec2(gl_FragCoord.xy) * d;
    ivec2 size0 = textureSize(t_pos, 0);
    float id = 0.0;
    int mat = 0;
    vec3 xo = vec3(0.0);
    vec2 centre = vec2(0.0);
    float count = 0.0;
    for (int y = 0; y < d; y++)
        for (int x = 0; x < d; x++) {
            ivec2 q = base + ivec2(x, y);
            if (any(greaterThanEqual(q, size0))) continue;
            vec4 I = texelFetch(t_irr, q, 0);
            if (I.w < 0.5 || (id > 0.0 && I.w != id)) continue;
            int m = int(objects[int(I.w - 0.5)].anim.y);
            if (materials[m].albedo.w > 0.5) continue;
            id = I.w;
            mat = m;
            xo += texelFetch(t_pos, q, 0).xyz;
            centre += vec2(q) + 0.5;
            count += 1.0;
        }
    o_sum = vec4(0.0);
    o_block_pos = vec4(0.0);
    if (count == 0.0) return;
    xo /= count;
    float h = float(max(u_supersample, 1)) * (float(u_n) + 0.5);
    o_sum = vec4(outer_sum(lut_info(mat), xo, id, centre / count, size0, h), id);
    o_block_pos = vec4(xo, 1.0);
}
#else
#if OUTER_PASS == 2
// The outer sum at pixel px from the blocks' (OUTER_PASS 1): bilinear weights on the four nearest
// blocks, kept only for blocks of the pixel's object and falling off with their distance from its
// tangent plane in block widths at its depth (across a depth gap of one object, a chin over a neck,
// the sum belongs to another surface). Where no block is kept the pixel evaluates the layers itself.
vec3 outer_upsampled(LutInfo L, vec3 xo, float id, ivec2 px, ivec2 size0, float h)
{
    float d = float(u_outer_divisor);
    ivec2 low = textureSize(t_outer, 0);
    vec2 t = (vec2(px) + 0.5) / d - 0.5;
    ivec2 t0 = ivec2(floor(t));
    vec2 f = t - vec2(t0);
    vec3 no = texelFetch(t_nrm, px, 0).xyz;
    float z_o = max(dot(xo - u_camera_pos.xyz, u_camera_fwd.xyz), u_misc.w);
    float block = d * z_o * u_camera_fwd.w; // a block's width at x_o's depth
    vec3 s = vec3(0.0);
    float wsum = 0.0;
    for (int c = 0; c < 4; c++) {
        ivec2 o = ivec2(c & 1, c >> 1);
        ivec2 q = clamp(t0 + o, ivec2(0), low - 1);
        vec4 O = texelFetch(t_outer, q, 0);
        float off_plane = abs(dot(texelFetch(t_outer_pos, q, 0).xyz - xo, no)) / block;
        float w = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
        w *= O.w == id ? exp(-2.0 * off_plane * off_plane) : 0.0;
        s += w * O.rgb;
        wsum += w;
    }
    vec3 sum = s / max(wsum, 1e-30);
    // a loop of one or no pass: llvmpipe skips it for SIMD groups where no pixel needs it
    for (int once = int(wsum < 0.05); once > 0; once--) sum = outer_sum(L, xo, id, vec2(px) + 0.5, size0, h);
    return sum;
}
#endif

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec4 I0 = texelFetch(t_irr, px, 0);
    o_sum = vec4(0.0);
    if (I0.w < 0.5) return;
    int mat = int(objects[int(I0.w - 0.5)].anim.y);
    if (materials[mat].albedo.w > 0.5) return;
    vec3 xo = texelFetch(t_pos, px, 0).xyz;
    LutInfo L = lut_info(mat);
    float id = I0.w;
    ivec2 size0 = textureSize(t_pos, 0);
    // the inner square's half-width h in render pixels (k = 1: n + 1/2, the (2n + 1)^2 pixels)
    float h = float(max(u_supersample, 1)) * (float(u_n) + 0.5);
    vec3 sum = inner_sum(L, xo, id, px, size0, h);
#if OUTER_PASS == 2
    sum += outer_upsampled(L, xo, id, px, size0, h);
#else
    sum += outer_sum(L, xo, id, vec2(px) + 0.5, size0, h);
#endif
    o_sum = vec4(sum, 1.0);
}
#endif
