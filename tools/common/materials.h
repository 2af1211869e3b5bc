/* materials.h - the material table (data/materials.csv, docs/SELECTION.md, "The material
 * table"): loading with
 * "file:line: problem" errors, merging user files over it by name, lookup and suggestions. */
#ifndef ABRDF_MATERIALS_H
#define ABRDF_MATERIALS_H

#include <stddef.h>
#include <stdio.h>
#include "abrdf_select.h"

#define MAT_NAME_MAX 64 /* with the NUL, as the scene format's names (SCENE_NAME_MAX) */
#define MAT_SOURCE_MAX 400
#define MAT_FILE_MAX 256
#define MAT_ERR_MAX 512

typedef struct mat_entry {
    char name[MAT_NAME_MAX];
    char source[MAT_SOURCE_MAX]; /* where the numbers come from (never empty) */
    char file[MAT_FILE_MAX];     /* file and line that defined it (last one wins) */
    int line;
    abrdf_material m; /* m.name points at name */
} mat_entry;

typedef struct mat_table {
    mat_entry *items;
    int count, cap;
} mat_table;

/* The column names, in order (the header line every file starts with). */
extern const char *const mat_columns[];
extern const int mat_column_count;

/* Load `path` (a regular file: in_file.h) into t: new names are appended, known names
 * replaced (a user file overrides the built-in table). Lines may have any length. On failure
 * t is unchanged except for entries of earlier files, and err holds "path:line: problem".
 * Returns 0 or -1. */
int mat_table_load(mat_table *t, const char *path, char *err, size_t err_size);
/* The same from an open stream; `path` is used in messages (tests/fuzz/fuzz_materials.c). */
int mat_table_read(mat_table *t, FILE *fp, const char *path, char *err, size_t err_size);
void mat_table_free(mat_table *t);
const mat_entry *mat_table_find(const mat_table *t, const char *name);
/* Up to max names nearest to `name` by edit distance (<= 3), closest first; returns count. */
int mat_table_nearest(const mat_table *t, const char *name, const char **out, int max);

#endif
