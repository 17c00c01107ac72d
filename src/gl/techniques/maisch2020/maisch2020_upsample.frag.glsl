#version 450 core
// Maisch & Ropinski 2020, pass 5: bicubic upsampling of the low-resolution translucency with the fast third-order
// filter of Sigg & Hadwiger 2005 (cubic B-spline from 4 bilinear taps). The alpha channel holds the
// receivers' validity, so the result is normalised by it and silhouettes do not darken.
layout(binding = 0) uniform sampler2D u_low; // bilinear filtering enabled

uniform int u_bicubic;

layout(location = 0) out vec4 o_color;

vec4 bicubic_bspline(sampler2D tex, vec2 uv)
{
    vec2 size = vec2(textureSize(tex, 0));
    vec2 p = uv * size - 0.5;
    vec2 i = floor(p), f = p - i;
    vec2 f2 = f * f, f3 = f2 * f;
    vec2 w0 = (1.0 - 3.0 * f + 3.0 * f2 - f3) / 6.0;
    vec2 w1 = (4.0 - 6.0 * f2 + 3.0 * f3) / 6.0;
    vec2 w2 = (1.0 + 3.0 * f + 3.0 * f2 - 3.0 * f3) / 6.0;
    vec2 w3 = f3 / 6.0;
    vec2 g0 = w0 + w1, g1 = w2 + w3;
    vec2 h0 = i - 1.0 + w1 / g0 + 0.5; // texel-space positions of the two bilinear taps per axis
    vec2 h1 = i + 1.0 + w3 / g1 + 0.5;
    vec4 t00 = textureLod(tex, vec2(h0.x, h0.y) / size, 0.0);
    vec4 t10 = textureLod(tex, vec2(h1.x, h0.y) / size, 0.0);
    vec4 t01 = textureLod(tex, vec2(h0.x, h1.y) / size, 0.0);
    vec4 t11 = textureLod(tex, vec2(h1.x, h1.y) / size, 0.0);
    return g0.y * (g0.x * t00 + g1.x * t10) + g1.y * (g0.x * t01 + g1.x * t11);
}

uniform vec2 u_full_size;

void main()
{
    vec2 uv = gl_FragCoord.xy / u_full_size;
    vec4 t = u_bicubic != 0 ? bicubic_bspline(u_low, uv) : textureLod(u_low, uv, 0.0);
    // t.a: the filtered fraction of valid receivers around this pixel
    o_color = t.a > 1e-3 ? vec4(t.rgb / t.a, 1.0) : vec4(0.0);
}
