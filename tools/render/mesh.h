/* mesh.h - triangle meshes of the scene format (`mesh file=...`, docs/RENDERER.md, "Triangle
 * meshes"): a Wavefront OBJ file read by tinyobjloader (mesh_obj.h), every line checked,
 * polygons split into triangles, and the vertex normals smooth shading interpolates. Object
 * space; float, as the file's precision and the hosts' (POV-Ray and Cycles store meshes in
 * float).
 *
 * Normals: the file's `vn` (normalised) where it gives them, per face corner. Otherwise the
 * normal of a vertex is the sum of the unit normals of the triangles around it weighted by
 * the triangle's angle at that vertex, normalised (Thuermer and Wuethrich 1998), the rule
 * Blender applies to a mesh without custom normals.
 *
 * PUBLIC FUNCTIONS
 *   mesh_load_file   read and check an OBJ file
 *   mesh_load_text   the same for text in memory (name is used in messages)
 *   mesh_free        release a mesh
 *   mesh_compute_normals, mesh_bounding_sphere   for meshes built in memory (glTF, gltf.h)
 */
#ifndef ABRDF_MESH_H
#define ABRDF_MESH_H

#include <stddef.h>

#define MESH_MAX_TRIANGLES (1 << 24) /* triangles per file, and per scene (scene.h) */
#define MESH_MAX_ELEMENTS (1 << 26)  /* v, vt or vn statements per file */
#define MESH_MAX_FILE ((size_t)1 << 30)
#define MESH_MAX_COORD 1e6 /* |coordinate|, as the scene format's (SCENE_MAX_COORD) */

typedef struct mesh {
    char *path;         /* the file as the scene names it, resolved (messages, exporters) */
    int vertex_count;   /* positions */
    int normal_count;   /* unit normals */
    int uv_count;       /* texture coordinates (0: the file has none) */
    int triangle_count; /* 1 .. MESH_MAX_TRIANGLES */
    float *position;    /* 3 per vertex */
    float *normal;      /* 3 per normal, unit length */
    float *uv;          /* 2 per texture coordinate, or NULL */
    int *tri; /* 3 position indices per triangle (4 spare ints follow: Embree reads 16 bytes) */
    int *tri_normal;       /* 3 normal indices per triangle */
    int *tri_uv;           /* 3 texture-coordinate indices per triangle, or NULL */
    int normals_from_file; /* 1: the file's vn; 0: computed (angle-weighted, above) */
    double center[3];      /* centre of the positions' bounding box */
    double radius;         /* largest distance of a position from center */
    int polygons_split;    /* faces of more than 3 corners, split as fans (0, k, k+1) */
    int in_memory;         /* 1: built from another file's data (a glTF primitive, gltf.h); path is
                              then "FILE#node/N/mesh/M/primitive/P", a name for messages, no file */
    int uv_origin_top;     /* 1: v = 0 is the image's top row (glTF's texture coordinates, kept as
                              the file has them); 0: its bottom row (OBJ's) */
} mesh;

/* Read; on failure frees everything, writes the message to err and returns -1 for a problem
 * in the text ("NAME:LINE: problem", line 0 for whole-file problems such as no faces) or,
 * from mesh_load_file, -2 when the file cannot be read at all ("PATH: problem").
 * max_triangles (<= MESH_MAX_TRIANGLES) is the most the caller accepts. */
int mesh_load_text(const char *name, const char *text, size_t len, int max_triangles, mesh *out,
                   char *err, size_t err_size);
int mesh_load_file(const char *path, int max_triangles, mesh *out, char *err, size_t err_size);
void mesh_free(mesh *m);
/* The angle-weighted vertex normals above, replacing normal and tri_normal (position and tri
 * set): 0, or -1 out of memory. */
int mesh_compute_normals(mesh *m);
/* center and radius from the positions. */
void mesh_bounding_sphere(mesh *m);

#endif
