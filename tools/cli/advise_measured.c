/* advise_measured.c - `abrdf advise --measured FILE --budget CLASS|NMSE`: the budget mode
 * (docs/SELECTION.md, "The budget mode") with a measured table as the photoreal reference:
 * every general candidate fitted to the table (abrdf_fit_to, metric auto, as the budget mode
 * fits), its image NMSE predicted against it, its cost read from the built-in table; the
 * cheapest within the budget wins, costs within 15 % of it counting as equal (of those, the
 * lowest predicted NMSE), as abrdf_select_budget decides. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "budget_run.h"
#include "cli.h"
#include "measured_ref.h"
#include "metrics.h"

#define CMD "advise"
#define NONE ABRDF_MODEL_NONE
/* abrdf_select_budget's COST_TIE (budget.c): calibrations move cost ratios by up to 15 %. */
#define COST_TIE 0.15
#define CAND_MAX 96

/* The candidates: each specular lobe alone and over each diffuse term, and each diffuse term
 * alone (the general class's pairs of the budget mode). */
static int candidate(int k, abrdf_model *d, abrdf_model *s)
{
    int nd = measured_ref_diffuse_count + 1, ns = measured_ref_specular_count;
    if (k < ns * nd) {
        int i = k / nd, j = k % nd;
        *s = measured_ref_specular[i];
        *d = j == 0 ? NONE : measured_ref_diffuse[j - 1];
        return 1;
    }
    k -= ns * nd;
    if (k < measured_ref_diffuse_count) {
        *d = NONE;
        *s = measured_ref_diffuse[k];
        return 1;
    }
    return 0;
}

static const char *class_name(double max)
{
    static const char *const names[3] = {"none", "slight", "noticeable"};
    const double *c = abrdf_select_rules_get()->nmse_class_max;
    for (int i = 0; i < 3; ++i)
        if (max == c[i]) return names[i];
    return NULL;
}

static void json_model(abrdf_model m)
{
    if (m == NONE)
        printf("null");
    else
        cli_json_string(stdout, abrdf_model_get(m)->name);
}

static void json_cost(double c)
{
    if (c >= 0.0)
        printf("%.6g", c);
    else
        printf("null");
}

/* A candidate's line of the trace, in the words of the budget mode's. */
static void candidate_text(const measured_fit *f, double max, char *buf, size_t size)
{
    char nm[128], cs[48];
    budget_pair_name(f->diffuse, f->specular, NULL, nm, sizeof nm);
    int within = f->res.nmse_pred < max;
    if (f->cost >= 0.0)
        snprintf(cs, sizeof cs, "%.3g ns/eval", f->cost);
    else
        snprintf(cs, sizeof cs, "cost unknown");
    snprintf(buf, size, "%s: NMSE %.3g %s %g (%s), rel L2 %.3g, highlight %.3g%%, %s: %s", nm,
             f->res.nmse_pred, within ? "<" : ">=", max, abrdf_nmse_class(f->res.nmse_pred),
             f->res.rel_l2, f->res.max_rel_pct, cs,
             !within          ? "over the budget"
             : f->cost >= 0.0 ? "within the budget"
                              : "within, but cannot be ranked");
}

static void print_json(const measured_ref *ref, double max, const measured_fit *c, int n, int win,
                       double secs, const abrdf_costs *costs)
{
    const char *bc = class_name(max);
    printf("{\"measured\": ");
    cli_json_string(stdout, ref->path);
    printf(", \"format\": ");
    cli_json_string(stdout, ref->format);
    printf(", \"grid\": [%d, %d, %d], \"unmeasured\": %zu,\n \"budget\": {\"max_nmse\": %.10g, "
           "\"class\": ",
           ref->table.n_theta_h, ref->table.n_theta_d, ref->table.n_phi_d, ref->table.unmeasured,
           max);
    if (bc)
        printf("\"%s\"", bc);
    else
        printf("null");
    printf("},\n \"reference\": {\"model\": \"measured\", \"file\": ");
    cli_json_string(stdout, ref->path);
    printf(", \"cost\": null},\n \"diffuse\": ");
    json_model(win >= 0 ? c[win].diffuse : NONE);
    printf(", \"specular\": ");
    if (win >= 0)
        json_model(c[win].specular);
    else
        printf("\"measured\"");
    printf(", \"params\": ");
    if (win >= 0)
        budget_params_json(stdout, c[win].diffuse, c[win].specular, &c[win].params);
    else
        printf("null");
    printf(",\n \"error\": {\"nmse_pred\": ");
    cli_json_number(stdout, win >= 0 ? c[win].res.nmse_pred : 0.0);
    printf(", \"class\": \"%s\", \"rel_l2\": ",
           abrdf_nmse_class(win >= 0 ? c[win].res.nmse_pred : 0.0));
    cli_json_number(stdout, win >= 0 ? c[win].res.rel_l2 : 0.0);
    printf("},\n \"cost\": {\"total\": ");
    json_cost(win >= 0 ? c[win].cost : -1.0);
    printf(", \"unit\": ");
    cli_json_string(stdout, costs->unit);
    printf("}, \"seconds\": %.3f,\n \"candidates\": [", secs);
    for (int i = 0; i < n; ++i) {
        printf("%s\n  {\"diffuse\": ", i ? "," : "");
        json_model(c[i].diffuse);
        printf(", \"specular\": ");
        json_model(c[i].specular);
        printf(", \"metric\": \"%s\", \"params\": ", abrdf_fit_metric_name(c[i].res.metric));
        budget_params_json(stdout, c[i].diffuse, c[i].specular, &c[i].params);
        printf(", \"nmse_pred\": ");
        cli_json_number(stdout, c[i].res.nmse_pred);
        printf(", \"class\": \"%s\", \"rel_l2\": ", abrdf_nmse_class(c[i].res.nmse_pred));
        cli_json_number(stdout, c[i].res.rel_l2);
        printf(", \"rel_log\": ");
        cli_json_number(stdout, c[i].res.rel_log);
        printf(", \"rel_cbrt\": ");
        cli_json_number(stdout, c[i].res.rel_cbrt);
        printf(", \"cost\": ");
        json_cost(c[i].cost);
        printf(", \"within\": %s}",
               c[i].res.nmse_pred < max && c[i].cost >= 0.0 ? "true" : "false");
    }
    printf("\n]}\n");
}

static void print_human(const measured_ref *ref, double max, const measured_fit *c, int n, int win,
                        double secs, const abrdf_costs *costs)
{
    char desc[1400], nm[128], line[512];
    const char *bc = class_name(max);
    measured_ref_describe(ref, desc, sizeof desc);
    printf("measured   %s\n", desc);
    printf("reference  measured (the table: the photoreal reference), cost unknown\n");
    printf("budget     predicted image NMSE < %g%s%s%s\n", max, bc ? " (" : "", bc ? bc : "",
           bc ? ")" : "");
    if (win >= 0) {
        const measured_fit *w = &c[win];
        budget_pair_name(w->diffuse, w->specular, NULL, nm, sizeof nm);
        printf("choice     %s\nparams     ", nm);
        budget_params_text(stdout, w->diffuse, w->specular, &w->params);
        printf("\nerror      predicted NMSE %.3g (%s); rel L2 %.3g, highlight %.3g%% against the "
               "table\n",
               w->res.nmse_pred, abrdf_nmse_class(w->res.nmse_pred), w->res.rel_l2,
               w->res.max_rel_pct);
        printf("cost       %.3g ns/eval  [%s]\n", w->cost, costs->unit);
    } else {
        printf(
            "choice     measured (no fitted candidate is within the budget: the table itself)\n");
    }
    printf("candidates (%d, %.2f s):\n", n, secs);
    printf("  %-36s %10s %11s  %-12s %s\n", "model", "cost", "NMSE", "class", "fitted");
    for (int i = 0; i < n; ++i) {
        budget_pair_name(c[i].diffuse, c[i].specular, NULL, nm, sizeof nm);
        printf("  %-36s %10.3g %11.3g  %-12s ", nm, c[i].cost, c[i].res.nmse_pred,
               abrdf_nmse_class(c[i].res.nmse_pred));
        budget_params_text(stdout, c[i].diffuse, c[i].specular, &c[i].params);
        printf("\n");
    }
    printf("why:\n");
    printf("   1. budget: image NMSE < %g against the reference measured (%s, the photoreal "
           "reference), predicted on an analytic sphere; fits by the auto metric on %d "
           "direction pairs\n",
           max, ref->path, n ? c[0].res.directions : 0);
    for (int i = 0; i < n; ++i) {
        candidate_text(&c[i], max, line, sizeof line);
        printf("  %2d. %s\n", i + 2, line);
    }
    if (win >= 0) {
        budget_pair_name(c[win].diffuse, c[win].specular, NULL, nm, sizeof nm);
        printf("  %2d. %s: the cheapest within NMSE < %g (costs within %.0f %% of it counted "
               "equal, the lowest predicted NMSE of those): %.3g ns/eval, predicted NMSE %.3g "
               "(%s)\n",
               n + 2, nm, max, 100.0 * COST_TIE, c[win].cost, c[win].res.nmse_pred,
               abrdf_nmse_class(c[win].res.nmse_pred));
    } else {
        printf("  %2d. measured: no fitted candidate with a known cost is within NMSE < %g: "
               "the table itself\n",
               n + 2, max);
    }
}

int advise_measured(const char *path, double max_nmse, int json)
{
    measured_ref ref;
    int rc = measured_ref_load(CMD, path, &ref);
    if (rc) return rc;
    abrdf_costs costs;
    abrdf_costs_builtin(&costs);
    abrdf_fit_options opt;
    abrdf_fit_options_init(&opt);
    opt.metric = ABRDF_FIT_AUTO;
    size_t ws = abrdf_fit_workspace_size(&opt, NULL);
    void *work = malloc(ws);
    measured_fit *c = malloc(CAND_MAX * sizeof *c);
    if (!work || !c) {
        free(work);
        free(c);
        measured_ref_free(&ref);
        return cli_fail(CMD, "out of memory");
    }
    double t0 = measured_ref_wall(), cheapest = INFINITY;
    int n = 0;
    abrdf_model d, s;
    for (int k = 0; n < CAND_MAX && candidate(k, &d, &s); ++k, ++n) {
        int st = measured_ref_fit(&ref, d, s, &opt, &costs, work, ws, &c[n]);
        if (st != ABRDF_OK) {
            fprintf(stderr, "abrdf %s: %s\n", CMD, c[n].res.message);
            free(work);
            free(c);
            measured_ref_free(&ref);
            return 1;
        }
        if (c[n].res.nmse_pred < max_nmse && c[n].cost >= 0.0 && c[n].cost < cheapest)
            cheapest = c[n].cost;
    }
    double secs = measured_ref_wall() - t0;
    int win = -1;
    for (int i = 0; i < n; ++i) {
        if (!(c[i].res.nmse_pred < max_nmse) || !(c[i].cost >= 0.0) ||
            c[i].cost > cheapest * (1.0 + COST_TIE))
            continue;
        if (win < 0 || c[i].res.nmse_pred < c[win].res.nmse_pred ||
            (c[i].res.nmse_pred == c[win].res.nmse_pred && c[i].cost < c[win].cost))
            win = i;
    }
    if (json)
        print_json(&ref, max_nmse, c, n, win, secs, &costs);
    else
        print_human(&ref, max_nmse, c, n, win, secs, &costs);
    free(work);
    free(c);
    measured_ref_free(&ref);
    return 0;
}
