#version 450 core
// Cube maps store the distance to the light over the far distance; 2D maps the projected depth.
uniform int u_cube;
uniform vec3 u_light_pos;
uniform float u_far;

in vec3 v_pos;

void main()
{
    gl_FragDepth = u_cube != 0 ? length(v_pos - u_light_pos) / u_far : gl_FragCoord.z;
}
