/* scene_load.h - the one way every command reads a scene file: by its extension, a glTF file
 * (.gltf, .glb: gltf.h) or the scene format (anything else: scene.h). */
#ifndef ABRDF_SCENE_LOAD_H
#define ABRDF_SCENE_LOAD_H

#include <stddef.h>

#include "scene.h"

/* 1 if path names a glTF file (.gltf or .glb, any case). */
int scene_is_gltf(const char *path);
/* Read path into out: 0, or -1 with one line in err (as scene_parse_file / gltf_read_file). */
int scene_load(const char *path, scene *out, char *err, size_t err_size);

#endif
