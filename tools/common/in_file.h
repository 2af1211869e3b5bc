/* in_file.h - the files the tools read (scenes, material tables, cost files, the paper's
 * data): regular files only, checked before anything waits on them (a FIFO or a directory is
 * refused at once, never blocks), and lines of any length.
 *
 *   in_file_open    open a regular file for reading, or say why not
 *   in_file_check   the same check without keeping the file open (for readers that open it
 *                   themselves, as OpenImageIO does)
 *   in_file_line    the next whole line, however long
 */
#ifndef ABRDF_IN_FILE_H
#define ABRDF_IN_FILE_H

#include <stddef.h>
#include <stdio.h>
#include <sys/types.h>

/* The open file, or NULL with "PATH: reason" in err ("cannot open: No such file or
 * directory", "is a directory, not a file", "is a FIFO, not a regular file", ...). */
FILE *in_file_open(const char *path, char *err, size_t err_size);
/* 0 if path is a regular file that can be opened for reading, else -1 with "PATH: reason". */
int in_file_check(const char *path, char *err, size_t err_size);
/* Read the next line into *buf (grown with realloc; free it when done), without its "\n" or
 * "\r\n". Returns its length (it may hold NUL bytes: compare with strlen), or -1 at the end
 * of the file, on a read error (ferror) or when out of memory (errno ENOMEM). */
ssize_t in_file_line(FILE *f, char **buf, size_t *cap);

#endif
