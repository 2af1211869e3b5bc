/* out_file.c - outputs written whole or not at all (out_file.h). */
#define _GNU_SOURCE /* fopencookie */
#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <time.h>
#include <unistd.h>

#include "out_file.h"
#include "path_msg.h"

/* ---- temporary files removed on SIGINT, SIGTERM, SIGHUP --------------------------------- */

#define LIVE_MAX 32
static char *volatile live[LIVE_MAX]; /* temporary files of this process, not yet renamed */

/* Who holds live[]: 0 nobody, 1 a thread of this process changing it (live_lock), 2 the signal
 * handler, which removes the files listed and ends the process. The process has threads it did
 * not start (OpenImageIO's and Embree's pools) on which a signal may be handled, so a signal
 * arriving while a temporary file is created and listed, or unlisted and freed, is held off by
 * the lock rather than by a thread's signal mask alone: the handler takes the list only when
 * no change is under way, and no change starts once it has. */
static int live_owner;
static const int live_signals[] = {SIGINT, SIGTERM, SIGHUP};

static void live_pause(void)
{
    struct timespec ms = {0, 1000000};
    nanosleep(&ms, NULL); /* async-signal-safe */
}

static void on_signal(int sig)
{
    int free_ = 0;
    while (!__atomic_compare_exchange_n(&live_owner, &free_, 2, 0, __ATOMIC_SEQ_CST,
                                        __ATOMIC_SEQ_CST)) {
        free_ = 0; /* a change under way ends in microseconds; another handler ends us */
        live_pause();
    }
    for (int i = 0; i < LIVE_MAX; ++i)
        if (live[i]) unlink(live[i]); /* async-signal-safe */
    signal(sig, SIG_DFL);
    raise(sig);
}

static void live_install(void)
{
    static int installed;
    if (installed) return;
    installed = 1;
    for (int i = 0; i < 3; ++i) {
        struct sigaction sa, old;
        memset(&sa, 0, sizeof sa);
        sa.sa_handler = on_signal;
        sigemptyset(&sa.sa_mask); /* the three held while one is handled: none waits on it */
        for (int k = 0; k < 3; ++k) sigaddset(&sa.sa_mask, live_signals[k]);
        /* A signal the caller ignores (nohup) stays ignored. */
        if (sigaction(live_signals[i], NULL, &old) == 0 && old.sa_handler == SIG_DFL)
            sigaction(live_signals[i], &sa, NULL);
    }
    signal(SIGXFSZ, SIG_IGN); /* write(2) then fails with EFBIG, which is reported */
}

/* Takes live[] for a change: the three signals blocked in this thread first (their previous
 * mask into *saved), so that a handler running on it cannot wait for its own change. If the
 * handler holds the list, the process is ending: wait for it. */
static void live_lock(sigset_t *saved)
{
    sigset_t block;
    sigemptyset(&block);
    for (int i = 0; i < 3; ++i) sigaddset(&block, live_signals[i]);
    pthread_sigmask(SIG_BLOCK, &block, saved);
    int free_ = 0;
    while (!__atomic_compare_exchange_n(&live_owner, &free_, 1, 0, __ATOMIC_SEQ_CST,
                                        __ATOMIC_SEQ_CST)) {
        free_ = 0;
        live_pause();
    }
}

/* Gives live[] back; a signal held by this thread meanwhile is handled now, with the list as
 * the change left it. */
static void live_unlock(const sigset_t *saved)
{
    __atomic_store_n(&live_owner, 0, __ATOMIC_SEQ_CST);
    pthread_sigmask(SIG_SETMASK, saved, NULL);
}

static void live_add(char *path)
{
    for (int i = 0; i < LIVE_MAX; ++i)
        if (!live[i]) {
            live[i] = path;
            return;
        }
}

/* path out of live[], under the lock: the caller may free it then. */
static void live_remove(const char *path)
{
    sigset_t saved;
    live_lock(&saved);
    for (int i = 0; i < LIVE_MAX; ++i)
        if (live[i] == path) live[i] = NULL;
    live_unlock(&saved);
}

/* ---- the checked stream ------------------------------------------------------------------ */

/* Every buffer the stream flushes reaches write(2) here; the first failure is kept. */
static ssize_t checked_write(void *cookie, const char *buf, size_t size)
{
    out_file *o = cookie;
    size_t done = 0;
    while (done < size) {
        ssize_t w = write(o->fd, buf + done, size - done);
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0) {
            if (!o->error) o->error = w < 0 ? errno : EIO;
            return -1;
        }
        done += (size_t)w;
    }
    return (ssize_t)size;
}

static int fail(out_file *o, char *err, size_t err_size, const char *what, int code)
{
    path_msg(err, err_size, o->target ? o->target : "", ": %s%s%s", what, *what ? ": " : "",
             strerror(code));
    return -1;
}

/* ---- names ------------------------------------------------------------------------------- */

static char *dup_str(const char *s)
{
    size_t n = strlen(s) + 1;
    char *d = malloc(n);
    if (d) memcpy(d, s, n);
    return d;
}

/* A new name beside path: DIR/.STEM.XXXXXX.EXT (OpenImageIO picks a format by its extension),
 * the stem shortened so that the name stays within NAME_MAX. */
static char *temp_name(const char *path, unsigned long long salt)
{
    const char *slash = strrchr(path, '/');
    const char *base = slash ? slash + 1 : path;
    size_t dir_len = (size_t)(base - path);
    const char *dot = strrchr(base, '.');
    if (!dot || dot == base || strlen(dot) > 16) dot = base + strlen(base);
    size_t stem = (size_t)(dot - base), ext = strlen(dot);
    const size_t name_max = 255, fixed = 1 + 1 + 6; /* '.', '.', XXXXXX */
    if (stem + ext + fixed > name_max) stem = name_max - ext - fixed;
    while (stem > 0 && ((unsigned char)base[stem] & 0xc0) == 0x80) --stem; /* whole UTF-8 */
    char *t = malloc(dir_len + fixed + stem + ext + 1);
    if (!t) return NULL;
    static const char alphabet[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
    char rnd[7];
    for (int i = 0; i < 6; ++i) {
        salt ^= salt >> 33;
        salt *= 0xff51afd7ed558ccdull;
        salt ^= salt >> 33;
        rnd[i] = alphabet[salt % 62];
    }
    rnd[6] = '\0';
    memcpy(t, path, dir_len);
    sprintf(t + dir_len, ".%.*s.%s%s", (int)stem, base, rnd, dot);
    return t;
}

/* ---- the life of an output ---------------------------------------------------------------- */

static void empty(out_file *o)
{
    memset(o, 0, sizeof *o);
    o->fd = -1;
}

static void remove_temp(out_file *o)
{
    if (!o->temp) return;
    unlink(o->temp);
    live_remove(o->temp);
    free(o->temp);
    o->temp = NULL;
}

void out_file_discard(out_file *o)
{
    if (!o) return;
    if (o->f) fclose(o->f);
    if (o->fd >= 0) close(o->fd);
    remove_temp(o);
    free(o->target);
    free(o->path);
    empty(o);
}

int out_file_open(out_file *o, const char *target, char *err, size_t err_size)
{
    empty(o);
    if (!target || !*target) {
        snprintf(err, err_size, "empty output file name");
        return -1;
    }
    if (!(o->target = dup_str(target))) return fail(o, err, err_size, "", ENOMEM), -1;
    struct stat st;
    int exists = 0;
    /* A link is followed to the file it names; a dangling one is replaced. */
    char *real = NULL;
    if (lstat(target, &st) == 0 && S_ISLNK(st.st_mode)) real = realpath(target, NULL);
    o->path = real ? real : dup_str(target);
    if (!o->path) goto nomem;
    if (stat(o->path, &st) == 0) {
        exists = 1;
        if (S_ISDIR(st.st_mode)) {
            path_msg(err, err_size, target, ": is a directory, not a file");
            goto bad;
        }
        if (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode)) { /* written in place */
            do o->fd = open(o->path, O_WRONLY | O_CLOEXEC);
            while (o->fd < 0 && errno == EINTR);
            if (o->fd < 0) {
                fail(o, err, err_size, "cannot open", errno);
                goto bad;
            }
            goto stream;
        }
        if (!S_ISREG(st.st_mode)) {
            path_msg(err, err_size, target,
                     ": is not a regular file, a character device or a FIFO");
            goto bad;
        }
    }
    struct timespec now;
    clock_gettime(CLOCK_REALTIME, &now);
    unsigned long long salt = (unsigned long long)now.tv_nsec ^
                              ((unsigned long long)now.tv_sec << 20) ^
                              ((unsigned long long)getpid() << 40) ^ (uintptr_t)o;
    live_install();
    sigset_t saved;
    live_lock(&saved); /* from before the file exists until it is listed */
    for (int attempt = 0; attempt < 100 && o->fd < 0; ++attempt) {
        free(o->temp);
        o->temp = temp_name(o->path, salt + 0x9e3779b97f4a7c15ull * (unsigned)attempt);
        if (!o->temp) {
            errno = ENOMEM;
            break;
        }
        o->fd = open(o->temp, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (o->fd < 0 && errno != EEXIST) break;
    }
    if (o->fd >= 0) live_add(o->temp);
    int code = errno;
    live_unlock(&saved);
    if (!o->temp) goto nomem;
    if (o->fd < 0) {
        free(o->temp);
        o->temp = NULL;
        fail(o, err, err_size, "cannot create a file beside it", code);
        goto bad;
    }
    if (exists) fchmod(o->fd, st.st_mode & 07777); /* the replaced file's permissions */
stream:;
    cookie_io_functions_t io = {NULL, checked_write, NULL, NULL};
    if (!(o->f = fopencookie(o, "w", io))) goto nomem;
    setvbuf(o->f, NULL, _IOFBF, 1 << 16);
    return 0;
nomem:
    fail(o, err, err_size, "", ENOMEM);
bad:
    out_file_discard(o);
    return -1;
}

void out_file_write(out_file *o, const void *data, size_t len)
{
    if (o->f && len) fwrite(data, 1, len, o->f);
}

int out_file_close(out_file *o, char *err, size_t err_size)
{
    if (!o->f) return fail(o, err, err_size, "", EBADF);
    int flushed = fflush(o->f) == 0 && !ferror(o->f);
    fclose(o->f); /* the cookie has no close: the descriptor stays open */
    o->f = NULL;
    if (o->error || !flushed)
        return fail(o, err, err_size, "write failed", o->error ? o->error : EIO);
    /* In place, a device or a pipe may not sync (EINVAL); a file must. */
    if (fsync(o->fd) != 0 && (o->temp || (errno != EINVAL && errno != EROFS && errno != ENOTSUP)))
        return fail(o, err, err_size, "write failed (sync)", errno);
    int fd = o->fd;
    o->fd = -1;
    if (close(fd) != 0 && errno != EINTR)
        return fail(o, err, err_size, "write failed (close)", errno);
    o->closed = 1;
    if (!o->temp) o->committed = 1; /* written in place */
    return 0;
}

/* The directory holding path, opened for reading (a descriptor, or -1). */
static int open_dir_of(const char *path)
{
    const char *slash = strrchr(path, '/');
    char *dir = slash ? malloc((size_t)(slash - path) + 2) : NULL;
    if (slash && !dir) return -1;
    if (dir) {
        size_t n = slash == path ? 1 : (size_t)(slash - path);
        memcpy(dir, path, n);
        dir[n] = '\0';
    }
    int fd = open(dir ? dir : ".", O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    free(dir);
    return fd;
}

static void sync_dir(const char *path)
{
    int fd = open_dir_of(path);
    if (fd >= 0) {
        fsync(fd); /* durability of the rename; not every file system supports it */
        close(fd);
    }
}

typedef struct dir_lock {
    int fd;
    dev_t dev;
    ino_t ino;
} dir_lock;

static int dir_lock_order(const void *a, const void *b)
{
    const dir_lock *x = a, *y = b;
    if (x->dev != y->dev) return x->dev < y->dev ? -1 : 1;
    return x->ino < y->ino ? -1 : x->ino > y->ino;
}

/* Outputs committed together are renamed under an exclusive lock (flock) on each directory
 * they go to, taken in one order (device, inode) by every abrdf process, so that two commands
 * writing the same outputs at once leave all of one's or all of the other's, never a mix.
 * Returns how many locks are held (their descriptors in locks), or -1 with errno set. */
static int lock_dirs(out_file *const *files, int n, dir_lock *locks)
{
    int k = 0;
    for (int i = 0; i < n; ++i) {
        if (!files[i]->temp) continue; /* written in place: no rename */
        struct stat st;
        int fd = open_dir_of(files[i]->path);
        if (fd < 0 || fstat(fd, &st) != 0) {
            int e = errno;
            if (fd >= 0) close(fd);
            for (int j = 0; j < k; ++j) close(locks[j].fd);
            errno = e;
            return -1;
        }
        int seen = 0;
        for (int j = 0; j < k; ++j) seen |= locks[j].dev == st.st_dev && locks[j].ino == st.st_ino;
        if (seen) {
            close(fd);
            continue;
        }
        locks[k].fd = fd, locks[k].dev = st.st_dev, locks[k].ino = st.st_ino;
        ++k;
    }
    qsort(locks, (size_t)k, sizeof *locks, dir_lock_order);
    for (int j = 0; j < k; ++j) {
        int rc;
        do rc = flock(locks[j].fd, LOCK_EX);
        while (rc != 0 && errno == EINTR);
        if (rc != 0) {
            int e = errno;
            for (int i = 0; i < k; ++i) close(locks[i].fd);
            errno = e;
            return -1;
        }
    }
    return k;
}

int out_file_commit(out_file *const *files, int n, char *err, size_t err_size)
{
    for (int i = 0; i < n; ++i)
        if (!files[i]->closed) {
            fail(files[i], err, err_size, "not complete", EINVAL);
            for (int j = 0; j < n; ++j) remove_temp(files[j]);
            return -1;
        }
    dir_lock locks[LIVE_MAX];
    int nlocks = 0;
    if (n > 1 && n <= LIVE_MAX && (nlocks = lock_dirs(files, n, locks)) < 0) {
        fail(files[0], err, err_size, "cannot lock its directory for the commit", errno);
        for (int j = 0; j < n; ++j) remove_temp(files[j]);
        return -1;
    }
    int rc = 0;
    for (int i = 0; i < n && rc == 0; ++i) {
        out_file *o = files[i];
        if (o->committed) continue;
        if (rename(o->temp, o->path) != 0) {
            fail(o, err, err_size, "cannot replace it", errno);
            for (int j = i; j < n; ++j) remove_temp(files[j]);
            rc = -1;
            break;
        }
        live_remove(o->temp);
        free(o->temp);
        o->temp = NULL;
        o->committed = 1;
        sync_dir(o->path);
    }
    for (int j = 0; j < nlocks; ++j) close(locks[j].fd); /* closing releases the lock */
    return rc;
}

/* ---- inputs are never outputs ------------------------------------------------------------- */

typedef struct file_key {
    dev_t dev;
    ino_t ino;
    int exists;       /* 1: the file; 0: (dev, ino) are its directory's and name its name */
    const char *name; /* last component, for a file that does not exist yet */
} file_key;

static int key_of(const char *path, file_key *k)
{
    struct stat st;
    if (stat(path, &st) == 0) {
        k->dev = st.st_dev, k->ino = st.st_ino, k->exists = 1, k->name = NULL;
        return 0;
    }
    if (errno != ENOENT) return -1;
    const char *slash = strrchr(path, '/');
    k->name = slash ? slash + 1 : path;
    char *dir = NULL;
    if (slash) {
        size_t n = slash == path ? 1 : (size_t)(slash - path);
        if (!(dir = malloc(n + 1))) return -1;
        memcpy(dir, path, n);
        dir[n] = '\0';
    }
    int rc = stat(dir ? dir : ".", &st);
    free(dir);
    if (rc != 0 || !*k->name) return -1;
    k->dev = st.st_dev, k->ino = st.st_ino, k->exists = 0;
    return 0;
}

static int same_key(const file_key *a, const file_key *b)
{
    return a->exists == b->exists && a->dev == b->dev && a->ino == b->ino &&
           (a->exists || !strcmp(a->name, b->name));
}

static void refuse(char *err, size_t err_size, const char *role_a, const char *a,
                   const char *role_b, const char *b)
{
    char sa[320], sb[320];
    snprintf(err, err_size, "the %s %s is the same file as the %s %s; nothing was written", role_a,
             path_short(sa, sizeof sa, a, sizeof sa - 1), role_b,
             path_short(sb, sizeof sb, b, sizeof sb - 1));
}

int out_files_distinct(const char *const *outputs, const char *const *output_roles, int nout,
                       const char *const *inputs, const char *const *input_roles, int nin,
                       char *err, size_t err_size)
{
    for (int i = 0; i < nout; ++i) {
        file_key ko, k;
        if (!outputs[i] || key_of(outputs[i], &ko)) continue;
        for (int j = 0; j < nin; ++j)
            if (inputs[j] && !key_of(inputs[j], &k) && same_key(&ko, &k)) {
                refuse(err, err_size, output_roles[i], outputs[i], input_roles[j], inputs[j]);
                return -1;
            }
        for (int j = 0; j < i; ++j)
            if (outputs[j] && !key_of(outputs[j], &k) && same_key(&ko, &k)) {
                refuse(err, err_size, output_roles[i], outputs[i], output_roles[j], outputs[j]);
                return -1;
            }
    }
    return 0;
}

/* ---- a program's single output ------------------------------------------------------------- */

FILE *out_file_or_stdout(out_file *o, const char *path, const char *program)
{
    char err[1024];
    *o = (out_file)OUT_FILE_INIT;
    if (!path) return stdout;
    if (out_file_open(o, path, err, sizeof err) == 0) return o->f;
    fprintf(stderr, "%s: %s\n", program, err);
    return NULL;
}

int out_file_finish(out_file *o, const char *program)
{
    char err[1024];
    if (!o->target) return out_stdout_check(program);
    out_file *const files[1] = {o};
    int rc = out_file_close(o, err, sizeof err) || out_file_commit(files, 1, err, sizeof err);
    out_file_discard(o);
    if (rc) fprintf(stderr, "%s: %s\n", program, err);
    return rc;
}

/* ---- standard output ---------------------------------------------------------------------- */

int out_stdout_check(const char *program)
{
    errno = 0;
    int flushed = fflush(stdout) == 0;
    int code = errno;
    if (flushed && !ferror(stdout)) return 0;
    fprintf(stderr, "%s: standard output: %s\n", program,
            code ? strerror(code) : "a write failed (output incomplete)");
    return 1;
}
