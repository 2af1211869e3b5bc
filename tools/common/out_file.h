/* out_file.h - every file the tools write is written whole or not at all.
 *
 * An output goes to a temporary file beside its target (same directory, so the same file
 * system; the name keeps the target's extension, ".NAME.XXXXXX.EXT"), through a stream whose
 * every write is checked at the system call; closing flushes, syncs and closes it, checking
 * each step; committing renames it over the target. A command with several outputs opens
 * them all before its long work (so a missing directory or a read-only one fails first),
 * writes them all, and commits them only when every one is complete. On any failure the
 * temporary files are removed and existing targets are left as they were; the message names
 * the target and the reason (strerror). Concurrent writers to one target each rename a whole
 * file over it, so the last one wins whole; outputs committed together (an image and its
 * preview) are renamed under a lock on their directories, so that the last command wins all
 * of them, never some. SIGINT, SIGTERM and SIGHUP remove the temporary
 * files of a process before it dies; SIGXFSZ is ignored once an output is open, so that a
 * file-size limit fails a write (EFBIG) instead of killing the process.
 *
 * A target that is a symbolic link is written where the link points (the link stays); a
 * character device or a FIFO (/dev/null, /dev/stdout, a pipe) is written in place, still with
 * every write checked; a directory or any other kind of file is refused.
 *
 *   out_file_open      create the temporary file and its checked stream
 *   out_file_close     flush, sync and close it: the output is complete (not yet visible)
 *   out_file_commit    rename complete outputs over their targets, all of them or none
 *   out_file_discard   remove the temporary file (any state); the target is untouched
 *   out_file_write     write bytes through the stream
 *   out_files_distinct refuse an output that is an input of the command or another output
 *   out_stdout_check   flush standard output and report a failed write to it
 *   out_file_or_stdout / out_file_finish   a program's single output: a file or stdout
 */
#ifndef ABRDF_OUT_FILE_H
#define ABRDF_OUT_FILE_H

#include <stddef.h>
#include <stdio.h>

typedef struct out_file {
    char *target;  /* the name as given, for messages */
    char *path;    /* the file that receives the output: target, or where a link points */
    char *temp;    /* the temporary file beside path; NULL when written in place */
    FILE *f;       /* the checked stream; NULL after out_file_close */
    int fd;        /* the file under the stream; -1 when closed */
    int error;     /* errno of the first failed write (0: none) */
    int closed;    /* out_file_close succeeded */
    int committed; /* renamed over the target (or written in place) */
} out_file;

/* An out_file that holds nothing (out_file_discard of it is harmless). */
#define OUT_FILE_INIT                                                                              \
    {                                                                                              \
        NULL, NULL, NULL, NULL, -1, 0, 0, 0                                                        \
    }

/* Create the temporary file for `target` and open o->f on it; o must keep its address until
 * out_file_close (the stream refers to it). Returns 0, or -1 with "TARGET: reason" in err
 * (o is then empty: out_file_discard is harmless). */
int out_file_open(out_file *o, const char *target, char *err, size_t err_size);
/* Write len bytes; a failure is remembered and reported by out_file_close. */
void out_file_write(out_file *o, const void *data, size_t len);
/* Flush, fsync and close the stream; 0, or -1 with "TARGET: reason" (the first failed write's,
 * else the flush's, sync's or close's). The file stays temporary until out_file_commit. */
int out_file_close(out_file *o, char *err, size_t err_size);
/* Rename the n closed outputs over their targets, in order (and sync their directories).
 * Returns 0, or -1 with "TARGET: reason": an output not closed or a failed rename; then no
 * later output is committed and every temporary file is removed. */
int out_file_commit(out_file *const *files, int n, char *err, size_t err_size);
/* Remove the temporary file if it is still there and free o; the target is untouched. */
void out_file_discard(out_file *o);

/* Refuse outputs that would overwrite an input, or each other: an output is compared with
 * every input and every other output by device and inode (so "./x", symbolic and hard links
 * are caught; an output that does not exist yet by its directory's device and inode and its
 * name). roles name the files in the message ("output", "preview", "scene", "--materials file").
 * NULL entries are skipped. Returns 0, or -1 with one line in err. */
int out_files_distinct(const char *const *outputs, const char *const *output_roles, int nout,
                       const char *const *inputs, const char *const *input_roles, int nin,
                       char *err, size_t err_size);

/* A program with one output, a file (path) or standard output (path NULL): the stream to
 * write to, or NULL after printing "PROGRAM: reason" to stderr. */
FILE *out_file_or_stdout(out_file *o, const char *path, const char *program);
/* Then: close and commit the file (or check standard output). 0, or 1 after printing
 * "PROGRAM: reason"; the temporary file is gone either way. */
int out_file_finish(out_file *o, const char *program);

/* Flush standard output; if a write to it failed (a full disk, a closed pipe, /dev/full),
 * print "PROGRAM: standard output: reason" to stderr and return 1, else 0. */
int out_stdout_check(const char *program);

#endif
