#version 450 core
// Shell splatting, one level: light transport from a splat to the receiver of this texel,
// F_t E A R_d(|x_i - x_o|) (or the disc-integrated R'_d(r, A) of seed 000 Eq. 5 with
// u_preintegrated), for receivers on the splat's object whose distance lies in this level's shell.
// Additive blending accumulates all splats (no depth test).
#include "common.glsl"

layout(binding = 0) uniform sampler2D r_receiver; // xyz; w: object id + 1

uniform int u_preintegrated;

flat in vec4 v_centre;
flat in vec4 v_flux;
flat in vec2 v_shell;
flat in vec4 v_lut;
flat in vec4 v_lut_scales;
flat in ivec2 v_lut_mode;
layout(location = 0) out vec4 o_accum;

void main()
{
    vec4 R = texelFetch(r_receiver, ivec2(gl_FragCoord.xy), 0);
    if (R.w != v_flux.w) discard;
    float r = length(R.xyz - v_centre.xyz);
    if (r < v_shell.x || r >= v_shell.y) discard;
    LutInfo L = LutInfo(v_lut.x, v_lut.y, v_lut.z, v_lut.w, v_lut_mode.x, v_lut_mode.y != 0, v_lut_scales);
    vec3 k = lut_eval(L, r, u_preintegrated != 0 ? v_centre.w : 0.0);
    o_accum = vec4(v_flux.rgb * k, 0.0);
}
