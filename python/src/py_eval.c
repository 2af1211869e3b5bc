/* py_eval.c - f_r over arrays of direction pairs, the GIL released while the library works:
 *   eval_float   the float batch path (abrdf_prepare once), CHUNK pairs at a time through
 *                abrdf_eval_prepared_rows, which makes every row unit itself (abrdf.h: rows
 *                of unit length are used as given, others are scaled, zero or non-finite
 *                ones give f_r = 0): float32 rows are handed over as they are; float64 rows
 *                (and rows that out overlaps) are first converted into float rows on the
 *                stack, a row whose length float cannot hold (tiny, huge) normalised in
 *                double first. Several lobes (a material: a sequence of Params/Tables) are
 *                evaluated in the same pass over each chunk, the rows read from cache, and
 *                summed in their order. Large arrays are spread over the machine's cores:
 *                the threads (the caller's among them) take blocks of BLOCK_ROWS rows in turn
 *                until none is left, so a thread that starts late, or whose core is busy,
 *                takes fewer (the library itself has no threads);
 *   eval_double  the double-precision scalar reference (abrdf_eval with the local frame), one
 *                pair at a time; a Table (a measured table) by abrdf_eval_prepared, the
 *                model's only double path.
 *   _time_eval_batch  the C batch path alone on the same directions, timed here, so that the
 *                binding's cost is measured against it in one process (docs/BENCHMARKS.md):
 *                abrdf_eval_batch on structure-of-arrays copies, or abrdf_eval_prepared_rows
 *                on float rows.
 * Directions are in the local frame (N = +z, T = +x); wi toward the light, wo toward the
 * viewer; f_r is without the cosine (abrdf.h). Zero or non-finite vectors give f_r = 0. */
#include "abrdf_py.h" /* first: Python.h sets the feature macros */

#include <math.h>
#include <pthread.h>
#include <sched.h>
#include <signal.h>
#include <stdint.h>
#include <stdlib.h>
#include <time.h>
#include <unistd.h>

/* Pairs per call of abrdf_eval_prepared_rows: three buffers of CHUNK rows on the stack (9 KiB),
 * long enough for the batch loop to run at its vector speed. */
#define CHUNK 256

/* Row k of a (N, 3) buffer of `kind` as doubles. */
static void row(const void *buf, abrdf_py_real kind, Py_ssize_t k, double v[3])
{
    if (kind == ABRDF_PY_F32) {
        const float *p = (const float *)buf + 3 * k;
        v[0] = p[0], v[1] = p[1], v[2] = p[2];
    } else {
        const double *p = (const double *)buf + 3 * k;
        v[0] = p[0], v[1] = p[1], v[2] = p[2];
    }
}

/* Squared lengths that square and invert in double without overflow or loss: outside them a
 * row is first scaled by its largest component. */
#define LEN2_MIN 1e-290
#define LEN2_MAX 1e290

/* One row normalised in double, whatever its length: the exact path, for the rows the float
 * pass cannot take (zero, tiny, huge or non-finite). Zero or non-finite rows give 0. */
static void load_row_exact(const void *buf, abrdf_py_real kind, Py_ssize_t k, float *x, float *y,
                           float *z)
{
    double v[3];
    row(buf, kind, k, v);
    double len2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    if (!(len2 >= LEN2_MIN && len2 <= LEN2_MAX)) { /* rare: tiny, huge, zero or NaN */
        double m = fmax(fabs(v[0]), fmax(fabs(v[1]), fabs(v[2])));
        *x = *y = *z = 0.0f;
        if (!(m > 0.0) || !isfinite(v[0]) || !isfinite(v[1]) || !isfinite(v[2])) return;
        v[0] /= m, v[1] /= m, v[2] /= m;
        len2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    }
    double inv = 1.0 / sqrt(len2);
    *x = (float)(v[0] * inv), *y = (float)(v[1] * inv), *z = (float)(v[2] * inv);
}

/* Squared lengths (in double) of the float64 rows that are converted to float as they are:
 * their largest component stays far inside float's normal range. Others (and zero or
 * non-finite rows) take load_row_exact: normalised in double first. */
#define LEN2F_MIN 1e-60
#define LEN2F_MAX 1e60

/* The row loops run in vector registers: this file is built with -O3 -fno-math-errno
 * -fno-trapping-math, and, where GCC builds for x86-64 with glibc, each loop function is
 * compiled for AVX-512, AVX2 and the baseline, the best the CPU has chosen by glibc's ifunc
 * when the module loads (the library, which must link anywhere, dispatches its batch loops
 * itself instead). */
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__GLIBC__)
#define ROW_LOOPS __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define ROW_LOOPS
#endif

/* n float64 rows of p converted to float rows in dst; 1 if a row's squared length is outside
 * [LEN2F_MIN, LEN2F_MAX] (or not a number). The flag is a double select kept as its bits: an
 * integer flag from double compares would keep the loop from vectorising. */
ROW_LOOPS static int convert_rows(const double *restrict p, int n, float *restrict dst)
{
    uint64_t rare = 0;
    for (int k = 0; k < n; ++k) {
        double x = p[3 * k], y = p[3 * k + 1], z = p[3 * k + 2];
        dst[3 * k] = (float)x, dst[3 * k + 1] = (float)y, dst[3 * k + 2] = (float)z;
        double len2 = x * x + y * y + z * z;
        double t = len2 >= LEN2F_MIN && len2 <= LEN2F_MAX ? 0.0 : 1.0;
        uint64_t u;
        memcpy(&u, &t, sizeof u);
        rare |= u;
    }
    return rare != 0;
}

/* Rows [start, start + n) of buf as float rows in dst, for abrdf_eval_prepared_rows: float32
 * copied, float64 converted (rows whose length float cannot hold by the exact path). */
static void to_rows(const void *buf, abrdf_py_real kind, Py_ssize_t start, int n, float *dst)
{
    if (kind == ABRDF_PY_F32) {
        memcpy(dst, (const float *)buf + 3 * start, (size_t)n * 3 * sizeof *dst);
        return;
    }
    const double *p = (const double *)buf + 3 * start;
    if (!convert_rows(p, n, dst)) return;
    for (int k = 0; k < n; ++k) {
        double len2 =
            p[3 * k] * p[3 * k] + p[3 * k + 1] * p[3 * k + 1] + p[3 * k + 2] * p[3 * k + 2];
        if (!(len2 >= LEN2F_MIN && len2 <= LEN2F_MAX))
            load_row_exact(buf, kind, start + k, dst + 3 * k, dst + 3 * k + 1, dst + 3 * k + 2);
    }
}

/* The arguments every evaluation takes: a Params or a Table (a measured table) and two (N, 3)
 * direction arrays. */
typedef struct eval_args {
    abrdf_py_params *params; /* NULL for a Table */
    abrdf_py_table *table;   /* NULL for a Params */
    Py_buffer wi, wo, out;
    Py_ssize_t rows;
    abrdf_py_real wi_kind, wo_kind;
} eval_args;

static int get_args(PyObject *args, const char *name, int out_kind, eval_args *a)
{
    PyObject *p, *wi, *wo, *out;
    if (!PyArg_ParseTuple(args, "OOOO", &p, &wi, &wo, &out)) return -1;
    a->params = NULL, a->table = NULL;
    if (PyObject_TypeCheck(p, &abrdf_py_table_type))
        a->table = (abrdf_py_table *)p;
    else if (!(a->params = abrdf_py_params_arg(p, name)))
        return -1;
    Py_ssize_t n_wo, n_out;
    abrdf_py_real k_out;
    if (abrdf_py_rows3(wi, "wi", 0, 0, &a->wi, &a->rows, &a->wi_kind)) return -1;
    if (abrdf_py_rows3(wo, "wo", 0, 0, &a->wo, &n_wo, &a->wo_kind)) {
        PyBuffer_Release(&a->wi);
        return -1;
    }
    if (abrdf_py_rows3(out, "out", out_kind, 1, &a->out, &n_out, &k_out)) {
        PyBuffer_Release(&a->wi);
        PyBuffer_Release(&a->wo);
        return -1;
    }
    if (n_wo != a->rows || n_out != a->rows) {
        PyErr_Format(PyExc_ValueError,
                     "%s: wi, wo and out need the same number of rows (%zd, %zd, %zd)", name,
                     a->rows, n_wo, n_out);
        PyBuffer_Release(&a->wi);
        PyBuffer_Release(&a->wo);
        PyBuffer_Release(&a->out);
        return -1;
    }
    return 0;
}

static void release(eval_args *a)
{
    PyBuffer_Release(&a->wi);
    PyBuffer_Release(&a->wo);
    PyBuffer_Release(&a->out);
}

/* Rows per thread below which another thread does not pay for itself (waking one, after a
 * pause, costs about what 10^4-10^5 pairs of the cheapest model do: docs/BENCHMARKS.md). */
#define ROWS_PER_THREAD 32768
#define MAX_THREADS 64
/* Lobes of one material at most (2 KiB of prepared model each: STACK_LOBES on the stack,
 * more allocated per call). */
#define MAX_LOBES 4096

/* Rows a thread takes at a time: long enough that taking one (a lock) costs nothing, short
 * enough that a thread left without a core holds back little (a 10^6-row call has 62). */
#define BLOCK_ROWS 16384

/* The work of one eval_float call, shared by its threads: the sum of `lobes` prepared models
 * over a's rows; `next` (the first row no thread has taken) and `status` under `lock`. */
typedef struct eval_work {
    const abrdf_prepared *prep;
    int lobes;
    const eval_args *a;
    pthread_mutex_t lock;
    Py_ssize_t next;
    int status;
} eval_work;

/* o[k] += t[k] for n floats: a further lobe's values added to the sum so far. */
ROW_LOOPS static void add(float *restrict o, const float *restrict t, int n)
{
    for (int k = 0; k < n; ++k) o[k] += t[k];
}

/* 1 if two buffers share a byte. */
static int overlap(const Py_buffer *a, const Py_buffer *b)
{
    uintptr_t p = (uintptr_t)a->buf, q = (uintptr_t)b->buf;
    return p < q + (uintptr_t)b->len && q < p + (uintptr_t)a->len;
}

/* Rows [begin, end) of the work into a->out: ABRDF_OK or the library's status. */
static int eval_rows(const eval_work *r, Py_ssize_t begin, Py_ssize_t end)
{
    const eval_args *a = r->a;
    float more[3 * CHUNK], bi[3 * CHUNK], bo[3 * CHUNK];
    float *out = a->out.buf;
    int st = ABRDF_OK;
    /* float32 rows straight into the library's loops, unless out is over them (which only
     * the module function allows: the library's rows may not overlap its output) */
    int direct_i = a->wi_kind == ABRDF_PY_F32 && !overlap(&a->out, &a->wi);
    int direct_o = a->wo_kind == ABRDF_PY_F32 && !overlap(&a->out, &a->wo);
    for (Py_ssize_t start = begin; start < end && st == ABRDF_OK; start += CHUNK) {
        int n = end - start < CHUNK ? (int)(end - start) : CHUNK;
        const float *pi = bi, *po = bo;
        if (direct_i)
            pi = (const float *)a->wi.buf + 3 * start;
        else
            to_rows(a->wi.buf, a->wi_kind, start, n, bi);
        if (direct_o)
            po = (const float *)a->wo.buf + 3 * start;
        else
            to_rows(a->wo.buf, a->wo_kind, start, n, bo);
        float *o = out + 3 * start;
        st = abrdf_eval_prepared_rows(&r->prep[0], (size_t)n, pi, po, o);
        for (int l = 1; l < r->lobes && st == ABRDF_OK; ++l) {
            st = abrdf_eval_prepared_rows(&r->prep[l], (size_t)n, pi, po, more);
            add(o, more, 3 * n);
        }
    }
    return st; /* not ABRDF_OK: the caller raises; out is discarded */
}

/* The next block of rows not yet taken, into [*begin, *end): 0 when none is left or a block
 * has failed. */
static int take_block(eval_work *w, Py_ssize_t *begin, Py_ssize_t *end)
{
    pthread_mutex_lock(&w->lock);
    int more = w->status == ABRDF_OK && w->next < w->a->rows;
    if (more) {
        *begin = w->next;
        *end = w->a->rows - w->next > BLOCK_ROWS ? w->next + BLOCK_ROWS : w->a->rows;
        w->next = *end;
    }
    pthread_mutex_unlock(&w->lock);
    return more;
}

/* One thread of eval_float: blocks until none is left; the first failure stops every thread. */
static void *eval_blocks(void *arg)
{
    eval_work *w = arg;
    Py_ssize_t begin, end;
    while (take_block(w, &begin, &end)) {
        int st = eval_rows(w, begin, end);
        if (st == ABRDF_OK) continue;
        pthread_mutex_lock(&w->lock);
        if (w->status == ABRDF_OK) w->status = st;
        pthread_mutex_unlock(&w->lock);
    }
    return NULL;
}

/* THE THREADS, kept between calls. A call that spreads its rows over t threads hands the
 * work to t - 1 workers of this pool and works itself; a worker waits on a condition variable
 * between calls, so that a call pays a wake-up rather than a thread's start (about 60 us each
 * when every call started its own: a 65536-pair call took longer on two threads than on one).
 * Workers are started when a call first wants them (never more than MAX_THREADS - 1), with
 * the asynchronous signals blocked (those stay with Python's threads; a fault in a worker
 * still reaches its handler), and they only run eval_blocks, on the cores the calling thread
 * may use (the owner's affinity, given to every worker when it changes). One call at a time
 * owns the pool: a call made while another Python thread's call owns it runs on its own
 * thread. fork() takes the pool's lock first, and the child starts with an empty pool (its
 * workers are gone). The library itself has no threads and no state; this pool is the
 * binding's. */
typedef struct eval_pool {
    pthread_mutex_t lock; /* guards every field below */
    pthread_cond_t wake;  /* to the workers: tickets are up */
    pthread_cond_t idle;  /* to the owner: no worker is in its work any more */
    eval_work *work;      /* the owner's work, while it owns the pool */
    int workers;          /* started */
    int tickets;          /* workers the work still wants: each that wakes takes one */
    int busy;             /* workers in the work */
    int owned;            /* a call owns the pool */
    int spinners;         /* workers that watch for the next call: one per core but the caller's */
    pthread_t tid[MAX_THREADS]; /* the workers */
#ifdef __linux__
    cpu_set_t cores; /* the last owner's affinity, which every worker was given */
#endif
} eval_pool;
static eval_pool pool = {.lock = PTHREAD_MUTEX_INITIALIZER,
                         .wake = PTHREAD_COND_INITIALIZER,
                         .idle = PTHREAD_COND_INITIALIZER};
static pthread_once_t pool_once = PTHREAD_ONCE_INIT;
static int pool_usable; /* the fork handlers are registered: workers may be started */

/* A worker that has just finished looks for the next call's tickets for SPIN_NS before it
 * sleeps: calls that follow each other closely (a loop over chunks) then pay no wake-up. */
#define SPIN_NS 200000
static void spin_for_tickets(void)
{
    struct timespec t0, t;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    for (;;) {
        for (int i = 0; i < 256; ++i) {
            if (__atomic_load_n(&pool.tickets, __ATOMIC_RELAXED) > 0) return;
#if defined(__x86_64__) || defined(__i386__)
            __builtin_ia32_pause();
#elif defined(__aarch64__)
            __asm__ __volatile__("yield");
#endif
        }
        clock_gettime(CLOCK_MONOTONIC, &t);
        if ((t.tv_sec - t0.tv_sec) * 1000000000L + (t.tv_nsec - t0.tv_nsec) > SPIN_NS) return;
    }
}

static void *pool_worker(void *arg)
{
    const int spins = (int)(intptr_t)arg; /* this worker watches for the next call */
    pthread_mutex_lock(&pool.lock);
    for (;;) {
        if (pool.tickets == 0 && spins) {
            pthread_mutex_unlock(&pool.lock);
            spin_for_tickets();
            pthread_mutex_lock(&pool.lock);
        }
        while (pool.tickets == 0) pthread_cond_wait(&pool.wake, &pool.lock);
        __atomic_store_n(&pool.tickets, pool.tickets - 1, __ATOMIC_RELAXED);
        ++pool.busy;
        eval_work *w = pool.work;
        pthread_mutex_unlock(&pool.lock);
        eval_blocks(w);
        pthread_mutex_lock(&pool.lock);
        if (--pool.busy == 0) pthread_cond_signal(&pool.idle);
    }
    return NULL;
}

/* fork(): the parent takes the pool's lock, so that no other thread holds it while the
 * process is copied; the child, where only the forking thread exists, starts an empty pool. */
static void pool_before_fork(void) { pthread_mutex_lock(&pool.lock); }
static void pool_parent_after_fork(void) { pthread_mutex_unlock(&pool.lock); }
static void pool_child_after_fork(void)
{
    pthread_mutex_init(&pool.lock, NULL);
    pthread_cond_init(&pool.wake, NULL);
    pthread_cond_init(&pool.idle, NULL);
    pool.work = NULL;
    pool.workers = pool.tickets = pool.busy = pool.owned = pool.spinners = 0;
#ifdef __linux__
    CPU_ZERO(&pool.cores);
#endif
}
/* Once, before the pool's lock is first taken (registering under it could race a fork). */
static void pool_register(void)
{
    pool_usable =
        pthread_atfork(pool_before_fork, pool_parent_after_fork, pool_child_after_fork) == 0;
}

static long usable_cores(void);

/* One more worker (pool.lock held): 0 if the system would not start it. */
static int pool_grow(void)
{
    if (!pool_usable) return 0; /* workers a child would think it had: none at all */
    sigset_t async, old;
    sigfillset(&async);
    const int faults[] = {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGTRAP, SIGSYS, SIGABRT};
    for (size_t i = 0; i < sizeof faults / sizeof faults[0]; ++i) sigdelset(&async, faults[i]);
    pthread_sigmask(SIG_SETMASK, &async, &old);
    /* one worker per core but the caller's watches for the next call; more (threads=N above
     * the cores) would take the cores from the caller while they watch */
    int spins = pool.spinners + 1 < usable_cores();
    pthread_t *tid = &pool.tid[pool.workers];
    pthread_attr_t attr;
    int ok = pthread_attr_init(&attr) == 0;
    if (ok) {
        /* huang's table build takes about 128 KiB of stack (abrdf.h): at least 1 MiB
         * whatever the platform's default (musl's is 128 KiB) */
        size_t stack = 0;
        if (!pthread_attr_getstacksize(&attr, &stack) && stack < (1u << 20))
            pthread_attr_setstacksize(&attr, 1u << 20);
        ok = pthread_attr_setdetachstate(&attr, PTHREAD_CREATE_DETACHED) == 0 &&
             pthread_create(tid, &attr, pool_worker, (void *)(intptr_t)spins) == 0;
        pthread_attr_destroy(&attr);
    }
#ifdef __linux__
    if (ok) pthread_setname_np(*tid, "abrdf-eval"); /* as top and debuggers show it */
#endif
    pthread_sigmask(SIG_SETMASK, &old, NULL);
    pool.workers += ok;
    pool.spinners += ok && spins;
    return ok;
}

/* w on t threads: the caller and up to t - 1 of the pool's workers (fewer if the pool is
 * owned by another call or no more workers could be started: the blocks go to those there
 * are). Returns when every block is done and no worker holds w. */
static void run_work(eval_work *w, int t)
{
    int helpers = 0, owner = 0;
    if (t > 1) {
        pthread_once(&pool_once, pool_register);
#ifdef __linux__
        cpu_set_t cores;
        int have_cores = sched_getaffinity(0, sizeof cores, &cores) == 0;
#endif
        pthread_mutex_lock(&pool.lock);
        if (!pool.owned) {
            pool.owned = owner = 1;
            while (pool.workers < t - 1 && pool_grow()) continue;
            helpers = pool.workers < t - 1 ? pool.workers : t - 1;
            pool.work = w;
#ifdef __linux__
            /* every worker on the owner's cores (a worker started now has them already) */
            if (have_cores && !CPU_EQUAL(&cores, &pool.cores)) {
                pool.cores = cores;
                for (int i = 0; i < pool.workers; ++i)
                    pthread_setaffinity_np(pool.tid[i], sizeof cores, &cores);
            }
#endif
            __atomic_store_n(&pool.tickets, helpers, __ATOMIC_RELAXED);
            if (helpers == pool.workers)
                pthread_cond_broadcast(&pool.wake);
            else
                for (int i = 0; i < helpers; ++i) pthread_cond_signal(&pool.wake);
        }
        pthread_mutex_unlock(&pool.lock);
    }
    eval_blocks(w);
    if (!owner) return;
    pthread_mutex_lock(&pool.lock);
    /* every block is taken: a worker not yet awake is not needed */
    __atomic_store_n(&pool.tickets, 0, __ATOMIC_RELAXED);
    while (pool.busy > 0) pthread_cond_wait(&pool.idle, &pool.lock);
    pool.work = NULL;
    pool.owned = 0;
    pthread_mutex_unlock(&pool.lock);
}

/* The cores this thread may run on (its affinity mask: taskset, cgroup cpusets), else the
 * online ones. */
static long usable_cores(void)
{
#ifdef __linux__
    cpu_set_t set;
    if (sched_getaffinity(0, sizeof set, &set) == 0 && CPU_COUNT(&set) > 0) return CPU_COUNT(&set);
#endif
    return sysconf(_SC_NPROCESSORS_ONLN);
}

/* How many threads for `rows` pairs: `asked` if > 0 (at most MAX_THREADS, checked by the
 * caller), else one per usable core, as long as each gets ROWS_PER_THREAD rows; never more
 * than there are blocks of BLOCK_ROWS rows to take. */
static int thread_count(Py_ssize_t rows, int asked)
{
    long cores = usable_cores();
    long t = asked > 0 ? asked : (cores > 0 ? cores : 1);
    if (asked <= 0 && rows / ROWS_PER_THREAD < t) t = (long)(rows / ROWS_PER_THREAD);
    if (t > (rows + BLOCK_ROWS - 1) / BLOCK_ROWS) t = (long)((rows + BLOCK_ROWS - 1) / BLOCK_ROWS);
    if (t > MAX_THREADS) t = MAX_THREADS;
    return t < 1 ? 1 : (int)t;
}

/* Lobes prepared on the stack; more are allocated. */
#define STACK_LOBES 4

/* The lobes of eval_float's first argument: a Params or a Table alone (*lobes NULL), or a
 * tuple or list of them, copied into a new tuple *lobes (which holds every lobe while the GIL
 * is released). Their count, or -1 with an exception. */
static Py_ssize_t lobes_arg(PyObject *p, PyObject **lobes)
{
    *lobes = NULL;
    if (!PyTuple_Check(p) && !PyList_Check(p)) return 1;
    if (!(*lobes = PySequence_Tuple(p))) return -1;
    Py_ssize_t n = PyTuple_GET_SIZE(*lobes);
    if (n >= 1 && n <= MAX_LOBES) return n;
    if (n < 1)
        PyErr_SetString(PyExc_ValueError, "eval_float: a material needs at least one lobe");
    else
        PyErr_Format(PyExc_ValueError, "eval_float: at most %d lobes, got %zd", MAX_LOBES, n);
    Py_CLEAR(*lobes);
    return -1;
}

static PyObject *py_eval_float(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *p, *wi, *wo, *out, *lobes;
    int threads = 0;
    if (!PyArg_ParseTuple(args, "OOOO|i", &p, &wi, &wo, &out, &threads)) return NULL;
    if (threads < 0 || threads > MAX_THREADS)
        return PyErr_Format(PyExc_ValueError, "threads must be in [0, %d], got %d", MAX_THREADS,
                            threads);
    Py_ssize_t nl = lobes_arg(p, &lobes);
    if (nl < 0) return NULL;
    PyObject *first = lobes ? PyTuple_GET_ITEM(lobes, 0) : p;
    PyObject *four = Py_BuildValue("(OOOO)", first, wi, wo, out);
    eval_args a;
    int bad = !four || get_args(four, "eval_float", ABRDF_PY_F32, &a);
    Py_XDECREF(four);
    if (bad) {
        Py_XDECREF(lobes);
        return NULL;
    }
    abrdf_prepared small[STACK_LOBES];
    abrdf_prepared *prep = nl <= STACK_LOBES ? small : PyMem_Malloc((size_t)nl * sizeof *prep);
    if (!prep) PyErr_NoMemory();
    bad = !prep;
    for (Py_ssize_t i = 0; i < nl && !bad; ++i)
        bad = abrdf_py_prepared_arg(lobes ? PyTuple_GET_ITEM(lobes, i) : p, "eval_float",
                                    &prep[i]) != 0;
    if (bad) {
        if (prep != small) PyMem_Free(prep);
        release(&a);
        Py_XDECREF(lobes);
        return NULL;
    }
    /* out over the rows (only this module function allows it) is written as the rows are
     * read: one thread, in order, so that no thread reads a row another has overwritten */
    int t = overlap(&a.out, &a.wi) || overlap(&a.out, &a.wo) ? 1 : thread_count(a.rows, threads);
    eval_work w = {prep, (int)nl, &a, PTHREAD_MUTEX_INITIALIZER, 0, ABRDF_OK};
    Py_BEGIN_ALLOW_THREADS;
    run_work(&w, t);
    Py_END_ALLOW_THREADS;
    pthread_mutex_destroy(&w.lock);
    release(&a);
    if (prep != small) PyMem_Free(prep);
    Py_XDECREF(lobes);
    int st = w.status;
    if (st != ABRDF_OK)
        return abrdf_py_fail(st, "the float batch evaluation: %s", abrdf_strerror(st));
    Py_RETURN_NONE;
}

static PyObject *py_eval_double(PyObject *self, PyObject *args)
{
    (void)self;
    eval_args a;
    if (get_args(args, "eval_double", ABRDF_PY_F64, &a)) return NULL;
    int st = ABRDF_OK;
    double *out = a.out.buf;
    Py_BEGIN_ALLOW_THREADS;
    for (Py_ssize_t k = 0; k < a.rows && st == ABRDF_OK; ++k) {
        double wi[3], wo[3];
        row(a.wi.buf, a.wi_kind, k, wi);
        row(a.wo.buf, a.wo_kind, k, wo);
        st = a.table ? abrdf_eval_prepared(&a.table->prepared, NULL, wi, wo, out + 3 * k)
                     : abrdf_eval(a.params->model, &a.params->params, NULL, wi, wo, out + 3 * k);
    }
    Py_END_ALLOW_THREADS;
    release(&a);
    if (st != ABRDF_OK)
        return abrdf_py_fail(st, "%s: %s", a.table ? "abrdf_eval_prepared" : "abrdf_eval",
                             abrdf_strerror(st));
    Py_RETURN_NONE;
}

/* The thread's CPU time, as `abrdf calibrate` times models: time spent descheduled on a busy
 * machine is not counted. */
static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* _time_eval_batch(params, wi, wo, out, calls, layout=0) -> seconds per call over all rows,
 * `calls` calls between two reads of the clock (a read costs about as much as a call on a few
 * pairs), after one untimed call (the output's first touch is not the model's cost), on
 * copies made before the clock starts: layout 0 abrdf_eval_batch on structure-of-arrays
 * copies normalised in double, layout 1 abrdf_eval_prepared_rows (prepared before the clock)
 * on float rows as eval_float hands them over. */
static PyObject *py_time_eval_batch(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *p, *wi, *wo, *out;
    int calls, layout = 0;
    if (!PyArg_ParseTuple(args, "OOOOi|i", &p, &wi, &wo, &out, &calls, &layout)) return NULL;
    if (calls < 1) return PyErr_Format(PyExc_ValueError, "calls must be >= 1");
    if (layout != 0 && layout != 1) return PyErr_Format(PyExc_ValueError, "layout must be 0 or 1");
    PyObject *tuple = Py_BuildValue("(OOOO)", p, wi, wo, out);
    if (!tuple) return NULL;
    eval_args a;
    int bad = get_args(tuple, "_time_eval_batch", ABRDF_PY_F32, &a);
    Py_DECREF(tuple);
    if (bad) return NULL;
    if (!a.params) {
        release(&a);
        return PyErr_Format(PyExc_TypeError, "_time_eval_batch: a Params is needed");
    }
    size_t n = (size_t)a.rows;
    float *mem = malloc(9 * (n ? n : 1) * sizeof *mem);
    if (!mem) {
        release(&a);
        return PyErr_NoMemory();
    }
    abrdf_prepared prep;
    int st = abrdf_prepare(a.params->model, &a.params->params, &prep);
    double seconds = 0.0;
    float *o = a.out.buf;
    Py_BEGIN_ALLOW_THREADS;
    if (st == ABRDF_OK && layout == 1) {
        for (size_t start = 0; start < n; start += CHUNK) {
            int m = n - start < CHUNK ? (int)(n - start) : CHUNK;
            to_rows(a.wi.buf, a.wi_kind, (Py_ssize_t)start, m, mem + 3 * start);
            to_rows(a.wo.buf, a.wo_kind, (Py_ssize_t)start, m, mem + 3 * n + 3 * start);
        }
        st = abrdf_eval_prepared_rows(&prep, n, mem, mem + 3 * n, mem + 6 * n); /* untimed */
        double t0 = now();
        for (int r = 0; r < calls && st == ABRDF_OK; ++r)
            st = abrdf_eval_prepared_rows(&prep, n, mem, mem + 3 * n, mem + 6 * n);
        seconds = (now() - t0) / calls;
        memcpy(o, mem + 6 * n, 3 * n * sizeof *o);
    } else if (st == ABRDF_OK) {
        for (size_t k = 0; k < n; ++k) {
            for (int d = 0; d < 2; ++d) {
                double v[3];
                row(d ? a.wo.buf : a.wi.buf, d ? a.wo_kind : a.wi_kind, (Py_ssize_t)k, v);
                double len = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
                double s = len > 0.0 && isfinite(len) ? 1.0 / len : 0.0;
                for (int c = 0; c < 3; ++c) mem[(3 * d + c) * n + k] = (float)(v[c] * s);
            }
        }
        abrdf_batch b = {n,           mem,         mem + n,     mem + 2 * n, mem + 3 * n,
                         mem + 4 * n, mem + 5 * n, mem + 6 * n, mem + 7 * n, mem + 8 * n};
        st = abrdf_eval_batch(a.params->model, &a.params->params, &b); /* untimed: first touch */
        double t0 = now();
        for (int r = 0; r < calls && st == ABRDF_OK; ++r)
            st = abrdf_eval_batch(a.params->model, &a.params->params, &b);
        seconds = (now() - t0) / calls;
        for (size_t k = 0; k < n; ++k)
            o[3 * k] = b.f_r[k], o[3 * k + 1] = b.f_g[k], o[3 * k + 2] = b.f_b[k];
    }
    Py_END_ALLOW_THREADS;
    release(&a);
    free(mem);
    if (st != ABRDF_OK)
        return abrdf_py_fail(st, "%s: %s", layout ? "abrdf_eval_prepared_rows" : "abrdf_eval_batch",
                             abrdf_strerror(st));
    return PyFloat_FromDouble(seconds);
}

PyMethodDef abrdf_py_eval_methods[] = {
    {"eval_float", py_eval_float, METH_VARARGS,
     "eval_float(params, wi, wo, out, threads=0) -> None: f_r of every row pair (params: a "
     "Params or a Table, or a tuple or list of them: a material, its lobes evaluated in one "
     "pass over the rows and summed in their order) by the float "
     "batch path (abrdf_eval_prepared_rows; float64 rows converted to float first) into "
     "out; wi, wo: C-contiguous (N, 3) float32 or float64 local-frame directions (made unit "
     "by the library: zero or non-finite ones give 0); out: writable (N, 3) float32; threads: "
     "0 = one per usable core for large arrays (32768 rows or more per thread), else that "
     "many (at most 64, and one per block of 16384 rows: the threads take blocks in turn). "
     "Releases the GIL."},
    {"eval_double", py_eval_double, METH_VARARGS,
     "eval_double(params, wi, wo, out) -> None: the same by the double-precision scalar "
     "reference (abrdf_eval, local frame; a Table: abrdf_eval_prepared); out: writable (N, 3) "
     "float64. Releases the GIL."},
    {"_time_eval_batch", py_time_eval_batch, METH_VARARGS,
     "_time_eval_batch(params, wi, wo, out, calls, layout=0) -> float: seconds of thread CPU "
     "time per call over all rows, `calls` calls timed together, on copies made before timing "
     "(the C batch path alone, for the binding's benchmark): layout 0 abrdf_eval_batch on "
     "structure-of-arrays copies, 1 abrdf_eval_prepared_rows on float rows; out receives the "
     "result."},
    {NULL, NULL, 0, NULL}};
