/* fuzz_gltf.c - fuzz target of the glTF reader (tools/gltf/gltf.h): any bytes, as .gltf text or
 * .glb, must either be refused with one line naming the file, or read into a scene whose
 * meshes have their indices in range, unit normals and finite positions, with at least one
 * object, a camera and a light. libFuzzer entry point; tests/fuzz/fuzz_driver.c runs it
 * deterministically under CTest (also in the sanitizer build), in corpus/gltf so that the
 * seeds' .bin and image files are there. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_target.h"
#include "gltf.h"

#define FUZZ_REQUIRE(cond)                                                                         \
    do {                                                                                           \
        if (!(cond)) {                                                                             \
            fprintf(stderr, "fuzz_gltf: %s does not hold (%s)\n", #cond, err);                     \
            abort();                                                                               \
        }                                                                                          \
    } while (0)

static unsigned long read_ok, refused;

/* JSON of glTF and hostile numbers, inserted by the driver's mutations. */
const char *const fuzz_tokens[] = {
    "{",
    "}",
    "[",
    "]",
    ",",
    ":",
    "\"",
    "\0",
    "glTF",
    "JSON",
    "BIN",
    "\"nodes\"",
    "\"meshes\"",
    "\"mesh\"",
    "\"indices\"",
    "\"mode\"",
    "\"children\"",
    "\"matrix\"",
    "\"count\"",
    "\"byteOffset\"",
    "\"byteStride\"",
    "\"byteLength\"",
    "\"bufferView\"",
    "\"componentType\"",
    "\"type\"",
    "\"VEC3\"",
    "\"SCALAR\"",
    "\"camera\"",
    "\"yfov\"",
    "\"material\"",
    "\"texCoord\"",
    "\"source\"",
    "\"uri\"",
    "\"light\"",
    "5126",
    "5125",
    "5123",
    "5121",
    "-1",
    "0",
    "1",
    "2",
    "3",
    "4",
    "5",
    "6",
    "7",
    "4294967295",
    "1e308",
    "-1e308",
    "1e-320",
    "0.5",
    "null",
    "true",
    "\"data:application/octet-stream;base64,AAAA\"",
    "\"strip.bin\"",
};
const size_t fuzz_token_count = sizeof fuzz_tokens / sizeof fuzz_tokens[0];

void fuzz_report(FILE *f) { fprintf(f, "%lu read, %lu refused", read_ok, refused); }

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    scene s;
    char err[512] = "";
    if (gltf_read_memory("fuzz.gltf", data, size, &s, err, sizeof err) != 0) {
        FUZZ_REQUIRE(memchr(err, '\0', sizeof err) && !strncmp(err, "fuzz.gltf: ", 11));
        FUZZ_REQUIRE(!strchr(err, '\n'));
        FUZZ_REQUIRE(s.object_count == 0 && s.meshes == NULL);
        ++refused;
        return 0;
    }
    FUZZ_REQUIRE(s.object_count >= 1 && s.light_count >= 1);
    FUZZ_REQUIRE(s.camera.fov_deg > 0 && s.camera.fov_deg < 180);
    FUZZ_REQUIRE(s.camera.width >= 1 && s.camera.width <= SCENE_MAX_RESOLUTION);
    for (int o = 0; o < s.object_count; ++o) {
        const scene_object *ob = &s.objects[o];
        FUZZ_REQUIRE(ob->material >= 0 && ob->material < s.material_count);
        FUZZ_REQUIRE(ob->mesh >= 0 && ob->mesh < s.mesh_count);
        const mesh *m = s.meshes[ob->mesh];
        FUZZ_REQUIRE(m->in_memory && m->triangle_count >= 1);
        for (int t = 0; t < 3 * m->triangle_count; ++t) {
            FUZZ_REQUIRE(m->tri[t] >= 0 && m->tri[t] < m->vertex_count);
            FUZZ_REQUIRE(m->tri_normal[t] >= 0 && m->tri_normal[t] < m->normal_count);
            FUZZ_REQUIRE(!m->tri_uv || (m->tri_uv[t] >= 0 && m->tri_uv[t] < m->uv_count));
        }
        for (int i = 0; i < 3 * m->vertex_count; ++i)
            FUZZ_REQUIRE(fabs(m->position[i]) <= SCENE_MAX_COORD);
        for (int i = 0; i < m->normal_count; ++i) {
            const float *n = m->normal + 3 * i;
            FUZZ_REQUIRE(fabs(sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) - 1) < 1e-5);
        }
    }
    for (int i = 0; i < s.material_count; ++i)
        for (int k = 0; k < SCENE_MAP_COUNT; ++k) {
            const scene_map *mp = &s.materials[i].maps[k];
            FUZZ_REQUIRE(!mp->blob || (mp->path && mp->blob_size > 0));
        }
    ++read_ok;
    scene_free(&s);
    return 0;
}
