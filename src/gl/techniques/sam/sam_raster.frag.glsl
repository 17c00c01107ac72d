#version 450 core
// Technique "sam": the interpolated per-vertex translucency of the front-most subsurface surface.
in vec3 v_trans;

layout(location = 0) out vec4 o_trans;

void main() { o_trans = vec4(max(v_trans, vec3(0.0)), 1.0); }
