// placeholder so the shader table is never empty; replaced by real shaders
#version 450 core
void main() {}
