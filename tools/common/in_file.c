/* in_file.c - regular input files and whole lines (in_file.h). */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <fcntl.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "in_file.h"
#include "path_msg.h"

static const char *kind(mode_t m)
{
    return S_ISDIR(m)    ? "is a directory, not a file"
           : S_ISFIFO(m) ? "is a FIFO, not a regular file"
           : S_ISCHR(m)  ? "is a character device, not a regular file"
           : S_ISBLK(m)  ? "is a block device, not a regular file"
           : S_ISSOCK(m) ? "is a socket, not a regular file"
                         : "is not a regular file";
}

/* O_NONBLOCK: opening a FIFO must not wait for a writer; fstat then refuses it. */
static int open_regular(const char *path, char *err, size_t err_size)
{
    int fd;
    do fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    while (fd < 0 && errno == EINTR);
    if (fd < 0) {
        int e = errno;
        struct stat st; /* a socket cannot be opened at all (ENXIO): name what it is */
        if (stat(path, &st) == 0 && !S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode))
            path_msg(err, err_size, path, ": %s", kind(st.st_mode));
        else
            path_msg(err, err_size, path, ": cannot open: %s", strerror(e));
        return -1;
    }
    struct stat st;
    if (fstat(fd, &st) != 0) {
        path_msg(err, err_size, path, ": cannot open: %s", strerror(errno));
        close(fd);
        return -1;
    }
    if (!S_ISREG(st.st_mode)) {
        path_msg(err, err_size, path, ": %s", kind(st.st_mode));
        close(fd);
        return -1;
    }
    int flags = fcntl(fd, F_GETFL);
    if (flags >= 0) fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
    return fd;
}

FILE *in_file_open(const char *path, char *err, size_t err_size)
{
    int fd = open_regular(path, err, err_size);
    if (fd < 0) return NULL;
    FILE *f = fdopen(fd, "r");
    if (!f) {
        path_msg(err, err_size, path, ": cannot open: %s", strerror(errno));
        close(fd);
    }
    return f;
}

int in_file_check(const char *path, char *err, size_t err_size)
{
    int fd = open_regular(path, err, err_size);
    if (fd < 0) return -1;
    close(fd);
    return 0;
}

ssize_t in_file_line(FILE *f, char **buf, size_t *cap)
{
    ssize_t n = getline(buf, cap, f);
    if (n < 0) return -1;
    if (n > 0 && (*buf)[n - 1] == '\n') (*buf)[--n] = '\0';
    if (n > 0 && (*buf)[n - 1] == '\r') (*buf)[--n] = '\0';
    return n;
}
