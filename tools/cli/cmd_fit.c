/* cmd_fit.c - `abrdf fit`: one model (or diffuse + specular pair) fitted to another with
 * abrdf_fit (abrdf_fit.h, docs/SELECTION.md, "1. The fit"): the fitted parameters, the errors
 * against the reference (relative L2, highlight, absolute), the predicted image NMSE, and
 * whether the budget mode offers the candidate for the reference's surface class
 * (abrdf_budget_candidate).
 * It fits whatever abrdf_fit fits; a refusal is the library's, with its reason. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "abrdf_fit.h"
#include "cli.h"
#include "data_path.h"
#include "materials.h"
#include "measured_ref.h"
#include "metrics.h"

#define CMD "fit"
#define MAX_SETS 64
#define MAX_FILES 8
#define NONE ABRDF_MODEL_NONE

static int usage(void)
{
    printf("usage: abrdf fit (--ref MODEL[+MODEL] [--set NAME=VALUE ...] | --material NAME)\n"
           "                 --candidate MODEL[+MODEL] [--metric l2|log|cbrt|auto]\n"
           "                 [--resolution 0..5] [--materials FILE] [--json]\n"
           "       abrdf fit --to FILE (MODEL [--diffuse MODEL] | --all) [...]: fit to a measured\n"
           "                 file (abrdf fit --to FILE --help)\n\n"
           "Fits the candidate's parameters to the reference (abrdf_fit, docs/SELECTION.md,\n"
           "\"1. The fit\"): cosine-weighted least squares over a direction set covering the\n"
           "hemisphere, the weights (kd, ks, ks*f0) solved in closed form for every trial of the\n"
           "other parameters. Prints the fitted parameters, the relative L2 error of f cos, the\n"
           "highlight zone's largest relative error (Table 2's measure), the largest absolute\n"
           "error (Table 3's) and the image NMSE predicted on an analytic sphere.\n"
           "  --ref M[+M]        the reference: one model, or diffuse+specular (shared block)\n"
           "  --set NAME=VALUE   a parameter of the reference (R,G,B or one value for colours)\n"
           "  --material NAME    the reference is the flowchart's photoreal choice for a\n"
           "                     material of the table (abrdf advise --list)\n"
           "  --candidate M[+M]  the model or diffuse+specular pair to fit: any model (a lobe\n"
           "                     the reference has keeps its parameters); the surface line\n"
           "                     says whether the budget mode offers it for the reference's\n"
           "                     surface class (--json lists the class's candidates)\n"
           "  --metric           l2 (default), log, cbrt, or auto (each; the best predicted)\n"
           "  --resolution N     direction-set density, 1 (coarse) to 5; 0: default\n"
           "  --materials FILE   a material file merged over data/materials.csv\n"
           "  --json             machine-readable output\n");
    return 0;
}

typedef struct fit_args {
    const char *ref, *cand, *material;
    const char *sets[MAX_SETS], *files[MAX_FILES];
    int nsets, nfiles, json, help;
    abrdf_fit_options opt;
} fit_args;

/* The reference, the candidate, the material the budget mode would see, and the fit. */
typedef struct fit_job {
    abrdf_model ref[2], cand[2]; /* (diffuse or NONE, specular) */
    abrdf_params rp, cp;         /* the reference's block; the candidate's fitted block */
    abrdf_material m;            /* its surface class picks the budget mode's candidates */
    abrdf_fit_result res;
    double secs, cpu_secs;
} fit_job;

/* One option with its value; 0 or a usage error. */
static int parse_option(fit_args *a, const char *opt, const char *v)
{
    if (!strcmp(opt, "--ref")) {
        a->ref = v;
    } else if (!strcmp(opt, "--candidate")) {
        a->cand = v;
    } else if (!strcmp(opt, "--material")) {
        a->material = v;
    } else if (!strcmp(opt, "--set")) {
        if (a->nsets == MAX_SETS)
            return cli_fail(CMD, "too many --set options (%d at most)", MAX_SETS);
        a->sets[a->nsets++] = v;
    } else if (!strcmp(opt, "--materials")) {
        if (a->nfiles == MAX_FILES) return cli_fail(CMD, "at most %d --materials files", MAX_FILES);
        a->files[a->nfiles++] = v;
    } else if (!strcmp(opt, "--metric")) {
        if (abrdf_fit_metric_find(v, &a->opt.metric) != ABRDF_OK)
            return cli_fail(CMD, "--metric needs l2, log, cbrt or auto, got '%s'", v);
    } else if (!strcmp(opt, "--resolution")) {
        long r;
        if (!cli_parse_int(v, 0, 5, &r))
            return cli_fail(CMD, "--resolution needs a whole number in [0, 5], got '%s'", v);
        a->opt.resolution = (int)r;
    } else {
        return cli_fail(CMD, "unknown option '%s' (abrdf fit --help)", opt);
    }
    return 0;
}

static int parse_args(int argc, char **argv, fit_args *a)
{
    memset(a, 0, sizeof *a);
    abrdf_fit_options_init(&a->opt);
    for (int i = 1; i < argc; ++i) {
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (cli_is_help(argv[i])) {
            a->help = 1;
            return 0;
        }
        if (!strcmp(argv[i], "--json")) {
            a->json = 1;
            continue;
        }
        if (!v) return cli_fail(CMD, "%s needs a value (abrdf fit --help)", argv[i]);
        int rc = parse_option(a, argv[i++], v);
        if (rc) return rc;
    }
    if (!a->cand) return cli_fail(CMD, "missing --candidate MODEL (abrdf fit --help)");
    if (!a->ref == !a->material)
        return cli_fail(CMD, "give the reference as --ref MODEL or --material NAME (one of them)");
    if (a->material && a->nsets)
        return cli_fail(CMD, "--set changes --ref's parameters, not a --material's");
    return 0;
}

/* "a+b" -> (a, b); "b" -> (none, b). */
static int parse_pair(const char *opt, const char *s, abrdf_model out[2])
{
    char buf[128];
    if (strlen(s) >= sizeof buf) return cli_fail(CMD, "%s: '%s' is too long", opt, s);
    strcpy(buf, s);
    char *plus = strchr(buf, '+');
    out[0] = NONE;
    if (plus) {
        *plus = '\0';
        if (strchr(plus + 1, '+'))
            return cli_fail(CMD, "%s: '%s' names more than two models", opt, s);
        if (cli_model(CMD, buf, &out[0])) return CLI_EXIT_USAGE;
        if (cli_model(CMD, plus + 1, &out[1])) return CLI_EXIT_USAGE;
    } else if (cli_model(CMD, buf, &out[1])) {
        return CLI_EXIT_USAGE;
    }
    return 0;
}

/* Whether a lobe of the pair reads the parameter `name`. */
static int pair_reads(const abrdf_model pair[2], const char *name)
{
    int id;
    return abrdf_param_find(name, &id) == ABRDF_OK &&
           (cli_model_reads(pair[0], id) || cli_model_reads(pair[1], id));
}

static const char *name_of(abrdf_model m)
{
    const abrdf_model_info *i = abrdf_model_get(m);
    return i ? i->name : "none";
}

static void pair_name(const abrdf_model p[2], char *buf, size_t size)
{
    if (p[0] == NONE)
        snprintf(buf, size, "%s", name_of(p[1]));
    else
        snprintf(buf, size, "%s+%s", name_of(p[0]), name_of(p[1]));
}

/* ---- the reference ------------------------------------------------------------------------ */

/* data/materials.csv with the --materials files merged over it; 0 or a usage error. */
static int load_tables(mat_table *t, const fit_args *a)
{
    char path[1024], err[MAT_ERR_MAX];
    if (data_path_find("materials.csv", path, sizeof path) != 0)
        return cli_fail(CMD, "the material table %s is missing (set ABRDF_DATA_DIR)", path);
    if (mat_table_load(t, path, err, sizeof err)) return cli_fail(CMD, "%s", err);
    for (int i = 0; i < a->nfiles; ++i)
        if (mat_table_load(t, a->files[i], err, sizeof err)) return cli_fail(CMD, "%s", err);
    return 0;
}

/* NAME=VALUE for the pair: checked against the lobe that reads NAME. */
static int set_pair(const abrdf_model pair[2], abrdf_params *p, const char *assign)
{
    char name[64];
    size_t n = strcspn(assign, "=");
    int id;
    snprintf(name, sizeof name, "%.*s", (int)(n < sizeof name ? n : sizeof name - 1), assign);
    abrdf_model m = pair[1];
    if (pair[0] != NONE && abrdf_param_find(name, &id) == ABRDF_OK &&
        !cli_model_reads(pair[1], id) && cli_model_reads(pair[0], id))
        m = pair[0];
    return cli_set_param(CMD, m, p, assign);
}

/* The parameters only the diffuse lobe reads, at its defaults, into the pair's block. */
static void diffuse_defaults(const abrdf_model pair[2], abrdf_params *p)
{
    abrdf_params d;
    abrdf_params_init(pair[0], &d);
    const abrdf_model_info *mi = abrdf_model_get(pair[0]);
    for (int k = 0; mi && k < mi->param_count; ++k) {
        double v[3];
        int id = mi->params[k].id, n;
        if (!cli_model_reads(pair[1], id) && (n = abrdf_param_read(&d, id, v)) > 0)
            abrdf_param_set(p, id, v, n);
    }
}

/* Whether model x is a lobe of one of the budget mode's candidates for m. */
static int offers_lobe(const abrdf_material *m, abrdf_model x)
{
    abrdf_model d, s;
    for (int i = 0; abrdf_budget_candidate(m, i, &d, &s) == ABRDF_OK; ++i)
        if (d == x || s == x) return 1;
    return 0;
}

/* The surface class a reference stands for: the first class, in the library's order (general
 * first), among whose budget candidates is every lobe of the reference. A class's photoreal
 * model is its candidate 0, so each special model finds the class whose rule chooses it
 * (kajiya_kay: cloth_shiny, belcour: layered_plate), and a model no rule chooses the class
 * that offers it (marschner: hair, disney_clearcoat: layered_plate). */
static void class_of(const abrdf_model ref[2], abrdf_material *m)
{
    const abrdf_select_rules *R = abrdf_select_rules_get();
    for (int i = 0; i < R->surface_count; ++i) {
        m->type = (abrdf_surface)i;
        if ((ref[0] == NONE || offers_lobe(m, ref[0])) && offers_lobe(m, ref[1])) return;
    }
    m->type = ABRDF_SURFACE_GENERAL;
}

/* The material a --ref stands for, as far as it picks the budget mode's candidates: the
 * class, the roughness (the smooth branch's lobes, which read no r, stand for a smooth
 * surface), the anisotropy and the diffuse albedo (none: no diffuse lobe). */
static void class_material(const abrdf_model ref[2], const abrdf_params *rp, abrdf_material *m)
{
    const abrdf_select_rules *R = abrdf_select_rules_get();
    abrdf_material_init(m);
    int by_n = pair_reads(ref, "n") && !pair_reads(ref, "r");
    m->n = by_n ? rp->n : -1.0;
    m->r = by_n ? -1.0 : rp->r;
    for (int l = 0; l < 2; ++l)
        if (ref[l] == R->smooth_diffuse || ref[l] == R->smooth_specular) m->r = R->smooth_r_max;
    m->anisotropy = pair_reads(ref, "anisotropic") ? rp->anisotropic : 0.0;
    if (pair_reads(ref, "kd"))
        memcpy(m->kd, rp->kd, sizeof m->kd);
    else
        m->kd[0] = m->kd[1] = m->kd[2] = 0.0;
    class_of(ref, m);
}

/* --ref M[+M] with its --set values; 0 or a usage error. */
static int ref_from_models(const fit_args *a, fit_job *j)
{
    int rc = parse_pair("--ref", a->ref, j->ref);
    if (rc) return rc;
    abrdf_params_init(j->ref[1], &j->rp);
    if (j->ref[0] != NONE) diffuse_defaults(j->ref, &j->rp);
    for (int i = 0; i < a->nsets; ++i)
        if (set_pair(j->ref, &j->rp, a->sets[i])) return CLI_EXIT_USAGE;
    for (int l = 0; l < 2; ++l) {
        char msg[256];
        if (j->ref[l] != NONE && abrdf_params_check(j->ref[l], &j->rp, msg, sizeof msg))
            return cli_fail(CMD, "--ref: %s", msg);
    }
    class_material(j->ref, &j->rp, &j->m);
    return 0;
}

/* --material NAME: the flowchart's photoreal choice for the table's entry; 0 or an error. */
static int ref_from_table(const mat_table *t, const char *name, fit_job *j)
{
    const mat_entry *e = mat_table_find(t, name);
    if (!e) {
        const char *near[4];
        int k = mat_table_nearest(t, name, near, 4);
        char hint[256] = "";
        for (int i = 0; i < k; ++i) strcat(strcat(hint, i ? ", " : ""), near[i]);
        return cli_fail(CMD, "unknown material '%s'%s%s%s", name, k ? "; did you mean: " : "", hint,
                        k ? "?" : " (abrdf advise --list)");
    }
    j->m = e->m;
    j->m.name = NULL; /* the table is freed before the fit */
    abrdf_selection sel;
    abrdf_selection_init(&sel);
    abrdf_params_init(NONE, &j->rp);
    if (abrdf_select(&j->m, ABRDF_GOAL_PHOTOREAL, NULL, NULL, &sel, &j->rp, NULL, NULL) != ABRDF_OK)
        return cli_fail(CMD, "material '%s': %s", name, sel.message);
    j->ref[0] = sel.diffuse;
    j->ref[1] = sel.specular;
    return 0;
}

/* The reference of either kind; the --materials files are loaded (and refused when they
 * cannot be read) whichever it is. */
static int reference(const fit_args *a, fit_job *j)
{
    mat_table t = {NULL, 0, 0};
    int rc = a->material || a->nfiles ? load_tables(&t, a) : 0;
    if (!rc) rc = a->material ? ref_from_table(&t, a->material, j) : ref_from_models(a, j);
    mat_table_free(&t);
    return rc;
}

/* ---- the fit and its report ------------------------------------------------------------- */

static double wall(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* abrdf_fit; 0, or the library's reason and 2 (what it was given) or 1 (anything else). */
static int run_fit(const fit_args *a, fit_job *j)
{
    size_t ws = abrdf_fit_workspace_size(&a->opt, NULL);
    void *work = malloc(ws);
    if (!work) return cli_fail(CMD, "out of memory (%zu bytes of workspace)", ws);
    abrdf_params_init(j->cand[1], &j->cp);
    abrdf_fit_result_init(&j->res);
    double t0 = wall();
    clock_t c0 = clock();
    int st = abrdf_fit(j->ref[0], j->ref[1], &j->rp, j->cand[0], j->cand[1], &j->cp, &a->opt,
                       &j->res, work, ws);
    j->secs = wall() - t0;
    j->cpu_secs = (double)(clock() - c0) / CLOCKS_PER_SEC;
    free(work);
    if (st == ABRDF_OK) return 0;
    cli_fail(CMD, "%s", j->res.message);
    return st == ABRDF_E_MODEL || st == ABRDF_E_RANGE ? CLI_EXIT_USAGE : 1;
}

/* Whether the budget mode fits cand for m (a lone model also stands for a pair's specular
 * lobe). */
static int offers_pair(const abrdf_material *m, const abrdf_model cand[2])
{
    abrdf_model d, s;
    for (int i = 0; abrdf_budget_candidate(m, i, &d, &s) == ABRDF_OK; ++i)
        if (s == cand[1] && (d == cand[0] || cand[0] == NONE)) return 1;
    return 0;
}

static int offer_count(const abrdf_material *m)
{
    abrdf_model d, s;
    int n = 0;
    while (abrdf_budget_candidate(m, n, &d, &s) == ABRDF_OK) ++n;
    return n;
}

/* The budget mode's candidates for m: a JSON array of names or a comma-separated list. */
static void print_offer(const abrdf_material *m, int json)
{
    abrdf_model p[2];
    char nm[96];
    printf("%s", json ? "[" : "");
    for (int i = 0; abrdf_budget_candidate(m, i, &p[0], &p[1]) == ABRDF_OK; ++i) {
        pair_name(p, nm, sizeof nm);
        printf(json ? "%s\"%s\"" : "%s%s", i ? ", " : "", nm);
    }
    printf("%s", json ? "]" : "");
}

/* The candidate's fitted block: every parameter the pair reads. */
static void print_params(const abrdf_model cand[2], const abrdf_params *p, int json)
{
    int count = abrdf_param_count(), first = 1;
    if (json) printf("{");
    for (int id = 0; id < count; ++id) {
        if (!cli_model_reads(cand[0], id) && !cli_model_reads(cand[1], id)) continue;
        const abrdf_param_info *pi = abrdf_param_get(id);
        double v[3];
        int n = abrdf_param_read(p, id, v);
        if (json) {
            printf("%s\"%s\": ", first ? "" : ", ", pi->name);
            if (n == 3)
                printf("[%.10g, %.10g, %.10g]", v[0], v[1], v[2]);
            else
                printf("%.10g", v[0]);
        } else if (n == 3) {
            printf("  %-16s %.6g, %.6g, %.6g\n", pi->name, v[0], v[1], v[2]);
        } else {
            printf("  %-16s %.6g\n", pi->name, v[0]);
        }
        first = 0;
    }
    if (json) printf("}");
}

static void print_json(const fit_job *j, const char *rn, const char *cn)
{
    const abrdf_fit_result *r = &j->res;
    printf("{\"reference\": ");
    cli_json_string(stdout, rn);
    printf(", \"candidate\": ");
    cli_json_string(stdout, cn);
    printf(", \"metric\": \"%s\", \"params\": ", abrdf_fit_metric_name(r->metric));
    print_params(j->cand, &j->cp, 1);
    /* a prediction or an error may be infinite (a candidate that cannot follow the
     * reference at all): JSON says null */
    const char *keys[7] = {"rel_l2",  "rel_log",   "rel_cbrt", "max_rel_pct",
                           "max_abs", "nmse_pred", "objective"};
    const double vals[7] = {r->rel_l2,  r->rel_log,   r->rel_cbrt, r->max_rel_pct,
                            r->max_abs, r->nmse_pred, r->objective};
    for (int k = 0; k < 7; ++k) {
        printf("%s\"%s\": ", k ? ", " : ",\n ", keys[k]);
        cli_json_number(stdout, vals[k]);
    }
    printf(", \"class\": \"%s\", \"fitted\": %d, \"evals\": %d, \"directions\": %d, "
           "\"seconds\": %.4f, \"cpu_seconds\": %.4f,\n",
           abrdf_nmse_class(r->nmse_pred), r->fitted, r->evals, r->directions, j->secs,
           j->cpu_secs);
    printf(" \"surface\": \"%s\", \"budget_candidate\": %s, \"budget_candidates\": ",
           abrdf_surface_name(j->m.type), offers_pair(&j->m, j->cand) ? "true" : "false");
    print_offer(&j->m, 1);
    printf("}\n");
}

static void print_text(const fit_job *j, const char *rn, const char *cn)
{
    const abrdf_fit_result *r = &j->res;
    printf("reference   %s\n", rn);
    printf("candidate   %s (fitted, metric %s)\n", cn, abrdf_fit_metric_name(r->metric));
    print_params(j->cand, &j->cp, 0);
    printf("rel L2      %.4g   (of f cos over %d direction pairs)\n", r->rel_l2, r->directions);
    printf("rel log     %.4g   (of log(1 + f cos), exact on the same set)\n", r->rel_log);
    printf("rel cbrt    %.4g   (of (f cos)^(1/3), exact on the same set)\n", r->rel_cbrt);
    printf("highlight   %.4g%%  (largest relative error in the reference's highlight zone)\n",
           r->max_rel_pct);
    printf("max abs     %.4g   (largest |f - f_ref| cos / largest f_ref cos)\n", r->max_abs);
    printf("image NMSE  %.4g   (predicted on the default sphere: %s)\n", r->nmse_pred,
           abrdf_nmse_class(r->nmse_pred));
    printf("work        %d parameters, %d objective evaluations, %.3f s\n", r->fitted, r->evals,
           j->secs);
    const char *surface = abrdf_surface_name(j->m.type);
    if (offers_pair(&j->m, j->cand)) {
        printf("surface     %s: %s is one of the budget mode's %d candidates (--json lists them)\n",
               surface, cn, offer_count(&j->m));
        return;
    }
    printf("surface     %s: %s is not one of the budget mode's candidates (", surface, cn);
    print_offer(&j->m, 0);
    printf(")\n");
}

int cmd_fit(int argc, char **argv)
{
    for (int i = 1; i < argc; ++i)
        if (!strcmp(argv[i], "--to")) return fit_to_run(argc, argv); /* a measured file */
    fit_args a;
    fit_job j;
    int rc = parse_args(argc, argv, &a);
    if (rc || a.help) return rc ? rc : usage();
    if ((rc = parse_pair("--candidate", a.cand, j.cand))) return rc;
    if ((rc = reference(&a, &j))) return rc;
    if ((rc = run_fit(&a, &j))) return rc;
    char rn[96], cn[96];
    pair_name(j.ref, rn, sizeof rn);
    pair_name(j.cand, cn, sizeof cn);
    if (a.json)
        print_json(&j, rn, cn);
    else
        print_text(&j, rn, cn);
    return 0;
}
