/* path_msg.h - one-line messages that name a file. When a message does not fit its buffer,
 * the file name is shortened in its middle ("..."), never the reason: "a/very/lo...ng/x.exr:
 * No space left on device". Control bytes of a name (a line break) are shown as \xHH, so the
 * message stays one line.
 *
 *   path_msg     "PATH" followed by a formatted rest, into a buffer
 *   path_short   a path shortened to at most a given length
 */
#ifndef ABRDF_PATH_MSG_H
#define ABRDF_PATH_MSG_H

#include <stddef.h>

/* dst = path + the formatted rest (e.g. path_msg(err, size, path, ":%d: %s", line, why)). */
void path_msg(char *dst, size_t size, const char *path, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

/* path (control bytes as \xHH) if it has at most max bytes, else its start, "...", and its
 * end, max bytes in all, cut between UTF-8 characters; written to dst (size > max).
 * Returns dst. */
const char *path_short(char *dst, size_t size, const char *path, size_t max);

#endif
