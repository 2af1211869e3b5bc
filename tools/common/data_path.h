/* data_path.h - where the tool finds its data files (data/ in the source tree, or the
 * installed share/abrdf), so `abrdf` works from the build tree and after installation. */
#ifndef ABRDF_DATA_PATH_H
#define ABRDF_DATA_PATH_H
#include <stddef.h>

/* Full path of data file `name` into buf: the first readable of $ABRDF_DATA_DIR/name, the
 * source tree's data/name, the installed share/abrdf/name. Returns 0 if found, -1 if not
 * (buf then holds the source-tree path, for the error message). */
int data_path_find(const char *name, char *buf, size_t size);

#endif
