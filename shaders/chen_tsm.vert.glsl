#version 450 core
// Light-view G-buffer ("translucent shadow map"): the vertex stage of gbuffer.vert.glsl with the
// light's view-projection; the animation deforms every vertex here each frame.
#include "common.glsl"

layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec3 a_nrm;
layout(location = 2) in vec2 a_uv;

uniform int u_object;
uniform mat4 u_light_vp;

out vec3 v_pos;
out vec3 v_nrm;
out vec2 v_uv;

void main()
{
    Object o = objects[u_object];
    vec3 wp, wn;
    object_to_world(o, a_pos, a_nrm, u_camera_pos.w, wp, wn);
    v_pos = wp;
    v_nrm = wn;
    v_uv = a_uv;
    gl_Position = u_light_vp * vec4(wp, 1.0);
}
