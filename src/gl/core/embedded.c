#include "gl/core/embedded.h"

#include <string.h>

const sss_embedded_file *sss_embedded_shader_find(const char *name)
{
    for (int i = 0; i < sss_embedded_shader_count; i++)
        if (strcmp(sss_embedded_shaders[i].name, name) == 0) return &sss_embedded_shaders[i];
    return NULL;
}
