/* budget_run.h - the selection's budget mode (abrdf_select_budget, abrdf_fit.h) as the tools
 * run it: the budget from the command line or a scene ("slight" or a number), the workspace,
 * the kept trace, and the fitted candidates read back from it (for --pareto, tables and the
 * benchmarks). */
#ifndef ABRDF_BUDGET_RUN_H
#define ABRDF_BUDGET_RUN_H

#include <stddef.h>
#include <stdio.h>
#include "abrdf_fit.h"
#include "select_trace.h"

/* "none", "slight", "noticeable" (the paper's Table 8) or a number in (0, 1]. Returns 0, or
 * -1 with a one-line reason in err ("unknown class 'slite' (none, slight, noticeable or a
 * number in (0, 1])", "-1 is not in (0, 1]"). */
int budget_parse(const char *s, double *max_nmse, char *err, size_t err_size);

typedef struct budget_result {
    abrdf_selection sel; /* the choice (diffuse may be ABRDF_MODEL_NONE) */
    abrdf_params params; /* its fitted block */
    select_trace trace;  /* every step: the flowchart's, the reference, each fit, the winner */
    double seconds;      /* wall time of abrdf_select_budget */
    int prepared;        /* the reference was the caller's prepared object (budget_run_to) */
} budget_result;

/* Run the budget mode for m. view NULL: the default sphere; costs NULL: the built-in table.
 * Returns 0, or -1 with the library's message in err (the result is then empty). */
int budget_run(const abrdf_material *m, double max_nmse, const abrdf_costs *costs,
               const abrdf_view *view, budget_result *out, char *err, size_t err_size);
/* The same with the fits' direction-set density (abrdf_budget.resolution, [0, 5]; 0 is the
 * default, which budget_run uses). */
int budget_run_at(const abrdf_material *m, double max_nmse, int resolution,
                  const abrdf_costs *costs, const abrdf_view *view, budget_result *out, char *err,
                  size_t err_size);
/* The same against a caller's prepared reference (abrdf_budget.reference, reference_cost;
 * reference NULL: budget_run_at). */
int budget_run_to(const abrdf_material *m, double max_nmse, int resolution,
                  const abrdf_costs *costs, const abrdf_view *view, const abrdf_prepared *reference,
                  double reference_cost, budget_result *out, char *err, size_t err_size);
void budget_result_free(budget_result *r);

/* The cost of one evaluation of `prepared`, a form of `model` at parameters p (huang from its
 * table), in the unit of costs (NULL: the built-in table), for abrdf_budget.reference_cost:
 * the model's entry there times the ratio of prepared's time to the time of
 * abrdf_prepare(model, p) with huang's grids at their defaults (as the entries are measured),
 * both timed here on the float batch path (fixed pairs, one light per view, the median of 3
 * runs on this thread's CPU clock) so that the ratio, not this machine's speed, carries over.
 * < 0 if either cannot be timed or the model has no entry. */
double budget_prepared_cost(const abrdf_prepared *prepared, abrdf_model model,
                            const abrdf_params *p, const abrdf_costs *costs);

/* The ABRDF_STEP_FIT steps of a result: *count candidates, their steps in trace order (the
 * first is the reference). The pointers stay valid until budget_result_free. */
int budget_candidates(const budget_result *r, const abrdf_select_step **out, int max);

/* Indices (into cand) of the cost/error Pareto front, cheapest first: the candidates with a
 * known cost whose predicted NMSE is below that of every cheaper one. Returns the count. */
int budget_pareto(const abrdf_select_step *const *cand, int count, int *front);

/* Every parameter the pair reads, as a JSON object {"kd": [r, g, b], "n": 80, ...} or as
 * text "kd 0.5,0.4,0.3  n 80" (colours with equal channels as one number). */
void budget_params_json(FILE *f, abrdf_model diffuse, abrdf_model specular, const abrdf_params *p);
void budget_params_text(FILE *f, abrdf_model diffuse, abrdf_model specular, const abrdf_params *p);

/* "lambert + disney_specular" or "kajiya_kay"; with p (may be NULL), a quadrature parameter
 * of the pair away from its model's default follows: "huang (entry_grid 4)". */
void budget_pair_name(abrdf_model diffuse, abrdf_model specular, const abrdf_params *p, char *buf,
                      size_t size);

/* The class name ("none", "slight", "noticeable") of a budget that is a class bound of the
 * paper's Table 8, else NULL. */
const char *budget_class_name(double max_nmse);
/* The ABRDF_STEP_REFERENCE step of a result, or NULL. */
const abrdf_select_step *budget_reference_step(const budget_result *r);
/* The result as the JSON object of `abrdf advise --budget --json` (pareto 0) or `--pareto
 * --json` (pareto 1; max_nmse 1): the choice, its error and cost, the candidates cand[0..n)
 * (budget_candidates) with the front (budget_pareto) flagged, and the trace. material: the
 * material's name or NULL. */
void budget_json(FILE *f, const budget_result *r, const char *material, double max_nmse,
                 const abrdf_select_step *const *cand, int n, const int *front, int nf, int pareto);

#endif
