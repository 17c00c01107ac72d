#version 450 core
// G-buffer vertex stage: the animation deforms every vertex here each frame (no precomputation).
// With LIGHT_VIEW it projects with a light's view-projection instead (chen2012's light-view G-buffer,
// the "translucent shadow map").
#include "common.glsl"

layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec3 a_nrm;
layout(location = 2) in vec2 a_uv;

uniform int u_object;
#ifdef LIGHT_VIEW
uniform mat4 u_light_vp;
#endif

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
#ifdef LIGHT_VIEW
    gl_Position = u_light_vp * vec4(wp, 1.0);
#else
    gl_Position = u_view_proj * vec4(wp, 1.0);
#endif
}
