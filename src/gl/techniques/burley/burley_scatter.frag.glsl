#version 450 core
// burley, pass 2: the screen-space integral of Burley's normalized diffusion profile over the signal
// (Golubev 2018; HDRP's SubsurfaceScattering.compute), per channel
//     S(x_o) = A int R^(r) E(x) dA,   R^(r) = (e^(-r/d) + e^(-r/(3d))) / (8 pi d r)   (normalised: int = 1).
//  - samples: n = floor(pi r_k^2 / u_pps), r_k the kernel radius (holding filter_cdf of the widest
//    channel's energy) in output pixels at the pixel's depth, capped at u_samples; n < 1 keeps the
//    pixel's own light, A E(x_o) (the kernel is under a pixel);
//  - sample i: u = (i + 1/2) / n through the closed-form inverse CDF of the widest channel (d_max), the
//    golden angle i pi (3 - sqrt 5) plus a per-pixel random rotation (u_rotate), placed on the
//    image-plane disc at the pixel's depth and read at the nearest texel;
//  - weights f / p per channel: R^_c(sqrt(r^2 + dz^2)) / R^_max(r), dz the difference in view depth
//    (u_bilateral; HDRP's ComputeBilateralWeight), 0 on another object, a diffuse one or the background;
//  - the estimate sum(w E) / sum(w) (HDRP's renormalisation: the light of the samples that remain), A x it;
//  - u_center: the pixel's own disc (area one pixel on the image plane) integrated exactly, F_c(rho / d_c)
//    E(x_o), and the samples drawn from the rest of the widest channel's CDF, weighted 1 - F_c(rho / d_c).
// Output: rgb the subsurface light (before c_o sqrt(albedo)), a: the sample count n.
#include "common.glsl"

layout(binding = 0) uniform sampler2D t_signal; // rgb signal; a: object id + 1 on subsurface pixels, 0 elsewhere
layout(binding = 1) uniform sampler2D g_pos;

layout(std430, binding = 12) readonly buffer BurleyBlock { vec4 bd[]; };

uniform int u_samples;
uniform float u_pps;         // output pixels per sample
uniform float u_supersample; // render pixels per output pixel
uniform int u_rotate;
uniform int u_bilateral;
uniform int u_center;

layout(location = 0) out vec4 o_value;

const float GOLDEN_ANGLE = 2.39996322972865; // pi (3 - sqrt 5)

// x = r / d with F(x) = u: y = e^(-x/3) solves y^3 + 3y = 4(1 - u) (burley_fit.c, burley_inverse_cdf).
float inverse_cdf(float u)
{
    float q = 1.0 - u;
    float g = 1.0 + 4.0 * q * (2.0 * q + sqrt(1.0 + 4.0 * q * q));
    float g3 = pow(g, 1.0 / 3.0);
    return 3.0 * log((1.0 + g3 + 1.0 / g3) / (4.0 * q));
}

vec3 cdf(vec3 x) { return 1.0 - 0.25 * exp(-x) - 0.75 * exp(-x / 3.0); }

// R^(r) / (8 pi): the profile of lengths 1 / invd, normalised, without the constant (it cancels).
vec3 profile(vec3 invd, float r)
{
    vec3 e = exp(-r * invd / 3.0);
    return invd * (e * e * e + e) / r;
}

float hash01(uvec2 p)
{
    uvec2 q = p * uvec2(1597334673u, 3812015801u);
    uint n = (q.x ^ q.y) * 1597334673u;
    n ^= n >> 15;
    n *= 0x2c1b3c6du;
    n ^= n >> 12;
    return float(n) * (1.0 / 4294967296.0);
}

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec4 C = texelFetch(t_signal, px, 0);
    o_value = vec4(0.0);
    if (C.w < 0.5) return;
    int mat = int(objects[int(C.w - 0.5)].anim.y);
    vec3 A = bd[3 * mat].rgb, invd = bd[3 * mat + 1].rgb;
    float d_max = bd[3 * mat + 1].w, radius = bd[3 * mat + 2].x;
    vec3 P = texelFetch(g_pos, px, 0).xyz;
    float depth = dot(P - u_camera_pos.xyz, u_camera_fwd.xyz);
    float ppu = 1.0 / max(u_camera_fwd.w * depth, 1e-30); // render pixels per scene unit at this depth
    float r_out = radius * ppu / u_supersample;
    int n = int(min(floor(PI * r_out * r_out / u_pps), float(u_samples)));
    if (n < 1) {
        o_value = vec4(A * C.rgb, 0.0);
        return;
    }
    // the pixel's own disc: radius rho on the image plane, its share of each channel's energy
    float rho = inversesqrt(PI) / ppu;
    vec3 own = u_center != 0 ? cdf(rho * invd) : vec3(0.0);
    float u0 = u_center != 0 ? cdf(vec3(rho / d_max)).x : 0.0;
    float rot = u_rotate != 0 ? 2.0 * PI * hash01(uvec2(px)) : 0.0;
    ivec2 size = textureSize(t_signal, 0);
    vec3 sum = vec3(0.0), wsum = vec3(0.0);
    for (int i = 0; i < n; i++) {
        float r = inverse_cdf(u0 + (1.0 - u0) * (float(i) + 0.5) / float(n)) * d_max;
        float phi = float(i) * GOLDEN_ANGLE + rot;
        ivec2 q = ivec2(floor(gl_FragCoord.xy + r * ppu * vec2(cos(phi), sin(phi))));
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
        vec4 S = texelFetch(t_signal, q, 0);
        if (abs(S.w - C.w) >= 0.5) continue; // another object, a diffuse one or the background
        float dz = u_bilateral != 0 ? dot(texelFetch(g_pos, q, 0).xyz - P, u_camera_fwd.xyz) : 0.0;
        vec3 w = profile(invd, sqrt(r * r + dz * dz)) / profile(vec3(1.0 / d_max), r).x;
        sum += w * S.rgb;
        wsum += w;
    }
    vec3 mean = mix(C.rgb, sum / max(wsum, vec3(1e-30)), greaterThan(wsum, vec3(0.0)));
    o_value = vec4(A * (own * C.rgb + (1.0 - own) * mean), float(n));
}
