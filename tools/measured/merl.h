/* merl.h - MERL BRDF database files (".binary"; Matusik, Pfister, Brand, McMillan, "A
 * Data-Driven Reflectance Model", SIGGRAPH 2003) read into and written from a measured table
 * (measured_table.h). docs/MEASURED.md, "Files".
 *
 * THE FORMAT: three little-endian int32, the grid n_theta_h, n_theta_d, n_phi_d (MERL's
 * files: 90, 90, 180); then three channels, red, green, blue, each n = the grid's product of
 * little-endian doubles in the table's cell order ((ih * n_theta_d + id) * n_phi_d + ip).
 * A stored value times its channel's scale is f_r in 1/sr (MERL_SCALE_*); a negative stored
 * value means "not measured" (-1 in the table). The file is exactly 12 + 24 * cells bytes.
 *
 *   merl_read         a file into a new table, or a one-line reason
 *   merl_read_stream  the same from an open stream of a known size (the fuzz target's way in)
 *   merl_write        a table to a file, whole or not at all
 *   merl_write_to     a table into an opened output (a command that opens its output first)
 */
#ifndef ABRDF_MERL_H
#define ABRDF_MERL_H

#include <stddef.h>
#include <stdio.h>

#include "measured_table.h"
#include "out_file.h"

/* The database's per-channel scales (stored value * scale = f_r), as MERL's reference reader
 * (BRDFRead.cpp) applies them. */
#define MERL_SCALE_R (1.0 / 1500.0)
#define MERL_SCALE_G (1.15 / 1500.0)
#define MERL_SCALE_B (1.66 / 1500.0)
/* The largest f_r (1/sr) a file may hold: a bound chosen here, not the database's, far above
 * a glossy highlight sampled on the grid; a value above it is taken for a corrupt file. */
#define MERL_MAX_FR 1e6
#define MERL_HEADER_BYTES 12

/* 0 and a new table in *out (free it with measured_table_free), or -1 with "PATH: reason" in
 * err and *out empty. Refused before any large allocation: not a regular file, shorter than
 * the header, a dimension outside [MEASURED_DIM_MIN, MEASURED_DIM_MAX] or more than
 * MEASURED_MAX_CELLS cells, a size other than 12 + 24 * cells; then, while reading, a NaN or
 * an infinity, or an f_r above MERL_MAX_FR (each named by channel and cell). Memory: the
 * table and a fixed buffer. */
int merl_read(const char *path, measured_table *out, char *err, size_t err_size);
/* merl_read of the size bytes of f from its current position; name is the PATH of messages. */
int merl_read_stream(FILE *f, unsigned long long size, const char *name, measured_table *out,
                     char *err, size_t err_size);
/* 0 after writing t to path whole (out_file.h), or -1 with "PATH: reason" in err and nothing
 * written: a table that is not a valid grid, or holds a NaN, an infinity or an f_r above
 * MERL_MAX_FR (checked before the file is created), or a failed write. Cells not measured
 * (any negative value) are written as -1. */
int merl_write(const char *path, const measured_table *t, char *err, size_t err_size);
/* The same through o, opened by the caller; it closes o but leaves committing (or
 * discarding, after a failure) to the caller. */
int merl_write_to(out_file *o, const measured_table *t, char *err, size_t err_size);

#endif
