/* fit_to.c - `abrdf fit --to FILE MODEL | --all`: analytic models fitted to a measured file
 * (abrdf_fit_to against the table prepared as the `measured` model; docs/MEASURED.md,
 * "Fitting measured data"): the fitted parameters, the cosine-weighted relative L2, log and
 * cube-root errors, the predicted image NMSE on the default sphere and its Table-8 class, the
 * cost in the built-in table and the time; with --all one row per specular lobe, like the
 * tables of Ngan, Durand, Matusik (EGSR 2005). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "budget_run.h"
#include "cli.h"
#include "measured_ref.h"
#include "metrics.h"

#define CMD "fit"
#define NONE ABRDF_MODEL_NONE
/* --all keeps Lambert under a lobe unless another diffuse term lowers the predicted NMSE by
 * more than this fraction: a smaller gain does not pay for a dearer term. */
#define DIFFUSE_GAIN 0.05

static int usage(void)
{
    printf("usage: abrdf fit --to FILE MODEL [--diffuse MODEL|none] [--metric l2|log|cbrt|auto]\n"
           "                 [--resolution 0..5] [--json]\n"
           "       abrdf fit --to FILE --all [--metric ...] [--resolution 0..5] [--json]\n\n"
           "Fits analytic models to a measured BRDF file (FILE.binary, FILE.bsdf; abrdf_fit_to,\n"
           "docs/MEASURED.md, \"Fitting measured data\"), the table being the photoreal\n"
           "reference. Prints the fitted parameters, the relative L2, log and cube-root errors of\n"
           "f cos on the fit's direction set, the image NMSE predicted on the default sphere with\n"
           "its Table-8 class, the cost (ns/eval, the built-in table) and the time.\n"
           "  MODEL              the model to fit; a specular lobe gets a diffuse term\n"
           "  --diffuse MODEL    the diffuse term under a specular MODEL (default lambert;\n"
           "                     none: the lobe alone)\n"
           "  --all              every general candidate: each specular lobe over lambert, or\n"
           "                     over disney_diffuse / oren_nayar where that lowers the predicted\n"
           "                     NMSE by more than 5 %%; sorted by predicted NMSE\n"
           "  --metric           l2 (default), log, cbrt, or auto (each; the best predicted)\n"
           "  --resolution N     direction-set density, 1 (coarse) to 5; 0: default\n"
           "  --json             machine-readable output\n");
    return 0;
}

typedef struct to_args {
    const char *file, *model, *diffuse;
    int all, json;
    abrdf_fit_options opt;
} to_args;

static int parse(int argc, char **argv, to_args *a)
{
    memset(a, 0, sizeof *a);
    abrdf_fit_options_init(&a->opt);
    for (int i = 1; i < argc; ++i) {
        const char *o = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(o, "--all")) {
            a->all = 1;
            continue;
        }
        if (!strcmp(o, "--json")) {
            a->json = 1;
            continue;
        }
        if (o[0] != '-') {
            if (a->model) return cli_fail(CMD, "one MODEL at a time ('%s' and '%s')", a->model, o);
            a->model = o;
            continue;
        }
        if (!v) return cli_fail(CMD, "%s needs a value (abrdf fit --help)", o);
        ++i;
        if (!strcmp(o, "--to")) {
            if (a->file) return cli_fail(CMD, "one --to FILE at a time");
            a->file = v;
        } else if (!strcmp(o, "--diffuse")) {
            a->diffuse = v;
        } else if (!strcmp(o, "--metric")) {
            if (abrdf_fit_metric_find(v, &a->opt.metric) != ABRDF_OK)
                return cli_fail(CMD, "--metric needs l2, log, cbrt or auto, got '%s'", v);
        } else if (!strcmp(o, "--resolution")) {
            long r;
            if (!cli_parse_int(v, 0, 5, &r))
                return cli_fail(CMD, "--resolution needs a whole number in [0, 5], got '%s'", v);
            a->opt.resolution = (int)r;
        } else {
            return cli_fail(CMD, "unknown option '%s' with --to (abrdf fit --help)", o);
        }
    }
    if (!a->file) return cli_fail(CMD, "--to needs a FILE");
    if (a->all && (a->model || a->diffuse))
        return cli_fail(CMD, "--all fits every candidate: no MODEL or --diffuse with it");
    if (!a->all && !a->model)
        return cli_fail(CMD, "give a MODEL to fit, or --all (abrdf fit --help)");
    return 0;
}

/* MODEL and --diffuse into the pair; 0 or a usage error. */
static int pair_of(const to_args *a, abrdf_model pair[2])
{
    if (cli_model(CMD, a->model, &pair[1])) return CLI_EXIT_USAGE;
    const abrdf_model_info *mi = abrdf_model_get(pair[1]);
    if (mi->needs & ABRDF_NEEDS_TABLE)
        return cli_fail(CMD, "%s is the table itself: fit an analytic model to it", mi->name);
    int specular = (mi->props & ABRDF_PROP_SPECULAR) && !(mi->props & ABRDF_PROP_DIFFUSE);
    pair[0] = specular ? ABRDF_LAMBERT : NONE;
    if (!a->diffuse) return 0;
    if (!strcmp(a->diffuse, "none")) {
        pair[0] = NONE;
        return 0;
    }
    if (!specular)
        return cli_fail(CMD, "--diffuse goes under a specular lobe; %s is not one", mi->name);
    if (cli_model(CMD, a->diffuse, &pair[0])) return CLI_EXIT_USAGE;
    if (!(abrdf_model_get(pair[0])->props & ABRDF_PROP_DIFFUSE) ||
        (abrdf_model_get(pair[0])->needs & ABRDF_NEEDS_TABLE))
        return cli_fail(CMD,
                        "--diffuse needs a diffuse model (lambert, disney_diffuse, ...), "
                        "got '%s'",
                        a->diffuse);
    return 0;
}

/* A fit's failure: the library's reason; 2 for what it was given, 1 for anything else. */
static int fit_failed(int st, const measured_fit *f)
{
    cli_fail(CMD, "%s", f->res.message);
    return st == ABRDF_E_MODEL || st == ABRDF_E_RANGE ? CLI_EXIT_USAGE : 1;
}

static void json_reference(const measured_ref *r)
{
    printf("{\"file\": ");
    cli_json_string(stdout, r->path);
    printf(", \"format\": ");
    cli_json_string(stdout, r->format);
    printf(", \"grid\": [%d, %d, %d], \"unmeasured\": %zu, \"read_seconds\": %.4f}",
           r->table.n_theta_h, r->table.n_theta_d, r->table.n_phi_d, r->table.unmeasured,
           r->read_secs);
}

static void json_model(abrdf_model m)
{
    if (m == NONE)
        printf("null");
    else
        cli_json_string(stdout, abrdf_model_get(m)->name);
}

/* One fit as JSON members (no braces). */
static void json_fit(const measured_fit *f)
{
    const abrdf_fit_result *r = &f->res;
    printf("\"diffuse\": ");
    json_model(f->diffuse);
    printf(", \"specular\": ");
    json_model(f->specular);
    printf(", \"metric\": \"%s\", \"params\": ", abrdf_fit_metric_name(r->metric));
    budget_params_json(stdout, f->diffuse, f->specular, &f->params);
    const char *keys[6] = {"rel_l2", "rel_log", "rel_cbrt", "max_rel_pct", "max_abs", "nmse_pred"};
    const double vals[6] = {r->rel_l2,      r->rel_log, r->rel_cbrt,
                            r->max_rel_pct, r->max_abs, r->nmse_pred};
    for (int k = 0; k < 6; ++k) {
        printf(", \"%s\": ", keys[k]);
        cli_json_number(stdout, vals[k]);
    }
    printf(", \"class\": \"%s\", \"cost\": ", abrdf_nmse_class(r->nmse_pred));
    if (f->cost >= 0.0)
        printf("%.6g", f->cost);
    else
        printf("null");
    printf(", \"directions\": %d, \"evals\": %d, \"seconds\": %.4f", r->directions, r->evals,
           f->secs);
}

/* ---- one model ----------------------------------------------------------------------------- */

static int fit_one(const to_args *a, const measured_ref *ref, const abrdf_costs *costs, void *work,
                   size_t ws)
{
    abrdf_model pair[2];
    int rc = pair_of(a, pair);
    if (rc) return rc;
    measured_fit f;
    int st = measured_ref_fit(ref, pair[0], pair[1], &a->opt, costs, work, ws, &f);
    if (st != ABRDF_OK) return fit_failed(st, &f);
    double bp = abrdf_costs_get(costs, ABRDF_BLINN_PHONG);
    if (a->json) {
        printf("{\"reference\": ");
        json_reference(ref);
        printf(",\n ");
        json_fit(&f);
        printf(", \"cost_unit\": ");
        cli_json_string(stdout, costs->unit);
        printf(", \"cost_vs_blinn_phong\": ");
        if (f.cost >= 0.0 && bp > 0.0)
            printf("%.4g", f.cost / bp);
        else
            printf("null");
        printf("}\n");
        return 0;
    }
    char desc[1400], nm[128];
    measured_ref_describe(ref, desc, sizeof desc);
    budget_pair_name(f.diffuse, f.specular, NULL, nm, sizeof nm);
    const abrdf_fit_result *r = &f.res;
    printf("reference   %s, read in %.3f s\n", desc, ref->read_secs);
    printf("candidate   %s (fitted, metric %s)\n", nm, abrdf_fit_metric_name(r->metric));
    printf("params      ");
    budget_params_text(stdout, f.diffuse, f.specular, &f.params);
    printf("\nrel L2      %.4g   (cosine-weighted, of f cos over %d direction pairs)\n", r->rel_l2,
           r->directions);
    printf("rel log     %.4g   (of log(1 + f cos), exact on the same set)\n", r->rel_log);
    printf("rel cbrt    %.4g   (of (f cos)^(1/3), exact on the same set)\n", r->rel_cbrt);
    printf("highlight   %.4g%%  (largest relative error in the table's highlight zone)\n",
           r->max_rel_pct);
    printf("image NMSE  %.4g   (predicted on the default sphere: %s)\n", r->nmse_pred,
           abrdf_nmse_class(r->nmse_pred));
    if (f.cost >= 0.0)
        printf("cost        %.3g ns/eval, %.2f x blinn_phong  [%s]\n", f.cost,
               bp > 0.0 ? f.cost / bp : NAN, costs->unit);
    else
        printf("cost        unknown in the built-in table\n");
    printf("fit time    %.3f s (%d parameters, %d objective evaluations)\n", f.secs, r->fitted,
           r->evals);
    return 0;
}

/* ---- every candidate ----------------------------------------------------------------------- */

/* One row: a specular lobe over the diffuse term kept, and what the others predicted. */
typedef struct all_row {
    measured_fit f;
    double tried[3]; /* predicted NMSE over each of measured_ref_diffuse */
} all_row;

static int row_order(const void *x, const void *y)
{
    const all_row *a = x, *b = y;
    double na = a->f.res.nmse_pred, nb = b->f.res.nmse_pred;
    if (na != nb) return na < nb ? -1 : 1;
    return (a->f.cost > b->f.cost) - (a->f.cost < b->f.cost);
}

static int fit_all(const to_args *a, const measured_ref *ref, const abrdf_costs *costs, void *work,
                   size_t ws)
{
    enum { ROWS_MAX = 32 };
    all_row rows[ROWS_MAX];
    int n = measured_ref_specular_count, fits = 0;
    double t0 = measured_ref_wall();
    for (int i = 0; i < n && i < ROWS_MAX; ++i) {
        all_row *row = &rows[i];
        for (int d = 0; d < measured_ref_diffuse_count; ++d) {
            measured_fit f;
            int st = measured_ref_fit(ref, measured_ref_diffuse[d], measured_ref_specular[i],
                                      &a->opt, costs, work, ws, &f);
            if (st != ABRDF_OK) return fit_failed(st, &f);
            ++fits;
            row->tried[d] = f.res.nmse_pred;
            /* Lambert unless another term gains more than DIFFUSE_GAIN on the best so far */
            if (d == 0 || f.res.nmse_pred < (1.0 - DIFFUSE_GAIN) * row->f.res.nmse_pred) row->f = f;
        }
    }
    double secs = measured_ref_wall() - t0;
    qsort(rows, (size_t)n, sizeof rows[0], row_order);
    if (a->json) {
        printf("{\"reference\": ");
        json_reference(ref);
        printf(", \"metric\": \"%s\", \"fits\": %d, \"seconds\": %.3f, \"cost_unit\": ",
               abrdf_fit_metric_name(a->opt.metric), fits, secs);
        cli_json_string(stdout, costs->unit);
        printf(",\n \"candidates\": [");
        for (int i = 0; i < n; ++i) {
            printf("%s\n  {", i ? "," : "");
            json_fit(&rows[i].f);
            printf(", \"diffuse_tried\": {");
            for (int d = 0; d < measured_ref_diffuse_count; ++d) {
                printf("%s\"%s\": ", d ? ", " : "", abrdf_model_get(measured_ref_diffuse[d])->name);
                cli_json_number(stdout, rows[i].tried[d]);
            }
            printf("}}");
        }
        printf("\n]}\n");
        return 0;
    }
    char desc[1400], nm[128];
    measured_ref_describe(ref, desc, sizeof desc);
    printf("reference  %s, read in %.3f s\n", desc, ref->read_secs);
    printf("fits       %d specular lobes x %d diffuse terms, metric %s: %d fits in %.2f s; a row\n"
           "           keeps lambert unless disney_diffuse or oren_nayar predicts a NMSE lower by\n"
           "           more than %.0f %%; sorted by predicted image NMSE (the default sphere)\n",
           n, measured_ref_diffuse_count, abrdf_fit_metric_name(a->opt.metric), fits, secs,
           100.0 * DIFFUSE_GAIN);
    printf("  %-32s %9s %9s %9s %10s  %-12s %8s  %s\n", "model", "rel L2", "rel log", "rel cbrt",
           "NMSE", "class", "ns/eval", "fitted");
    for (int i = 0; i < n; ++i) {
        const measured_fit *f = &rows[i].f;
        budget_pair_name(f->diffuse, f->specular, NULL, nm, sizeof nm);
        printf("  %-32s %9.3g %9.3g %9.3g %10.3g  %-12s %8.3g  ", nm, f->res.rel_l2, f->res.rel_log,
               f->res.rel_cbrt, f->res.nmse_pred, abrdf_nmse_class(f->res.nmse_pred), f->cost);
        budget_params_text(stdout, f->diffuse, f->specular, &f->params);
        printf("\n");
    }
    printf("cost: %s\n", costs->unit);
    return 0;
}

int fit_to_run(int argc, char **argv)
{
    for (int i = 1; i < argc; ++i)
        if (cli_is_help(argv[i])) return usage();
    to_args a;
    int rc = parse(argc, argv, &a);
    abrdf_model pair[2];
    if (!rc && !a.all) rc = pair_of(&a, pair); /* a bad MODEL before the file is read */
    if (rc) return rc;
    measured_ref ref;
    if ((rc = measured_ref_load(CMD, a.file, &ref))) return rc;
    abrdf_costs costs;
    abrdf_costs_builtin(&costs);
    size_t ws = abrdf_fit_workspace_size(&a.opt, NULL);
    void *work = malloc(ws);
    if (!work) {
        measured_ref_free(&ref);
        return cli_fail(CMD, "out of memory (%zu bytes of workspace)", ws);
    }
    rc = a.all ? fit_all(&a, &ref, &costs, work, ws) : fit_one(&a, &ref, &costs, work, ws);
    free(work);
    measured_ref_free(&ref);
    return rc;
}
