#version 450 core
// Shadow maps (pass 2 of Maisch & Ropinski 2020): the same deformation as the G-buffer.
#include "common.glsl"

layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec3 a_nrm;

uniform int u_object;
uniform mat4 u_light_view_proj;

out vec3 v_pos;

void main()
{
    vec3 wp, wn;
    object_to_world(objects[u_object], a_pos, a_nrm, u_camera_pos.w, wp, wn);
    v_pos = wp;
    gl_Position = u_light_view_proj * vec4(wp, 1.0);
}
