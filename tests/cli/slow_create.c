/* slow_create.c - a preload module for tests/cli/test_cli_outputs.py: open(2) of a new file
 * whose name starts with $SLOW_CREATE_PREFIX and ends with $SLOW_CREATE_SUFFIX returns only
 * after $SLOW_CREATE_SECONDS, so that a test can send a signal in the window between a
 * temporary output's creation and whatever follows it, every time rather than by chance. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <time.h>

static int slowed(const char *path, int flags)
{
    const char *pre = getenv("SLOW_CREATE_PREFIX"), *suf = getenv("SLOW_CREATE_SUFFIX");
    if (!(flags & O_CREAT) || !pre || !suf) return 0;
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    size_t n = strlen(base), ns = strlen(suf);
    return !strncmp(base, pre, strlen(pre)) && n >= ns && !strcmp(base + n - ns, suf);
}

static int wrapped(const char *name, const char *path, int flags, mode_t mode)
{
    int (*real)(const char *, int, ...) = (int (*)(const char *, int, ...))dlsym(RTLD_NEXT, name);
    int fd = real(path, flags, mode);
    if (fd >= 0 && slowed(path, flags)) {
        const char *s = getenv("SLOW_CREATE_SECONDS");
        double secs = s ? atof(s) : 1.0;
        struct timespec t = {(time_t)secs, (long)((secs - (double)(time_t)secs) * 1e9)};
        nanosleep(&t, NULL);
    }
    return fd;
}

#define WRAP(name)                                                                                 \
    int name(const char *path, int flags, ...)                                                     \
    {                                                                                              \
        mode_t mode = 0;                                                                           \
        if (flags & O_CREAT) {                                                                     \
            va_list a;                                                                             \
            va_start(a, flags);                                                                    \
            mode = (mode_t)va_arg(a, int);                                                         \
            va_end(a);                                                                             \
        }                                                                                          \
        return wrapped(#name, path, flags, mode);                                                  \
    }
WRAP(open)
WRAP(open64)
