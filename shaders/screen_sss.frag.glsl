#version 450 core
// Seed 000, pass 6: screen-space subsurface scattering with the layered pattern of section 4.2.
//  - inner kernel: (2n + 1)^2 samples at full resolution, one per pixel;
//  - layer i = 1..L: a grid of n_l x n_l cells of width w_i = d_(i-1) / (n_l - 2) pixels whose outer
//    ring of 4 (n_l - 1) cells are the samples, at p_i(s) = (s - (n_l - 1) / 2) w_i (Eq. 7),
//    d_0 = 2n + 1, d_i = d_(i-1) n_l / (n_l - 2); each sample reads the mip level nearest to its
//    footprint (one explicit level, never trilinear: GL-NOTES.md), where mip texels hold area-
//    weighted sums of position and irradiance over one object and the summed projected area; the
//    fetch is bilinear within the level (u_filtered; texelFetch otherwise, which snaps samples to
//    the level's texel grid and shows the blocky copies of section 4.1);
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

layout(location = 0) out vec4 o_sum;

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
                if (any(lessThan(sp, vec2(0.0))) || any(greaterThanEqual(sp, vec2(size0)))) continue;
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
                    vec2 uv = sp / texel / vec2(size);
                    vec4 P = textureLod(t_pos, uv, float(level));
                    if (P.w <= 0.0) continue;
                    vec4 I = textureLod(t_irr, uv, float(level));
                    if (abs(I.w / P.w - id) > 0.01) continue; // another object in the footprint
                    pos = P.xyz / P.w; irr = I.rgb / P.w; a = P.w;
                } else {
                    ivec2 q = ivec2(floor(sp / texel));
                    if (any(greaterThanEqual(q, size))) continue;
                    vec4 P = texelFetch(t_pos, q, level);
                    if (P.w <= 0.0) continue;
                    vec4 I = texelFetch(t_irr, q, level);
                    if (abs(I.w / P.w - id) > 0.01) continue;
                    pos = P.xyz / P.w; irr = I.rgb / P.w; a = P.w;
                }
                a *= area_scale;
                float r = length(pos - xo);
                layer_sum += irr * a * lut_eval(L, r, u_preintegrated != 0 ? a : 0.0);
            }
        sum += bright * layer_sum;
        d_prev *= grow;
    }
    o_sum = vec4(sum, 1.0);
}
