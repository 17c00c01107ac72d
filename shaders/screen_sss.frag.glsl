#version 450 core
// Seed 000, pass 6: screen-space subsurface scattering with the layered pattern of section 4.2.
//  - inner kernel: (2n + 1)^2 samples at full resolution, one per pixel;
//  - layer i = 1..L: a grid of n_l x n_l cells of width w_i = d_(i-1) / (n_l - 2) pixels whose outer
//    ring of 4 (n_l - 1) cells are the samples, at p_i(s) = (s - (n_l - 1) / 2) w_i (Eq. 7),
//    d_0 = 2n + 1, d_i = d_(i-1) n_l / (n_l - 2); each sample reads the mip level nearest to its
//    footprint (one explicit level, never trilinear: GL-NOTES.md), where mip texels hold area-
//    weighted sums of position and irradiance over one object and the summed projected area; the
//    fetch is bilinear within the level (u_filtered; texelFetch otherwise, which snaps samples to
//    the level's texel grid and shows the blocky copies of section 4.1); mip texels are sums
//    normalised to 4^l pixels (mip_reduce.comp.glsl), so w^2 / 4^l scales any texel to a cell;
//  - each sample adds F_t E A R'_d(|x_i - x_o|, A) (Eq. 6) with world-space distances, A the sample's
//    surface area (the mip texel's area scaled to the cell), times sqrt(i) for layer i (section 6.1).
// The sum is written without the exit factor c_o, which the combination pass applies.
#include "common.glsl"

layout(binding = 0) uniform sampler2D t_pos; // mips: xyz, w area
layout(binding = 1) uniform sampler2D t_irr; // mips: rgb F_t E, w object id + 1

uniform int u_n;
uniform int u_nl;
uniform int u_layers;
uniform int u_brightening;
uniform int u_preintegrated;
uniform int u_filtered;
uniform int u_screen_bound;

layout(location = 0) out vec4 o_sum;

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
    vec3 sum = vec3(0.0);
    for (int dy = -u_n; dy <= u_n; dy++)
        for (int dx = -u_n; dx <= u_n; dx++) {
            ivec2 q = px + ivec2(dx, dy);
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size0))) continue;
            vec4 P = texelFetch(t_pos, q, 0);
            vec4 I = texelFetch(t_irr, q, 0);
            if (I.w != id || P.w <= 0.0) continue;
            float r = length(P.xyz - xo);
            sum += I.rgb * P.w * lut_eval(L, r, u_preintegrated != 0 ? P.w : 0.0);
        }
    vec2 centre = vec2(px) + 0.5;
    float d_prev = float(2 * u_n + 1);
    float grow = float(u_nl) / float(u_nl - 2);
    int max_level = u_counts.w - 1;
    for (int i = 1; i <= u_layers; i++) {
        float w = d_prev / float(u_nl - 2);
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
                sp = 0.5 * (lo + hi);
                vec3 pos, irr;
                float a;
                if (level == 0) {
                    vec4 P = texelFetch(t_pos, ivec2(sp), 0);
                    vec4 I = texelFetch(t_irr, ivec2(sp), 0);
                    if (I.w != id || P.w <= 0.0) continue;
                    pos = P.xyz; irr = I.rgb; a = P.w;
                } else if (u_filtered != 0) {
                    // bilinear within the level: premultiplied sums, so the filtered means are
                    // area-weighted and background texels drop out
                    vec2 uv = level_coord(sp, texel, size, size0) / vec2(size);
                    vec4 P = textureLod(t_pos, uv, float(level));
                    if (P.w <= 0.0) continue;
                    vec4 I = textureLod(t_irr, uv, float(level));
                    if (abs(I.w / P.w - id) > 0.01) continue; // another object in the footprint
                    pos = P.xyz / P.w; irr = I.rgb / P.w; a = P.w;
                } else {
                    ivec2 q = min(ivec2(floor(level_coord(sp, texel, size, size0))), size - 1);
                    vec4 P = texelFetch(t_pos, q, level);
                    if (P.w <= 0.0) continue;
                    vec4 I = texelFetch(t_irr, q, level);
                    if (abs(I.w / P.w - id) > 0.01) continue;
                    pos = P.xyz / P.w; irr = I.rgb / P.w; a = P.w;
                }
                a *= area_scale * cover;
                // The cell lies outside the previous layer's square (Chebyshev distance >= d_(i-1) / 2
                // pixels), so its points, and their mean, are at least that far from x_o's view ray:
                // d_(i-1) / 2 pixels at the mean's depth. The bilinear read of a coarse level also
                // averages texels overlapping the inner region, whose mean may come too close (bright
                // blobs on curved surfaces at coarse levels); the bound keeps the cell where it is.
                float r_min = u_screen_bound != 0
                                  ? 0.5 * d_prev * max(dot(pos - u_camera_pos.xyz, u_camera_fwd.xyz), u_misc.w) * u_camera_fwd.w
                                  : 0.0;
                float r = max(length(pos - xo), r_min);
                layer_sum += irr * a * lut_eval(L, r, u_preintegrated != 0 ? a : 0.0);
            }
        sum += bright * layer_sum;
        d_prev *= grow;
    }
    o_sum = vec4(sum, 1.0);
}
