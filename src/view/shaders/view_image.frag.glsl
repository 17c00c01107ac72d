#version 450 core
// Viewer: an intermediate buffer of the technique (linear RGB, any size), stretched over the window and
// tone mapped as the scene format's exposure rule: srgb(clamp(linear * 2^exposure, 0, 1)).
layout(binding = 0) uniform sampler2D u_image;
uniform float u_exposure;
in vec2 v_uv;
out vec4 o_color;

vec3 srgb_encode(vec3 c)
{
    c = clamp(c, 0.0, 1.0);
    return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

void main()
{
    vec3 c = texture(u_image, v_uv).rgb;
    o_color = vec4(srgb_encode(max(c, vec3(0.0)) * exp2(u_exposure)), 1.0);
}
