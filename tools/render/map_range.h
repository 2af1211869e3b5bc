/* map_range.h - what the selection reads of a pbr material's textures: a map opened through
 * the texture system (a file, or an image embedded in a glTF file), and the roughness map's
 * values as a pbr_range (pbr_select.h) for scene_selection.map_range.
 *
 * PUBLIC FUNCTIONS
 *   map_open         open a material's map in a texture system (embedded bytes named by type)
 *   map_range_read   a scene_map_range_fn: the roughness map's histogram as roughness values
 */
#ifndef ABRDF_MAP_RANGE_H
#define ABRDF_MAP_RANGE_H

#include <stddef.h>
#include "pbr_select.h"
#include "scene.h"
#include "texture.h"

#define MAP_RANGE_BINS 64 /* histogram bins over [0, 1]; with the extremes: PBR_RANGE_MAX */

/* texture_open for map mp: its file, or its embedded bytes (scene_map.blob) under the name
 * "PATH.EXT", the extension from its mimeType or else its first bytes (PNG, JPEG), which
 * chooses OpenImageIO's reader. 0, or -1 with one line in err. */
int map_open(texture_system *ts, const scene_map *mp, texture_file **out, texture_info *info,
             char *err, size_t err_size);

/* The roughness map of sm (sm->maps[SCENE_MAP_ROUGHNESS], its channel) read whole at its
 * finest level through a texture system of TEXTURE_CACHE_MB_DEFAULT (memory: the cache bound
 * and one row): each non-empty bin of MAP_RANGE_BINS at the roughness factor times its
 * centre, with its share of the texels, and the factor times the least and the largest texel
 * (share 0). user is unused. 0, or -1 with one line in err. */
int map_range_read(void *user, const scene_material *sm, pbr_range *out, char *err,
                   size_t err_size);

#endif
