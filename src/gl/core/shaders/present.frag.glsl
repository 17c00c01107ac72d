#version 450 core
// Tone maps the linear result for a window (docs/scene-format.md exposure rule).
#include "common.glsl"

layout(binding = 0) uniform sampler2D u_image;
uniform vec2 u_scale; // source size / window size

out vec4 o_color;

void main()
{
    ivec2 src = ivec2(gl_FragCoord.xy * u_scale);
    o_color = vec4(tone_map(texelFetch(u_image, src, 0).rgb), 1.0);
}
