/* budget_run.c - the budget mode as the tools run it (budget_run.h). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "budget_run.h"
#include "cli_args.h"

int budget_parse(const char *s, double *max_nmse, char *err, size_t err_size)
{
    if (!s || !*s) {
        snprintf(err, err_size, "the budget is empty (none, slight, noticeable or a number)");
        return -1;
    }
    if (abrdf_budget_class_find(s, max_nmse) == ABRDF_OK) return 0;
    double v;
    if (!cli_parse_double(s, &v)) {
        snprintf(err, err_size,
                 "unknown budget class '%s' (none, slight, noticeable, or an NMSE in (0, 1])", s);
        return -1;
    }
    if (!(v > 0.0 && v <= 1.0)) {
        snprintf(err, err_size, "budget NMSE %s is not in (0, 1]", s);
        return -1;
    }
    *max_nmse = v;
    return 0;
}

int budget_run(const abrdf_material *m, double max_nmse, const abrdf_costs *costs,
               const abrdf_view *view, budget_result *out, char *err, size_t err_size)
{
    return budget_run_at(m, max_nmse, 0, costs, view, out, err, err_size);
}

int budget_run_at(const abrdf_material *m, double max_nmse, int resolution,
                  const abrdf_costs *costs, const abrdf_view *view, budget_result *out, char *err,
                  size_t err_size)
{
    return budget_run_to(m, max_nmse, resolution, costs, view, NULL, -1.0, out, err, err_size);
}

int budget_run_to(const abrdf_material *m, double max_nmse, int resolution,
                  const abrdf_costs *costs, const abrdf_view *view, const abrdf_prepared *reference,
                  double reference_cost, budget_result *out, char *err, size_t err_size)
{
    memset(out, 0, sizeof *out);
    out->trace = (select_trace)SELECT_TRACE_INIT;
    abrdf_selection_init(&out->sel);
    abrdf_params_init(ABRDF_MODEL_NONE, &out->params);
    abrdf_budget b;
    abrdf_budget_init(&b);
    b.max_nmse = max_nmse;
    b.resolution = resolution;
    b.view = view;
    b.reference = reference;
    b.reference_cost = reference_cost;
    size_t ws = abrdf_fit_workspace_size(NULL, view);
    if (!ws) {
        snprintf(err, err_size, "the prediction's view is invalid");
        return -1;
    }
    void *work = malloc(ws);
    if (!work) {
        snprintf(err, err_size, "out of memory (%zu bytes of workspace)", ws);
        return -1;
    }
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    int st = abrdf_select_budget(m, &b, costs, &out->sel, &out->params, select_trace_keep,
                                 &out->trace, work, ws);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    out->seconds = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
    out->prepared = reference != NULL;
    free(work);
    if (st != ABRDF_OK) {
        snprintf(err, err_size, "%s", out->sel.message);
        budget_result_free(out);
        return -1;
    }
    if (out->trace.lost) {
        snprintf(err, err_size, "out of memory");
        budget_result_free(out);
        return -1;
    }
    return 0;
}

void budget_result_free(budget_result *r) { select_trace_free(&r->trace); }

int budget_candidates(const budget_result *r, const abrdf_select_step **out, int max)
{
    int n = 0;
    for (int i = 0; i < r->trace.count && n < max; ++i)
        if (r->trace.steps[i].kind == ABRDF_STEP_FIT) out[n++] = &r->trace.steps[i];
    return n;
}

int budget_pareto(const abrdf_select_step *const *cand, int count, int *front)
{
    int n = 0;
    for (int i = 0; i < count; ++i)
        if (cand[i]->cost >= 0.0 && isfinite(cand[i]->value)) front[n++] = i;
    /* by cost, then by error */
    for (int a = 1; a < n; ++a)
        for (int b = a; b > 0; --b) {
            const abrdf_select_step *x = cand[front[b]], *y = cand[front[b - 1]];
            if (x->cost < y->cost || (x->cost == y->cost && x->value < y->value)) {
                int t = front[b];
                front[b] = front[b - 1];
                front[b - 1] = t;
            } else {
                break;
            }
        }
    int k = 0;
    double best = INFINITY;
    for (int a = 0; a < n; ++a)
        if (cand[front[a]]->value < best) {
            best = cand[front[a]]->value;
            front[k++] = front[a];
        }
    return k;
}

void budget_pair_name(abrdf_model diffuse, abrdf_model specular, const abrdf_params *p, char *buf,
                      size_t size)
{
    const abrdf_model_info *d = abrdf_model_get(diffuse), *s = abrdf_model_get(specular);
    if (!d)
        snprintf(buf, size, "%s", s ? s->name : "none");
    else
        snprintf(buf, size, "%s + %s", d->name, s ? s->name : "none");
    /* the whole-number parameters but a layer count are quadratures (huang's grids) */
    const abrdf_model_info *m[2] = {d, s};
    int any = 0;
    for (int l = 0; l < 2 && p; ++l)
        for (int k = 0; m[l] && k < m[l]->param_count; ++k) {
            const abrdf_param_info *pi = abrdf_param_get(m[l]->params[k].id);
            double v[3];
            if (pi->kind != ABRDF_PARAM_INT || !strcmp(pi->name, "layer_count") ||
                abrdf_param_read(p, m[l]->params[k].id, v) != 1 || v[0] == m[l]->params[k].def)
                continue;
            size_t len = strlen(buf);
            snprintf(buf + len, size - len, "%s%s %g", any++ ? ", " : " (", pi->name, v[0]);
        }
    if (any) {
        size_t len = strlen(buf);
        snprintf(buf + len, size - len, ")");
    }
}

static int pair_reads(abrdf_model d, abrdf_model s, int id)
{
    const abrdf_model_info *m[2] = {abrdf_model_get(d), abrdf_model_get(s)};
    for (int l = 0; l < 2; ++l)
        for (int k = 0; m[l] && k < m[l]->param_count; ++k)
            if (m[l]->params[k].id == id) return 1;
    return 0;
}

void budget_params_json(FILE *f, abrdf_model diffuse, abrdf_model specular, const abrdf_params *p)
{
    int first = 1;
    fprintf(f, "{");
    for (int id = 0; id < abrdf_param_count(); ++id) {
        if (!pair_reads(diffuse, specular, id)) continue;
        double v[3];
        int n = abrdf_param_read(p, id, v);
        fprintf(f, "%s\"%s\": ", first ? "" : ", ", abrdf_param_get(id)->name);
        if (n == 3)
            fprintf(f, "[%.10g, %.10g, %.10g]", v[0], v[1], v[2]);
        else
            fprintf(f, "%.10g", v[0]);
        first = 0;
    }
    fprintf(f, "}");
}

void budget_params_text(FILE *f, abrdf_model diffuse, abrdf_model specular, const abrdf_params *p)
{
    int first = 1;
    for (int id = 0; id < abrdf_param_count(); ++id) {
        if (!pair_reads(diffuse, specular, id)) continue;
        double v[3];
        int n = abrdf_param_read(p, id, v);
        fprintf(f, "%s%s ", first ? "" : "  ", abrdf_param_get(id)->name);
        if (n == 3 && !(v[0] == v[1] && v[1] == v[2]))
            fprintf(f, "%.4g,%.4g,%.4g", v[0], v[1], v[2]);
        else
            fprintf(f, "%.4g", v[0]);
        first = 0;
    }
}

/* ---- what a prepared form costs ----------------------------------------------------------- */

#define COST_PAIRS 256
#define COST_RUNS 3
#define COST_RUN_SECONDS 0.01

static double cpu_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* A fixed-seed unit direction on the upper hemisphere. */
static void hemisphere(uint64_t *s, float *x, float *y, float *z)
{
    double u[2];
    for (int k = 0; k < 2; ++k) {
        *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
        u[k] = (double)(*s >> 11) * (1.0 / 9007199254740992.0);
    }
    double ct = u[0], st = sqrt(1.0 - ct * ct), ph = 6.283185307179586 * u[1];
    *x = (float)(st * cos(ph)), *y = (float)(st * sin(ph)), *z = (float)ct;
}

/* The median ns per pair of pr on the float batch path over COST_PAIRS fixed pairs; < 0 if
 * it cannot be evaluated. */
static double time_prepared(const abrdf_prepared *pr)
{
    uint64_t seed = 0x2545F4914F6CDD1DULL;
    float d[9][COST_PAIRS];
    for (int i = 0; i < COST_PAIRS; ++i) {
        hemisphere(&seed, &d[0][i], &d[1][i], &d[2][i]);
        hemisphere(&seed, &d[3][i], &d[4][i], &d[5][i]);
    }
    abrdf_batch batch = {COST_PAIRS, d[0], d[1], d[2], d[3], d[4], d[5], d[6], d[7], d[8]};
    if (abrdf_eval_prepared_batch(pr, &batch) != ABRDF_OK) return -1.0;
    double ns[COST_RUNS];
    for (int r = 0; r < COST_RUNS; ++r) {
        long calls = 0;
        double t0 = cpu_seconds(), t;
        do {
            abrdf_eval_prepared_batch(pr, &batch);
            ++calls;
        } while ((t = cpu_seconds() - t0) < COST_RUN_SECONDS);
        ns[r] = 1e9 * t / ((double)calls * COST_PAIRS);
    }
    for (int a = 1; a < COST_RUNS; ++a) /* sort the three */
        for (int c = a; c > 0 && ns[c] < ns[c - 1]; --c) {
            double x = ns[c];
            ns[c] = ns[c - 1], ns[c - 1] = x;
        }
    return ns[COST_RUNS / 2];
}

double budget_prepared_cost(const abrdf_prepared *prepared, abrdf_model model,
                            const abrdf_params *p, const abrdf_costs *costs)
{
    abrdf_costs builtin;
    if (!costs) {
        abrdf_costs_builtin(&builtin);
        costs = &builtin;
    }
    double entry = abrdf_costs_get(costs, model);
    abrdf_params d, q = *p;
    if (abrdf_params_init(model, &d) != ABRDF_OK) return -1.0;
    q.entry_grid = d.entry_grid, q.internal_grid = d.internal_grid; /* huang's as measured */
    abrdf_prepared per_call;
    if (!(entry >= 0.0) || abrdf_prepare(model, &q, &per_call) != ABRDF_OK) return -1.0;
    double tt = time_prepared(prepared), tq = time_prepared(&per_call);
    return tt > 0.0 && tq > 0.0 ? entry * tt / tq : -1.0;
}
