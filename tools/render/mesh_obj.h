/* mesh_obj.h - Wavefront OBJ text through tinyobjloader (mesh_obj.cpp), as a C interface:
 * the library parses the statements and the sink receives them in file order with the
 * number and text of their line, so that the caller (mesh.c) can check each line and name
 * it in messages.
 *
 * PUBLIC FUNCTIONS
 *   mesh_obj_parse   run the parser over text in memory, calling the sink per line
 */
#ifndef ABRDF_MESH_OBJ_H
#define ABRDF_MESH_OBJ_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* One line of the file: its number (1-based) and its text without the line end. */
typedef struct mesh_obj_line {
    int number;
    const char *text;
    size_t len;
} mesh_obj_line;

/* Each callback returns 0 to go on or -1 to stop the parse (the sink keeps its message).
 * Face corners come as the file writes them (1-based, negative = relative, 0 = absent). */
typedef struct mesh_obj_sink {
    void *user;
    int (*vertex)(void *user, const mesh_obj_line *line, double x, double y, double z);
    int (*normal)(void *user, const mesh_obj_line *line, double x, double y, double z);
    int (*texcoord)(void *user, const mesh_obj_line *line, double u, double v);
    int (*face)(void *user, const mesh_obj_line *line, const int *v, const int *vt, const int *vn,
                int corners);
    /* every line the library reads without a statement for the sink: blank lines,
     * comments, o, g, s, usemtl, mtllib, l, p and anything it does not know */
    int (*other)(void *user, const mesh_obj_line *line);
} mesh_obj_sink;

/* Returns 0 when the whole text was read, -1 when a callback stopped it, -2 when the library
 * failed (out of memory; err holds its message). */
int mesh_obj_parse(const char *text, size_t len, const mesh_obj_sink *sink, char *err,
                   size_t err_size);

#ifdef __cplusplus
}
#endif

#endif
