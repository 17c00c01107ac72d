#version 450 core
// Maisch & Ropinski 2020, pass 4: light transport from a splat to the receiver of this low-resolution pixel,
// F_t E A R'_d(|x'_i - x_o|, A) (Eq. 6), accumulated by additive blending. x'_i is the point of the
// splat's disc (radius sqrt(A / pi), oriented along n_i) nearest to the receiver (Eq. 9, section 6.3).
// Note: Eq. 9 prints x_bar = x_o + n_i ((x_o - x_i) . n_i); the point of the splat's plane nearest
// to x_o, as the text defines it, is x_o - n_i ((x_o - x_i) . n_i), which is what we use.
#include "common.glsl"

layout(binding = 0) uniform sampler2D r_receiver;

uniform int u_preintegrated;
uniform int u_disc_adjust;

flat in vec4 v_centre; // the splat (maisch2020_splat.vert.glsl)
flat in vec4 v_normal;
flat in vec4 v_irradiance;
flat in vec4 v_lut;
flat in vec4 v_lut_scales;
flat in ivec2 v_lut_flags;
layout(location = 0) out vec4 o_accum;

void main()
{
    vec4 R = texelFetch(r_receiver, ivec2(gl_FragCoord.xy), 0);
    if (R.w != v_normal.w) discard;
    vec3 xo = R.xyz, xi = v_centre.xyz, ni = v_normal.xyz;
    float area = v_centre.w;
    vec3 xp = xi;
    if (u_disc_adjust != 0) {
        vec3 xbar = xo - ni * dot(xo - xi, ni);
        vec3 d = xbar - xi;
        float dl = length(d);
        if (dl > 0.0) xp = xi + d / dl * min(v_irradiance.w, dl);
    }
    float r = length(xp - xo);
    // Mode 2: R'_d is the mean over a COPLANAR disc of area A centred at distance r; a disc whose
    // nearest point is r' away is centred at r' + r_disk, not at r' (Eq. 9 taken with R'(r', A) counts
    // the kernel's peak at distance |r' - r_disk| that no point of the splat is that close to).
    if (u_disc_adjust == 2) r += v_irradiance.w;
    LutInfo L = LutInfo(v_lut.x, v_lut.y, v_lut.z, v_lut.w, v_lut_flags.x, v_lut_flags.y != 0, v_lut_scales);
    vec3 k = lut_eval(L, r, u_preintegrated != 0 ? area : 0.0);
    o_accum = vec4(v_irradiance.rgb * area * k, 0.0);
}
