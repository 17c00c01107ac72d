/* scene/scene_files.h — the files a loaded scene reads, as the inputs of a command's file set
 * (core/file_util.h sss_io_set): what no output of the command may overwrite. */
#ifndef SSS_SCENE_SCENE_FILES_H
#define SSS_SCENE_SCENE_FILES_H

#include "core/file_util.h"
#include "sss/scene.h"

/* Adds the scene file itself (scene->name), every object's mesh, splat mesh and texture, every
 * environment light's map and a glTF asset's files (scene->files). Names that are no file (a glTF
 * mesh's "asset#meshes[0]...") are harmless: a check only compares files that exist. */
void scene_add_inputs(sss_io_set *io, const sss_scene *scene);

#endif
