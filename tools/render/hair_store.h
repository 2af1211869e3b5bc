/* hair_store.h - huang tables as the tools make them (abrdf.h, "huang tabulated"): built with
 * their rows over threads, kept in and read back from a cache directory, and held in one
 * store for a whole command, so that a table the budget mode predicted against (scene_select)
 * is the one the render reads, built once. The store owns its tables; the prepared objects it
 * hands out point into them and are valid until hair_store_free. */
#ifndef ABRDF_HAIR_STORE_H
#define ABRDF_HAIR_STORE_H

#include <stddef.h>
#include "abrdf.h"
#include "abrdf_fit.h"
#include "budget_run.h"

/* The doubles before a table's nodes (abrdf.h, "huang tabulated": a header of 8). */
#define HAIR_STORE_HEADER 8

typedef struct hair_store {
    int sizes[4];      /* every table's sizes (abrdf_huang_table_size) */
    const char *cache; /* a directory keeping each table in a file named by its keys; NULL: none */
    int threads;       /* a build's rows over this many threads (>= 1) */
    int progress;      /* a line on stderr before each build */
    int count, cap;    /* tables held */
    double **values;   /* each table's doubles, header first */
    int built, read;   /* how many were built here, read from the cache */
    double build_seconds; /* wall time of the builds */
} hair_store;

/* An empty store for tables of these sizes. */
void hair_store_init(hair_store *t, const int sizes[4], const char *cache, int threads);
void hair_store_free(hair_store *t);

/* huang at parameters p prepared on its table into *out: a table this store holds for p, else
 * the cache's file, else built (and written to the cache, whole or not at all; a failure to
 * write is a warning on stderr). `what` names the material in messages ("material 'hair'
 * (line 9)"). 0, or -1 with one line in err (sizes out of range, out of memory). */
int hair_store_get(hair_store *t, const abrdf_params *p, const char *what, abrdf_prepared *out,
                   char *err, size_t err_size);

/* The table this store holds for parameters p (its doubles, header first; they stay the
 * store's), or NULL if it holds none: a table hair_store_get built or read for p. */
const double *hair_store_table(const hair_store *t, const abrdf_params *p);

/* What one evaluation of the prepared table costs in the unit of costs (NULL: the built-in
 * table) for the budget mode (abrdf_budget.reference_cost): budget_prepared_cost of huang,
 * its entry times the ratio of the table's time to the quadrature's at the default grids.
 * < 0 if either cannot be timed. */
double hair_store_cost(const abrdf_prepared *table, const abrdf_params *p,
                       const abrdf_costs *costs);

/* The budget mode for material m (budget_run_to) against huang's table from this store, when
 * m's photoreal choice is huang alone: the table got as hair_store_get gets it (`what` names
 * the material in messages), handed over at hair_store_cost's cost. 1 when done (out filled),
 * 0 when m's photoreal choice is another model or the table cannot be timed (nothing done: the
 * caller runs the budget as without tables), -1 with one line in err (out empty). */
int hair_store_budget(hair_store *t, const abrdf_material *m, double max_nmse,
                      const abrdf_costs *costs, const abrdf_view *view, const char *what,
                      budget_result *out, char *err, size_t err_size);

#endif
