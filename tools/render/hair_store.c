/* hair_store.c - huang tables built, cached and held for a command (hair_store.h). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "hair_store.h"
#include "in_file.h"
#include "out_file.h"

void hair_store_init(hair_store *t, const int sizes[4], const char *cache, int threads)
{
    memset(t, 0, sizeof *t);
    memcpy(t->sizes, sizes, sizeof t->sizes);
    t->cache = cache;
    t->threads = threads > 1 ? threads : 1;
}

void hair_store_free(hair_store *t)
{
    for (int i = 0; i < t->count; ++i) free(t->values[i]);
    free(t->values);
    memset(t, 0, sizeof *t);
}

/* ---- a build over threads --------------------------------------------------------------- */

typedef struct table_job {
    const abrdf_params *params;
    const int *sizes;
    double *values;
    int rows, next, status;
    pthread_mutex_t lock;
} table_job;

static void *table_worker(void *arg)
{
    table_job *j = arg;
    for (;;) {
        pthread_mutex_lock(&j->lock);
        int row = j->status == ABRDF_OK && j->next < j->rows ? j->next++ : -1;
        pthread_mutex_unlock(&j->lock);
        if (row < 0) return NULL;
        int st = abrdf_huang_table_build(j->params, j->sizes, row, row + 1, j->values);
        if (st != ABRDF_OK) {
            pthread_mutex_lock(&j->lock);
            j->status = st;
            pthread_mutex_unlock(&j->lock);
        }
    }
}

/* Every row of the table into v, over t->threads threads: ABRDF_OK or the build's status. */
static int table_build(const hair_store *t, const abrdf_params *p, int rows, double *v)
{
    table_job j = {p, t->sizes, v, rows, 0, ABRDF_OK, PTHREAD_MUTEX_INITIALIZER};
    int nt = t->threads < 64 ? t->threads : 64, started = 0;
    pthread_t th[64];
    /* a build takes about 128 KiB of stack (abrdf.h): at least 1 MiB whatever the
     * platform's default (musl's is 128 KiB) */
    pthread_attr_t attr;
    size_t stack = 0;
    int attr_ok = pthread_attr_init(&attr) == 0;
    if (attr_ok && !pthread_attr_getstacksize(&attr, &stack) && stack < (1u << 20))
        pthread_attr_setstacksize(&attr, 1u << 20);
    for (int i = 1; i < nt; ++i)
        started += !pthread_create(&th[started], attr_ok ? &attr : NULL, table_worker, &j);
    if (attr_ok) pthread_attr_destroy(&attr);
    table_worker(&j);
    for (int i = 0; i < started; ++i) pthread_join(th[i], NULL);
    return j.status;
}

/* ---- the cache directory ---------------------------------------------------------------- */

/* The file of a table in the cache directory: named by its header's keys and sizes
 * (abrdf_huang_table_build of rows [0, 0) writes the header alone). 0, or -1 if the name does
 * not fit. */
static int table_file(const char *dir, const double *header, char *buf, size_t size)
{
    int n = snprintf(buf, size, "%s/huang-%08lx%08lx-%dx%dx%dx%d.table", dir,
                     (unsigned long)header[6], (unsigned long)header[7], (int)header[2],
                     (int)header[3], (int)header[4], (int)header[5]);
    return n > 0 && (size_t)n < size ? 0 : -1;
}

/* The cached table into v (n doubles) if there is one that abrdf_prepare_huang_table takes:
 * 1, else 0 (no file, another size, another material: then it is rebuilt and replaced). */
static int table_read(const char *path, double *v, long n, const abrdf_params *p,
                      const int sizes[4], abrdf_prepared *out)
{
    char err[512];
    FILE *f = in_file_open(path, err, sizeof err);
    if (!f) return 0;
    int ok = fread(v, sizeof *v, (size_t)n, f) == (size_t)n && fgetc(f) == EOF && !ferror(f);
    fclose(f);
    return ok && abrdf_prepare_huang_table(p, sizes, v, out) == ABRDF_OK;
}

/* Write the table whole (out_file.h); a failure is a warning on stderr, the command goes on. */
static void table_write(const char *path, const double *v, long n, const char *what)
{
    char err[1024];
    out_file o = OUT_FILE_INIT, *list[1] = {&o};
    if (out_file_open(&o, path, err, sizeof err) == 0) {
        out_file_write(&o, v, (size_t)n * sizeof *v);
        if (out_file_close(&o, err, sizeof err) == 0 &&
            out_file_commit(list, 1, err, sizeof err) == 0) {
            out_file_discard(&o);
            return;
        }
    }
    out_file_discard(&o);
    fprintf(stderr, "abrdf: warning: %s: its huang table is not cached: %s\n", what, err);
}

/* ---- the store ---------------------------------------------------------------------------- */

/* v kept in the store: 0, or -1 if out of memory (v is then the caller's). */
static int store_add(hair_store *t, double *v)
{
    if (t->count == t->cap) {
        int cap = t->cap ? 2 * t->cap : 4;
        double **nv = realloc(t->values, (size_t)cap * sizeof *nv);
        if (!nv) return -1;
        t->values = nv;
        t->cap = cap;
    }
    t->values[t->count++] = v;
    return 0;
}

int hair_store_get(hair_store *t, const abrdf_params *p, const char *what, abrdf_prepared *out,
                   char *err, size_t err_size)
{
    long n = 0;
    int rows = 0, st = abrdf_huang_table_size(p, t->sizes, &n, &rows);
    if (st != ABRDF_OK) {
        snprintf(err, err_size, "%s: huang table %d,%d,%d,%d: %s", what, t->sizes[0], t->sizes[1],
                 t->sizes[2], t->sizes[3], abrdf_strerror(st));
        return -1;
    }
    /* a table held already: prepare takes only this material's, at these sizes */
    for (int i = 0; i < t->count; ++i)
        if (abrdf_prepare_huang_table(p, t->sizes, t->values[i], out) == ABRDF_OK) return 0;
    double *v = malloc((size_t)n * sizeof *v);
    if (!v || store_add(t, v)) {
        free(v);
        snprintf(err, err_size, "%s: no memory for its huang table (%ld MB)", what,
                 (long)(n * 8 / 1000000));
        return -1;
    }
    char path[4096] = "";
    if (t->cache) {
        abrdf_huang_table_build(p, t->sizes, 0, 0, v); /* the header alone */
        if (table_file(t->cache, v, path, sizeof path)) {
            v[0] = 0.0; /* no header: never prepared for anyone */
            snprintf(err, err_size, "--hair-table-cache %s: the directory's name is too long",
                     t->cache);
            return -1;
        }
        if (table_read(path, v, n, p, t->sizes, out)) {
            ++t->read;
            return 0;
        }
    }
    if (t->progress)
        fprintf(stderr, "tabulating huang of %s: %d x %d x %d x %d nodes, %d shift sets\n", what,
                t->sizes[0], t->sizes[1], t->sizes[0], t->sizes[2], t->sizes[3]);
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    st = table_build(t, p, rows, v);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    t->build_seconds += (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
    if (st == ABRDF_OK) st = abrdf_prepare_huang_table(p, t->sizes, v, out);
    if (st != ABRDF_OK) {
        v[0] = 0.0; /* no header: never prepared for anyone */
        snprintf(err, err_size, "%s: huang table: %s", what, abrdf_strerror(st));
        return -1;
    }
    ++t->built;
    if (path[0]) table_write(path, v, n, what);
    return 0;
}

const double *hair_store_table(const hair_store *t, const abrdf_params *p)
{
    abrdf_prepared unused;
    for (int i = 0; i < t->count; ++i)
        if (abrdf_prepare_huang_table(p, t->sizes, t->values[i], &unused) == ABRDF_OK)
            return t->values[i];
    return NULL;
}

/* ---- what an evaluation costs ----------------------------------------------------------- */

double hair_store_cost(const abrdf_prepared *table, const abrdf_params *p, const abrdf_costs *costs)
{
    return budget_prepared_cost(table, ABRDF_HUANG, p, costs);
}

/* ---- the budget against a table -------------------------------------------------------- */

int hair_store_budget(hair_store *t, const abrdf_material *m, double max_nmse,
                      const abrdf_costs *costs, const abrdf_view *view, const char *what,
                      budget_result *out, char *err, size_t err_size)
{
    abrdf_selection ps;
    abrdf_params pp;
    abrdf_selection_init(&ps);
    abrdf_params_init(ABRDF_MODEL_NONE, &pp);
    if (abrdf_select(m, ABRDF_GOAL_PHOTOREAL, NULL, NULL, &ps, &pp, NULL, NULL) != ABRDF_OK ||
        ps.diffuse != ABRDF_MODEL_NONE || ps.specular != ABRDF_HUANG)
        return 0;
    abrdf_prepared ref;
    if (hair_store_get(t, &pp, what, &ref, err, err_size)) {
        memset(out, 0, sizeof *out); /* budget_result_free's contract */
        out->trace = (select_trace)SELECT_TRACE_INIT;
        return -1;
    }
    double cost = hair_store_cost(&ref, &pp, costs);
    if (!(cost >= 0.0)) return 0;
    return budget_run_to(m, max_nmse, 0, costs, view, &ref, cost, out, err, err_size) ? -1 : 1;
}
