/* cmd_fit.c - `abrdf fit`: one model (or diffuse + specular pair) fitted to another with
 * abrdf_fit (abrdf_fit.h, docs/BUDGET.md): the fitted parameters, the errors against the
 * reference (relative L2, highlight, absolute) and the predicted image NMSE. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "abrdf_fit.h"
#include "cli.h"
#include "data_path.h"
#include "materials.h"
#include "metrics.h"

#define CMD "fit"
#define MAX_SETS 64

static int usage(void)
{
    printf("usage: abrdf fit (--ref MODEL[+MODEL] [--set NAME=VALUE ...] | --material NAME)\n"
           "                 --candidate MODEL[+MODEL] [--metric l2|log|cbrt|auto]\n"
           "                 [--resolution 0..5] [--materials FILE] [--json]\n\n"
           "Fits the candidate's parameters to the reference (abrdf_fit, docs/BUDGET.md):\n"
           "cosine-weighted least squares over a direction set covering the hemisphere, the\n"
           "weights (kd, ks, ks*f0) solved in closed form for every trial of the other\n"
           "parameters. Prints the fitted parameters, the relative L2 error of f cos, the\n"
           "highlight zone's largest relative error (Table 2's measure), the largest absolute\n"
           "error (Table 3's) and the image NMSE predicted on an analytic sphere.\n"
           "  --ref M[+M]        the reference: one model, or diffuse+specular (shared block)\n"
           "  --set NAME=VALUE   a parameter of the reference (R,G,B or one value for colours)\n"
           "  --material NAME    the reference is the flowchart's photoreal choice for a\n"
           "                     material of the table (abrdf advise --list)\n"
           "  --candidate M[+M]  the model or diffuse+specular pair to fit; it must be one the\n"
           "                     budget mode considers for the reference's surface class\n"
           "  --metric           l2 (default), log, cbrt, or auto (each; the best predicted)\n"
           "  --resolution N     direction-set density, 1 (coarse) to 5; 0: default\n"
           "  --materials FILE   a material file merged over data/materials.csv\n"
           "  --json             machine-readable output\n");
    return 0;
}

/* "a+b" -> (a, b); "b" -> (none, b). */
static int parse_pair(const char *opt, const char *s, abrdf_model out[2])
{
    char buf[128];
    if (!s) return cli_fail(CMD, "%s needs MODEL or DIFFUSE+SPECULAR", opt);
    if (strlen(s) >= sizeof buf) return cli_fail(CMD, "%s: '%s' is too long", opt, s);
    strcpy(buf, s);
    char *plus = strchr(buf, '+');
    out[0] = ABRDF_MODEL_NONE;
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

static int reads(abrdf_model m, int id)
{
    const abrdf_model_info *mi = abrdf_model_get(m);
    for (int k = 0; mi && k < mi->param_count; ++k)
        if (mi->params[k].id == id) return 1;
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
    if (pair[0] != ABRDF_MODEL_NONE && abrdf_param_find(name, &id) == ABRDF_OK &&
        !reads(pair[1], id) && reads(pair[0], id))
        m = pair[0];
    return cli_set_param(CMD, m, p, assign);
}

/* The surface class a reference model stands for: the class whose photoreal rule chooses it
 * (abrdf_select_rules), else general. */
static abrdf_surface class_of(abrdf_model specular)
{
    const abrdf_select_rules *R = abrdf_select_rules_get();
    for (int i = 1; i < R->surface_count; ++i)
        if (R->special[i] == specular) return (abrdf_surface)i;
    return ABRDF_SURFACE_GENERAL;
}

static const char *name_of(abrdf_model m)
{
    const abrdf_model_info *i = abrdf_model_get(m);
    return i ? i->name : "none";
}

static void pair_name(const abrdf_model p[2], char *buf, size_t size)
{
    if (p[0] == ABRDF_MODEL_NONE)
        snprintf(buf, size, "%s", name_of(p[1]));
    else
        snprintf(buf, size, "%s+%s", name_of(p[0]), name_of(p[1]));
}

/* The candidate must be one the budget mode fits for material m (a lone model may also stand
 * for a pair's specular lobe). Returns 0 or prints the class's candidates and returns 2. */
static int check_candidate(const abrdf_material *m, const abrdf_model cand[2], const char *what)
{
    char list[2048] = "", nm[96];
    abrdf_model d, s;
    for (int i = 1; abrdf_budget_candidate(m, i, &d, &s) == ABRDF_OK; ++i) {
        if ((d == cand[0] && s == cand[1]) || (cand[0] == ABRDF_MODEL_NONE && s == cand[1]))
            return 0;
        abrdf_model p[2] = {d, s};
        pair_name(p, nm, sizeof nm);
        if (strlen(list) + strlen(nm) + 3 < sizeof list)
            strcat(strcat(list, *list ? ", " : ""), nm);
    }
    pair_name(cand, nm, sizeof nm);
    return cli_fail(CMD, "%s cannot represent the surface class %s (%s); its candidates: %s", nm,
                    abrdf_surface_name(m->type), what, *list ? list : "none");
}

static double wall(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* The candidate's fitted block: every parameter the pair reads. */
static void print_params(const abrdf_model cand[2], const abrdf_params *p, int json)
{
    int count = abrdf_param_count(), first = 1;
    if (json) printf("{");
    for (int id = 0; id < count; ++id) {
        if (!reads(cand[0], id) && !reads(cand[1], id)) continue;
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

int cmd_fit(int argc, char **argv)
{
    const char *ref_s = NULL, *cand_s = NULL, *material = NULL, *sets[MAX_SETS], *files[8];
    int nsets = 0, nfiles = 0, json = 0;
    abrdf_fit_options opt;
    abrdf_fit_options_init(&opt);
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (cli_is_help(a)) return usage();
        if (!strcmp(a, "--json")) {
            json = 1;
            continue;
        }
        if (!v) return cli_fail(CMD, "%s needs a value (abrdf fit --help)", a);
        if (!strcmp(a, "--ref")) {
            ref_s = v;
        } else if (!strcmp(a, "--candidate")) {
            cand_s = v;
        } else if (!strcmp(a, "--material")) {
            material = v;
        } else if (!strcmp(a, "--set")) {
            if (nsets == MAX_SETS)
                return cli_fail(CMD, "too many --set options (%d at most)", MAX_SETS);
            sets[nsets++] = v;
        } else if (!strcmp(a, "--materials")) {
            if (nfiles == 8) return cli_fail(CMD, "at most 8 --materials files");
            files[nfiles++] = v;
        } else if (!strcmp(a, "--metric")) {
            if (abrdf_fit_metric_find(v, &opt.metric) != ABRDF_OK)
                return cli_fail(CMD, "--metric needs l2, log, cbrt or auto, got '%s'", v);
        } else if (!strcmp(a, "--resolution")) {
            long r;
            if (!cli_parse_int(v, 0, 5, &r))
                return cli_fail(CMD, "--resolution needs a whole number in [0, 5], got '%s'", v);
            opt.resolution = (int)r;
        } else {
            return cli_fail(CMD, "unknown option '%s' (abrdf fit --help)", a);
        }
        ++i;
    }
    if (!cand_s) return cli_fail(CMD, "missing --candidate MODEL (abrdf fit --help)");
    if (!ref_s == !material)
        return cli_fail(CMD, "give the reference as --ref MODEL or --material NAME (one of them)");
    if (material && nsets)
        return cli_fail(CMD, "--set changes --ref's parameters, not a --material's");
    abrdf_model cand[2], ref[2];
    int rc = parse_pair("--candidate", cand_s, cand);
    if (rc) return rc;

    abrdf_params rp;
    abrdf_material m;
    abrdf_material_init(&m);
    char what[160];
    if (ref_s) {
        if ((rc = parse_pair("--ref", ref_s, ref))) return rc;
        abrdf_params_init(ref[1], &rp);
        if (ref[0] != ABRDF_MODEL_NONE) { /* the diffuse lobe's own parameters at its defaults */
            abrdf_params d;
            abrdf_params_init(ref[0], &d);
            const abrdf_model_info *mi = abrdf_model_get(ref[0]);
            for (int k = 0; k < mi->param_count; ++k) {
                double v[3];
                int id = mi->params[k].id, n;
                if (!reads(ref[1], id) && (n = abrdf_param_read(&d, id, v)) > 0)
                    abrdf_param_set(&rp, id, v, n);
            }
        }
        for (int i = 0; i < nsets; ++i)
            if (set_pair(ref, &rp, sets[i])) return CLI_EXIT_USAGE;
        for (int l = 0; l < 2; ++l) {
            char msg[256];
            if (ref[l] != ABRDF_MODEL_NONE && abrdf_params_check(ref[l], &rp, msg, sizeof msg))
                return cli_fail(CMD, "--ref: %s", msg);
        }
        /* the class the reference stands for, described by its parameters */
        m.type = class_of(ref[1]);
        m.r = rp.r;
        int n_id, kd_id;
        abrdf_param_find("n", &n_id);
        abrdf_param_find("kd", &kd_id);
        m.n = reads(ref[1], n_id) || reads(ref[0], n_id) ? rp.n : -1.0;
        memcpy(m.ks, rp.ks, sizeof m.ks);
        memcpy(m.f0, rp.f0, sizeof m.f0);
        if (ref[0] == ABRDF_MODEL_NONE && !reads(ref[1], kd_id))
            m.kd[0] = m.kd[1] = m.kd[2] = 0.0;
        else
            memcpy(m.kd, rp.kd, sizeof m.kd);
        m.anisotropy = rp.anisotropic;
        m.melanin = rp.melanin;
        m.redness = rp.redness;
        m.layer_count = rp.layer_count < ABRDF_MAX_LAYERS ? rp.layer_count : ABRDF_MAX_LAYERS;
        memcpy(m.layers, rp.layers, sizeof m.layers);
        char rn[96];
        pair_name(ref, rn, sizeof rn);
        snprintf(what, sizeof what, "the class of %s", rn);
    } else {
        mat_table t = {NULL, 0, 0};
        char path[1024], err[MAT_ERR_MAX];
        if (data_path_find("materials.csv", path, sizeof path) != 0)
            return cli_fail(CMD, "the material table %s is missing (set ABRDF_DATA_DIR)", path);
        if (mat_table_load(&t, path, err, sizeof err)) return cli_fail(CMD, "%s", err);
        for (int i = 0; i < nfiles; ++i)
            if (mat_table_load(&t, files[i], err, sizeof err)) {
                mat_table_free(&t);
                return cli_fail(CMD, "%s", err);
            }
        const mat_entry *e = mat_table_find(&t, material);
        if (!e) {
            const char *near[4];
            int k = mat_table_nearest(&t, material, near, 4);
            char hint[256] = "";
            for (int j = 0; j < k; ++j) strcat(strcat(hint, j ? ", " : ""), near[j]);
            rc = cli_fail(CMD, "unknown material '%s'%s%s%s", material, k ? "; did you mean: " : "",
                          hint, k ? "?" : " (abrdf advise --list)");
            mat_table_free(&t);
            return rc;
        }
        m = e->m;
        m.name = NULL; /* the table is freed below */
        mat_table_free(&t);
        abrdf_selection sel;
        abrdf_selection_init(&sel);
        abrdf_params_init(ABRDF_MODEL_NONE, &rp);
        if (abrdf_select(&m, ABRDF_GOAL_PHOTOREAL, NULL, NULL, &sel, &rp, NULL, NULL) != ABRDF_OK)
            return cli_fail(CMD, "material '%s': %s", material, sel.message);
        ref[0] = sel.diffuse;
        ref[1] = sel.specular;
        snprintf(what, sizeof what, "of material %s", material);
    }
    if ((rc = check_candidate(&m, cand, what))) return rc;

    size_t ws = abrdf_fit_workspace_size(&opt, NULL);
    void *work = malloc(ws);
    if (!work) return cli_fail(CMD, "out of memory (%zu bytes of workspace)", ws);
    abrdf_params cp;
    abrdf_params_init(cand[1], &cp);
    abrdf_fit_result r;
    abrdf_fit_result_init(&r);
    double t0 = wall();
    clock_t c0 = clock();
    int st = abrdf_fit(ref[0], ref[1], &rp, cand[0], cand[1], &cp, &opt, &r, work, ws);
    double secs = wall() - t0, cpu = (double)(clock() - c0) / CLOCKS_PER_SEC;
    free(work);
    if (st != ABRDF_OK) {
        fprintf(stderr, "abrdf fit: %s\n", r.message);
        return 1;
    }
    char rn[96], cn[96];
    pair_name(ref, rn, sizeof rn);
    pair_name(cand, cn, sizeof cn);
    if (json) {
        printf("{\"reference\": ");
        cli_json_string(stdout, rn);
        printf(", \"candidate\": ");
        cli_json_string(stdout, cn);
        printf(", \"metric\": \"%s\", \"params\": ", abrdf_fit_metric_name(r.metric));
        print_params(cand, &cp, 1);
        printf(",\n \"rel_l2\": %.10g, \"max_rel_pct\": %.10g, \"max_abs\": %.10g, "
               "\"nmse_pred\": %.10g, \"class\": \"%s\", \"objective\": %.10g, \"fitted\": %d, "
               "\"evals\": %d, \"directions\": %d, \"seconds\": %.4f, \"cpu_seconds\": %.4f}\n",
               r.rel_l2, r.max_rel_pct, r.max_abs, r.nmse_pred, abrdf_nmse_class(r.nmse_pred),
               r.objective, r.fitted, r.evals, r.directions, secs, cpu);
        return 0;
    }
    printf("reference   %s\n", rn);
    printf("candidate   %s (fitted, metric %s)\n", cn, abrdf_fit_metric_name(r.metric));
    print_params(cand, &cp, 0);
    printf("rel L2      %.4g   (of f cos over %d direction pairs)\n", r.rel_l2, r.directions);
    printf("highlight   %.4g%%  (largest relative error in the reference's highlight zone)\n",
           r.max_rel_pct);
    printf("max abs     %.4g   (largest |f - f_ref| cos / largest f_ref cos)\n", r.max_abs);
    printf("image NMSE  %.4g   (predicted on the default sphere: %s)\n", r.nmse_pred,
           abrdf_nmse_class(r.nmse_pred));
    printf("work        %d parameters, %d objective evaluations, %.3f s\n", r.fitted, r.evals,
           secs);
    return 0;
}
