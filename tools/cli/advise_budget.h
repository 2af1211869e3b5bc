/* advise_budget.h - the budget mode of `abrdf advise` (advise_budget.c). */
#ifndef ABRDF_ADVISE_BUDGET_H
#define ABRDF_ADVISE_BUDGET_H

#include "abrdf_fit.h"
#include "hair_store.h"
#include "materials.h"

/* The budget mode for material m (e: its table entry, or NULL for explicit values): the
 * choice within max_nmse, or with pareto the cost/error front; plot (may be NULL) receives
 * the front as SVG. costs NULL: the built-in table. tables (NULL: none): a hair material's
 * budget against its huang table from this store (hair_store_budget). Returns the exit
 * status. */
int advise_budget(const abrdf_material *m, const mat_entry *e, double max_nmse,
                  const abrdf_costs *costs, int json, int pareto, const char *plot,
                  hair_store *tables);

#endif
