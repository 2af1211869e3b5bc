/* fuzz_mesh.c - fuzz target of the OBJ reader and the Embree scene behind it: any bytes must
 * either be rejected with a message naming the file, or read into a mesh whose indices are
 * in range and whose normals are unit vectors, and which the Embree scene and the
 * brute-force loop (geom.c) then hit alike. libFuzzer entry point; tests/fuzz/fuzz_driver.c
 * runs it deterministically under CTest (also in the sanitizer build). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "accel.h"
#include "fuzz_target.h"

/* A broken property names itself before the abort the driver counts as a failure. */
#define FUZZ_REQUIRE(cond)                                                                         \
    do {                                                                                           \
        if (!(cond)) {                                                                             \
            fprintf(stderr, "fuzz_mesh: %s does not hold (%s)\n", #cond, err);                     \
            abort();                                                                               \
        }                                                                                          \
    } while (0)

/* Inputs read into a mesh and ray traced (the driver reports it). */
static unsigned long traced;

/* Words of the OBJ format and hostile numbers, inserted by the driver's mutations. */
const char *const fuzz_tokens[] = {
    "\n",           "\r\n",  "\r",  " ",    "\t",    "#",     "\0",    "v ",
    "vn ",          "vt ",   "f ",  "o x",  "g a b", "s 1",   "s off", "usemtl m",
    "mtllib m.mtl", "l 1 2", "p 1", "curv", "vp",    "/",     "//",    "1",
    "-1",           "0",     "2",   "-3",   "1/1/1", "1//1",  "1/1",   "7",
    "99999999999",  "1e6",   "1e7", "-1e6", "nan",   "inf",   "0x1",   "1e-320",
    "1.5",          ".",     "-",   "e",    "0 0 0", "1 0 0", "\xff",
};
const size_t fuzz_token_count = sizeof fuzz_tokens / sizeof fuzz_tokens[0];

void fuzz_report(FILE *f) { fprintf(f, "%lu read and ray traced", traced); }

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    mesh m;
    char err[512];
    /* 1 << 16 triangles: inputs up to 64 KiB stay quick under the sanitizers */
    if (mesh_load_text("fuzz.obj", (const char *)data, size, 1 << 16, &m, err, sizeof err) != 0) {
        FUZZ_REQUIRE(memchr(err, '\0', sizeof err) && !strncmp(err, "fuzz.obj:", 9));
        return 0;
    }
    FUZZ_REQUIRE(m.triangle_count >= 1 && m.vertex_count >= 3);
    for (int t = 0; t < 3 * m.triangle_count; ++t) {
        FUZZ_REQUIRE(m.tri[t] >= 0 && m.tri[t] < m.vertex_count);
        FUZZ_REQUIRE(m.tri_normal[t] >= 0 && m.tri_normal[t] < m.normal_count);
        FUZZ_REQUIRE(!m.tri_uv || (m.tri_uv[t] >= 0 && m.tri_uv[t] < m.uv_count));
    }
    for (int i = 0; i < m.normal_count; ++i) {
        const float *n = m.normal + 3 * i;
        FUZZ_REQUIRE(fabs(sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) - 1) < 1e-5);
    }
    /* The mesh twice (smooth and flat, the second moved), rays toward its bounding sphere. */
    scene_object o[2];
    geom_object g[2];
    memset(o, 0, sizeof o);
    for (int k = 0; k < 2; ++k) {
        o[k].shape = SCENE_MESH, o[k].mesh = 0, o[k].mesh_data = &m, o[k].smooth = !k;
        o[k].scale[0] = o[k].scale[1] = o[k].scale[2] = 1;
        o[k].translate[0] = k * m.radius;
        geom_object_make(&o[k], &g[k]);
    }
    accel *a;
    double reach = 4 * (sqrt(geom_dot(g[0].center, g[0].center)) + 2 * g[0].bound + 1);
    FUZZ_REQUIRE(accel_build(g, 2, reach, &a, err, sizeof err) == 0);
    for (int r = 0; r < 16; ++r) {
        double ang = r * 0.7, o3[3], d[3];
        for (int c = 0; c < 3; ++c) o3[c] = g[0].center[c];
        o3[0] += 3 * (g[0].bound + 1) * cos(ang), o3[2] += 3 * (g[0].bound + 1) * sin(ang);
        o3[1] += (r % 5 - 2) * 0.3 * (g[0].bound + 1);
        for (int c = 0; c < 3; ++c) d[c] = g[0].center[c] - o3[c];
        d[1] += (r % 3 - 1) * 0.2 * g[0].bound;
        accel_hit h;
        int hit = accel_intersect(a, o3, d, 0.0, INFINITY, &h, NULL);
        if (hit) {
            FUZZ_REQUIRE(h.t > 0 && isfinite(h.t) && h.object >= 0 && h.object <= 1);
            for (int c = 0; c < 3; ++c) FUZZ_REQUIRE(isfinite(h.n[c]) && isfinite(h.ng[c]));
            FUZZ_REQUIRE(h.triangle >= 0 && h.triangle < m.triangle_count);
        }
        (void)accel_occluded(a, o3, d, 0.0, 1.0, 0, hit ? h.triangle : -1, NULL);
    }
    accel_release(a);
    mesh_free(&m);
    ++traced;
    return 0;
}
