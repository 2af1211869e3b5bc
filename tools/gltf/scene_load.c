/* scene_load.c - scene files by their extension (scene_load.h). */
#include <string.h>
#include <strings.h>

#include "gltf.h"
#include "scene_load.h"

int scene_is_gltf(const char *path)
{
    const char *dot = path ? strrchr(path, '.') : NULL, *slash = path ? strrchr(path, '/') : NULL;
    if (!dot || (slash && dot < slash)) return 0;
    return !strcasecmp(dot, ".gltf") || !strcasecmp(dot, ".glb");
}

int scene_load(const char *path, scene *out, char *err, size_t err_size)
{
    if (scene_is_gltf(path)) return gltf_read_file(path, out, err, err_size);
    return scene_parse_file(path, out, err, err_size);
}
