#version 450 core
// Technique "sam": rasterises a subsurface object with its per-vertex translucency (Eq. 12, from
// sam_vertex.comp.glsl) so that each pixel gets the barycentric blend of its triangle's vertices.
#include "common.glsl"

layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec3 a_nrm;

layout(std430, binding = 15) readonly buffer TransBlock { vec4 trans[]; };

uniform int u_object;

out vec3 v_trans;

void main()
{
    vec3 wp, wn;
    object_to_world(objects[u_object], a_pos, a_nrm, u_camera_pos.w, wp, wn);
    v_trans = trans[gl_VertexID].rgb; // indexed draw: gl_VertexID is the vertex index
    gl_Position = u_view_proj * vec4(wp, 1.0);
}
