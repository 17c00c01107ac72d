/* The files a loaded scene reads (scene/scene_files.h). */
#include "scene/scene_files.h"

void scene_add_inputs(sss_io_set *io, const sss_scene *scene)
{
    sss_io_add_input(io, scene->name);
    for (size_t i = 0; i < scene->object_count; i++) {
        sss_io_add_input(io, scene->objects[i].mesh_path);
        sss_io_add_input(io, scene->objects[i].splat_mesh_path);
        sss_io_add_input(io, scene->objects[i].material.texture);
    }
    for (size_t i = 0; i < scene->light_count; i++) sss_io_add_input(io, scene->lights[i].file);
    for (size_t i = 0; i < scene->file_count; i++) sss_io_add_input(io, scene->files[i]);
}
