// The last pass of a technique (common/): frame.final = reflected light, plus at subsurface pixels
// c_o sqrt(albedo) times the technique's subsurface light, c_o = F_t(x_o, w_o) / (pi c) (docs/physics.md §1).
// The including shader includes this file after common.glsl, then defines
//     vec3 subsurface_light(ivec2 px)
// (the sum of its transport at pixel px, before c_o sqrt(albedo)); the G-buffer is bound at units 0-2
// (g_pos, g_nrm, g_albedo, declared here) and the reflected light at 3. Linear output; tone mapping happens on display/writing (docs/scene-format.md
// exposure rule, common.glsl tone_map).

layout(binding = 0) uniform sampler2D g_pos;
layout(binding = 1) uniform sampler2D g_nrm;
layout(binding = 2) uniform sampler2D g_albedo;
layout(binding = 3) uniform sampler2D t_refl;

layout(location = 0) out vec4 o_color;

vec3 subsurface_light(ivec2 px);

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec3 refl = texelFetch(t_refl, px, 0).rgb;
    o_color = vec4(refl, 1.0);
    Material m;
    vec3 weight;
    if (!subsurface_exit(g_pos, g_nrm, g_albedo, px, m, weight)) return;
    o_color = vec4(refl + weight * subsurface_light(px), 1.0);
}
