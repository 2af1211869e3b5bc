/* measured_file.h - a measured table's file, its format chosen by the name's extension: the one
 * table of formats (measured_file.c) that the commands reading and writing measured BRDFs go
 * through, and where a new format is added (an RGL .bsdf reader, a writer).
 *
 *   measured_file_format  the format of a file name, for reading or for writing
 */
#ifndef ABRDF_MEASURED_FILE_H
#define ABRDF_MEASURED_FILE_H

#include <stddef.h>

#include "measured_table.h"
#include "out_file.h"

typedef struct measured_format {
    const char *extension; /* ".binary", compared without regard to case */
    const char *name;      /* "MERL BRDF database", for messages */
    /* a new table from the file, or -1 with "PATH: reason" (NULL: not read) */
    int (*read)(const char *path, measured_table *out, char *err, size_t err_size);
    /* the table into an opened output, closed after (NULL: not written) */
    int (*write_to)(out_file *o, const measured_table *t, char *err, size_t err_size);
} measured_format;

/* The format of path by its extension that can be read (writing 0) or written (writing 1), or
 * NULL with "PATH: reason" in err naming the extensions that can. */
const measured_format *measured_file_format(const char *path, int writing, char *err,
                                            size_t err_size);

#endif
