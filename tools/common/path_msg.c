/* path_msg.c - messages naming a file, the reason kept whole (path_msg.h). */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "path_msg.h"

/* Is byte c the continuation of a UTF-8 sequence (a cut must not fall before it)? */
static int continuation(unsigned char c) { return (c & 0xc0) == 0x80; }

/* path with its control bytes as \xHH (a name may hold a line break; a message may not),
 * malloc'd; NULL when out of memory. */
static char *visible(const char *path)
{
    size_t n = 0;
    for (const char *p = path; *p; ++p) n += (unsigned char)*p < 0x20 || *p == 0x7f ? 4 : 1;
    char *v = malloc(n + 1), *q = v;
    if (!v) return NULL;
    for (const char *p = path; *p; ++p)
        if ((unsigned char)*p < 0x20 || *p == 0x7f)
            q += sprintf(q, "\\x%02x", (unsigned char)*p);
        else
            *q++ = *p;
    *q = '\0';
    return v;
}

const char *path_short(char *dst, size_t size, const char *path, size_t max)
{
    if (!size) return dst;
    if (max >= size) max = size - 1;
    char *shown = visible(path);
    if (shown) path = shown;
    size_t len = strlen(path);
    if (len <= max) {
        memcpy(dst, path, len + 1);
    } else if (max < 5) { /* no room for "x...y": the end of the name is the most telling */
        size_t from = len - max;
        while (from < len && continuation((unsigned char)path[from])) ++from;
        memcpy(dst, path + from, len - from + 1);
    } else {
        size_t keep = max - 3, head = keep / 3, tail = keep - head;
        size_t from = len - tail;
        while (head > 0 && continuation((unsigned char)path[head])) --head;
        while (from < len && continuation((unsigned char)path[from])) ++from;
        memcpy(dst, path, head);
        memcpy(dst + head, "...", 3);
        memcpy(dst + head + 3, path + from, len - from + 1);
    }
    free(shown);
    return dst;
}

void path_msg(char *dst, size_t size, const char *path, const char *fmt, ...)
{
    if (!dst || !size) return;
    va_list ap;
    va_start(ap, fmt);
    char small[512], *rest = small;
    int n = vsnprintf(small, sizeof small, fmt, ap);
    va_end(ap);
    if (n < 0) n = 0, small[0] = '\0';
    if ((size_t)n >= sizeof small && (rest = malloc((size_t)n + 1)) != NULL) {
        va_start(ap, fmt);
        vsnprintf(rest, (size_t)n + 1, fmt, ap);
        va_end(ap);
    } else if (!rest) {
        rest = small; /* out of memory: the rest as far as it fit */
        n = (int)strlen(small);
    }
    /* The name gets what the reason leaves, but at least 16 bytes (then the reason, longer
     * than any this project writes, is what gets cut). */
    size_t room = size - 1, rl = strlen(rest);
    size_t name_room = rl + 16 > room ? (room < 16 ? room : 16) : room - rl;
    char *p = malloc(name_room + 1);
    if (p) {
        path_short(p, name_room + 1, path, name_room);
        snprintf(dst, size, "%s%s", p, rest);
        free(p);
    } else {
        snprintf(dst, size, "%s", rest);
    }
    if (rest != small) free(rest);
}
