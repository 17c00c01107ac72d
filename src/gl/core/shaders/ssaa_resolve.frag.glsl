#version 450 core
// Supersampling antialiasing (sss_gl_renderer_desc.supersample = k): an output pixel is the mean of
// its k x k render pixels of the linear result (a box filter over the pixel's footprint, the one the
// CPU reference integrates over with its stratified camera samples), before any tone mapping. The
// render size is exactly k x the output size, so output pixel p covers render pixels [k p, k p + k).
layout(binding = 0) uniform sampler2D t_src; // frame.final at k x the output size

uniform int u_k;

layout(location = 0) out vec4 o_color;

void main()
{
    ivec2 base = ivec2(gl_FragCoord.xy) * u_k;
    vec3 sum = vec3(0.0);
    for (int y = 0; y < u_k; y++)
        for (int x = 0; x < u_k; x++) sum += texelFetch(t_src, base + ivec2(x, y), 0).rgb;
    o_color = vec4(sum / float(u_k * u_k), 1.0);
}
