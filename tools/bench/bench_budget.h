/* bench_budget.h - `abrdf bench --budget`: the budget mode's payoff on the mixed scene
 * (bench_budget.c, docs/BENCHMARKS.md). */
#ifndef ABRDF_BENCH_BUDGET_H
#define ABRDF_BENCH_BUDGET_H
#include <stdio.h>

#include "hair_store.h"

/* Photoreal vs the budget mode per Table-8 class on scenes/mixed.scene: render time ratios
 * (median of `reps` interleaved renders), image NMSE and each material's NMSE over its own
 * pixels, written as a table (json 0) or a JSON object to out. size: image width (0 = the
 * scene's; the height keeps the aspect). tables (NULL: none): huang from its tables in this
 * store, photoreal's hair and the budgets' reference, beside photoreal with huang per call.
 * Returns 0, or 1 with a message on stderr. */
int bench_budget_report(FILE *out, int json, int size, int spp, int reps, int threads,
                        hair_store *tables);

#endif
