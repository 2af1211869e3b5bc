/* gltf.h - glTF 2.0 files (.gltf with its .bin and images, or data: URIs; .glb) read into
 * the parsed scene every command uses (scene.h), and a scene written as glTF. The files are
 * parsed by tinygltf (Debian libtinygltf-dev, gltf_read.cpp, gltf_write.cpp); every index,
 * range, count, type and stride they hold is checked here before a byte is read.
 * docs/GLTF.md, "Reading glTF" and "Writing glTF", says what is read and what is not.
 *
 * What a read scene holds:
 *   - one mesh object per node and triangle primitive (strips and fans made triangles), its
 *     positions and normals in world space (the node hierarchy baked in: every object has
 *     the identity transform); normals computed as mesh.h says where the file has none;
 *     the mesh's uv the TEXCOORD_n its material's maps read. Mesh paths are names for
 *     messages, "FILE#node/N/mesh/M/primitive/P" (mesh.in_memory = 1).
 *   - `pbr` materials (scene_material.pbr = 1) from pbrMetallicRoughness and the extensions
 *     KHR_materials_ior, _specular, _clearcoat, _sheen, _anisotropy, _transmission, their
 *     lobes as the scene format's (scene_pbr_finish); textures as scene_map, embedded images
 *     as scene_map.blob; glTF's default material where a primitive names none.
 *   - the camera of the first node (depth first) with a perspective camera, else one framing
 *     the bounding sphere; KHR_lights_punctual lights (spot lights as point lights), else one
 *     directional light.
 *   - scene.notes: every default taken and every feature left out, one line each
 *     (`abrdf render --explain` prints them).
 *
 * PUBLIC FUNCTIONS
 *   gltf_read_file     read a .gltf or .glb file into a scene
 *   gltf_read_memory   the same for bytes in memory (name: messages and the base directory)
 *   gltf_write_memory  a scene as .gltf text (its buffer a data: URI) or .glb bytes
 */
#ifndef ABRDF_GLTF_H
#define ABRDF_GLTF_H

#include <stddef.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

#include "scene.h" /* a C header without its own extern "C" */

#define GLTF_MAX_FILE ((size_t)1 << 30) /* bytes of the .gltf/.glb and of each file it names */
#define GLTF_MAX_FILES_TOTAL                                                                       \
    ((size_t)1 << 31)           /* bytes of all the files it names together (a
                                                  buffer named twice counts twice) */
#define GLTF_MAX_JSON_DEPTH 256 /* nesting of the JSON's arrays and objects */

/* Read; 0, or -1 with "FILE: problem" (one line) in err, *out left empty. The format is told
 * by the bytes (a .glb starts with "glTF"), not by the name. */
int gltf_read_file(const char *path, scene *out, char *err, size_t err_size);
int gltf_read_memory(const char *name, const unsigned char *bytes, size_t size, scene *out,
                     char *err, size_t err_size);

/* The scene as glTF for the file out_path - a .glb if it ends in .glb, else .gltf text with its
 * buffer as a data: URI - in a malloc'd *bytes of *size bytes, for the caller's
 * whole-or-nothing output (out_file.h). Maps become textures: an image file by a URI
 * relative to out_path's directory, a blob inside the buffer; what glTF cannot say (e.g.
 * metallic and roughness from two files) is left out with a line on warn (if not NULL).
 * Every material must be explicit (SCENE_MAT_MODELS: the selection applied) and not
 * measured; area and environment lights are refused. 0, or -1 with one line in err.
 * docs/GLTF.md, "Writing glTF". */
int gltf_write_memory(const scene *s, const char *out_path, FILE *warn, unsigned char **bytes,
                      size_t *size, char *err, size_t err_size);

#ifdef __cplusplus
}
#endif

#endif
