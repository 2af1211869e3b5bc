/* cmd_advise.c - `abrdf advise`: the paper's flowchart (abrdf_select) for a named material of
 * the table (data/materials.csv, plus --materials files) or explicit values; prints the
 * chosen models, their parameters, the predicted error and cost, and why (the trace). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "advise_asset.h"
#include "advise_budget.h"
#include "hair_table_args.h"
#include "measured_ref.h"
#include "cli.h"
#include "cost_file.h"
#include "data_path.h"
#include "materials.h"
#include "out_file.h"
#include "scene_choice.h"
#include "select_trace.h"

#define CMD "advise"
#define MAX_FILES 8

/* The r range of the photoreal model of surface class t when it is narrower than [0, 1]
 * (huang for hair): 1 and the range, else 0. */
static int special_r_range(abrdf_surface t, const char **model, double *lo, double *hi)
{
    const abrdf_select_rules *R = abrdf_select_rules_get();
    int id;
    if ((int)t < 0 || (int)t >= R->surface_count || R->special[t] == ABRDF_MODEL_NONE ||
        abrdf_param_find("r", &id) != ABRDF_OK)
        return 0;
    const abrdf_model_info *mi = abrdf_model_get(R->special[t]);
    for (int k = 0; mi && k < mi->param_count; ++k)
        if (mi->params[k].id == id && (mi->params[k].min > 0.0 || mi->params[k].max < 1.0)) {
            *model = mi->name;
            *lo = mi->params[k].min;
            *hi = mi->params[k].max;
            return 1;
        }
    return 0;
}

/* The largest whole n whose roughness r(n) = sqrt(alpha_g(n)) is still >= r_lo: what a
 * lower bound on r means for n (checked through the converters, so the bound is exact). */
static double n_max_for_r(double r_lo)
{
    double n = floor(abrdf_alpha_g_to_n(abrdf_r_to_alpha_g(r_lo)));
    while (abrdf_alpha_g_to_r(abrdf_n_to_alpha_g(n + 1)) >= r_lo) n += 1;
    while (n > 0 && !(abrdf_alpha_g_to_r(abrdf_n_to_alpha_g(n)) >= r_lo)) n -= 1;
    return n;
}

static void usage(FILE *f)
{
    fprintf(
        f,
        "usage: abrdf advise [MATERIAL] [options]\n"
        "       abrdf advise --list [--json] [--materials FILE]...\n"
        "       abrdf advise --rules [--json]\n"
        "       abrdf advise [MATERIAL] --budget none|slight|noticeable|NMSE [--json]\n"
        "       abrdf advise [MATERIAL] --pareto [--plot FILE.svg] [--json]\n"
        "       abrdf advise --measured FILE --budget none|slight|noticeable|NMSE [--json]\n"
        "       abrdf advise FILE.gltf|FILE.glb|FILE.mtlx|FILE.scene [--goal G|--budget B] "
        "[--json]\n\n"
        "Chooses the diffuse and specular models for a material by the paper's flowchart\n"
        "(Zavalniuk & Romanyuk 2024, Fig. 2) and explains every decision (docs/SELECTION.md).\n\n"
        "  MATERIAL               a name from the material table (abrdf advise --list)\n"
        "  FILE                   every glTF-style material of a glTF, MaterialX or scene\n"
        "                         file, each with its choice and trace (docs/GLTF.md)\n"
        "  --goal G               performance | photoreal (default photoreal)\n"
        "  --max-rel-error PCT    performance: max relative error in %% (default %g; 'none')\n"
        "  --max-abs-error X      performance: max absolute error (default %g; 'none')\n"
        "  --n N                  Blinn-Phong exponent, [0, 1e6]\n"
        "  --r R                  perceptual roughness (the paper's alpha), [0, 1]\n",
        abrdf_select_rules_get()->default_max_rel_pct, abrdf_select_rules_get()->default_max_abs);
    /* Where the photoreal model takes a narrower r (and so a narrower n), say so. */
    for (int t = 0; t < ABRDF_SURFACE_COUNT; ++t) {
        const char *model;
        double lo, hi;
        if (special_r_range((abrdf_surface)t, &model, &lo, &hi))
            fprintf(f, "                         photoreal %s (%s): r in [%g, %g], so n <= %.0f\n",
                    abrdf_surface_name((abrdf_surface)t), model, lo, hi, n_max_for_r(lo));
    }
    fprintf(
        f, "  --kd V|R,G,B --ks V|R,G,B --f0 V|R,G,B   colours, [0, 1]\n"
           "  --eta E                index of refraction, [1, 4] (sets f0 = ((E-1)/(E+1))^2)\n"
           "  --anisotropy A         [0, 1]\n"
           "  --melanin M --redness R   hair pigment, [0, 1]\n"
           "  --type T               general, cloth_rough, cloth_shiny, hair, layered_plastic,\n"
           "                         layered_plate, layered_metal\n"
           "  --materials FILE       extra material file (same format; overrides by name)\n"
           "  --costs FILE           costs measured by abrdf calibrate (default: the paper's Table "
           "4;\n"
           "                         with --budget/--pareto: the built-in table)\n"
           "  --budget B             budget mode (docs/SELECTION.md, \"The budget mode\"): the\n"
           "                         cheapest fitted candidate whose predicted image NMSE against\n"
           "                         the photoreal choice is below B, a Table-8 class (none,\n"
           "                         slight, noticeable) or a number in (0, 1]\n"
           "  --measured FILE        budget mode against a measured table (FILE.binary,\n"
           "                         FILE.bsdf) as the photoreal reference: every general\n"
           "                         candidate fitted to it\n"
           "                         (docs/MEASURED.md, \"Fitting measured data\")\n"
           "  --hair-table [--hair-table-sizes NT,NV,NP,SETS] [--hair-table-cache DIR]\n"
           "                         with --budget/--pareto: a hair material's reference is its\n"
           "                         huang table, the converged model (~1 min of one core;\n"
           "                         docs/SELECTION.md, \"A converged reference for hair\")\n"
           "  --pareto               every candidate's cost and predicted NMSE: the front\n"
           "  --plot FILE.svg        with --pareto: draw the cost/error plane\n"
           "  --list                 list the materials\n"
           "  --rules                the flowchart's thresholds and model choices "
           "(abrdf_select_rules)\n"
           "  --json                 machine-readable output\n");
}

/* ---- small printers ------------------------------------------------------------------- */

static void json_num(double v) { cli_json_number(stdout, v); }

/* -1 marks "not applicable" in abrdf_selection; JSON says null. */
static void json_opt(double v)
{
    if (v < 0.0)
        printf("null");
    else
        json_num(v);
}

static void json_rgb(const double v[3]) { printf("[%.10g, %.10g, %.10g]", v[0], v[1], v[2]); }

/* The model's stable name; NULL for ABRDF_MODEL_NONE. */
static const char *model_name(abrdf_model m)
{
    const abrdf_model_info *info = abrdf_model_get(m);
    return info ? info->name : NULL;
}

/* The same for the rules, which name only registered models. */
static const char *rule_name(abrdf_model m)
{
    const char *name = model_name(m);
    return name ? name : "none";
}

/* ---- the material table --------------------------------------------------------------- */

static int load_tables(mat_table *t, const char **files, int nfiles)
{
    char path[1024], err[MAT_ERR_MAX];
    if (data_path_find("materials.csv", path, sizeof path) != 0)
        return cli_fail(CMD, "the material table %s is missing (set ABRDF_DATA_DIR)", path);
    if (mat_table_load(t, path, err, sizeof err)) return cli_fail(CMD, "%s", err);
    for (int i = 0; i < nfiles; ++i)
        if (mat_table_load(t, files[i], err, sizeof err)) return cli_fail(CMD, "%s", err);
    return 0;
}

static void list_materials(const mat_table *t, int json)
{
    if (json) {
        printf("{\"materials\": [");
        for (int i = 0; i < t->count; ++i) {
            const mat_entry *e = &t->items[i];
            printf("%s\n  {\"name\": ", i ? "," : "");
            cli_json_string(stdout, e->name);
            printf(", \"type\": \"%s\", \"n\": ", abrdf_surface_name(e->m.type));
            json_opt(e->m.n);
            printf(", \"r\": ");
            json_opt(e->m.r);
            printf(", \"kd\": ");
            json_rgb(e->m.kd);
            printf(", \"ks\": ");
            json_rgb(e->m.ks);
            printf(", \"f0\": ");
            json_rgb(e->m.f0);
            printf(", \"eta\": ");
            json_opt(e->m.eta > 0.0 ? e->m.eta : -1.0);
            printf(", \"anisotropy\": %.10g, \"layers\": %d, \"source\": ", e->m.anisotropy,
                   e->m.layer_count);
            cli_json_string(stdout, e->source);
            printf("}");
        }
        printf("\n]}\n");
        return;
    }
    printf("%-20s %-16s %6s %8s  %s\n", "material", "type", "r", "n", "source");
    for (int i = 0; i < t->count; ++i) {
        const mat_entry *e = &t->items[i];
        char r[16] = "-", n[16] = "-";
        if (e->m.r >= 0.0) snprintf(r, sizeof r, "%g", e->m.r);
        if (e->m.n >= 0.0) snprintf(n, sizeof n, "%g", e->m.n);
        printf("%-20s %-16s %6s %8s  %.70s%s\n", e->name, abrdf_surface_name(e->m.type), r, n,
               e->source, strlen(e->source) > 70 ? "..." : "");
    }
    printf("%d materials\n", t->count);
}

/* The rules table, for people and for the ports' generators and tests. */
static void print_rules(int json)
{
    const abrdf_select_rules *R = abrdf_select_rules_get();
    if (!json) {
        printf("smooth if r <= %g; anisotropic lobe if anisotropy > %g\n", R->smooth_r_max,
               R->aniso_min);
        printf("default tolerances: rel %g%%, abs %g; n derived from r capped at %g, f_2e's n "
               "clamped to [%g, %g]\n",
               R->default_max_rel_pct, R->default_max_abs, R->n_max, R->n_min, R->n_max);
        printf("performance: %s + cheapest of", rule_name(R->perf_diffuse));
        for (int i = 0; i < R->candidate_count; ++i) printf(" %s", rule_name(R->candidates[i]));
        printf("; none passes: %s\n", rule_name(R->perf_fallback));
        printf("photoreal general: rough %s + %s (anisotropic %s); smooth %s + %s\n",
               rule_name(R->rough_diffuse), rule_name(R->rough_specular),
               rule_name(R->rough_specular_aniso), rule_name(R->smooth_diffuse),
               rule_name(R->smooth_specular));
        for (int i = 1; i < R->surface_count; ++i)
            printf("photoreal %s: %s\n", abrdf_surface_name((abrdf_surface)i),
                   rule_name(R->special[i]));
        return;
    }
    printf("{\"smooth_r_max\": %.17g, \"aniso_min\": %.17g, \"default_max_rel_pct\": %.17g, "
           "\"default_max_abs\": %.17g, \"n_min\": %.17g, \"n_max\": %.17g,\n",
           R->smooth_r_max, R->aniso_min, R->default_max_rel_pct, R->default_max_abs, R->n_min,
           R->n_max);
    printf(" \"perf_diffuse\": \"%s\", \"perf_fallback\": \"%s\", \"candidates\": [",
           rule_name(R->perf_diffuse), rule_name(R->perf_fallback));
    for (int i = 0; i < R->candidate_count; ++i)
        printf("%s\"%s\"", i ? ", " : "", rule_name(R->candidates[i]));
    printf("],\n \"rough_diffuse\": \"%s\", \"rough_specular\": \"%s\", \"rough_specular_aniso\": "
           "\"%s\", "
           "\"smooth_diffuse\": \"%s\", \"smooth_specular\": \"%s\",\n \"special\": {",
           rule_name(R->rough_diffuse), rule_name(R->rough_specular),
           rule_name(R->rough_specular_aniso), rule_name(R->smooth_diffuse),
           rule_name(R->smooth_specular));
    for (int i = 1; i < R->surface_count; ++i) {
        printf("%s\"%s\": {\"model\": \"%s\", \"reason\": ", i > 1 ? ", " : "",
               abrdf_surface_name((abrdf_surface)i), rule_name(R->special[i]));
        cli_json_string(stdout, R->special_reason[i]);
        printf("}");
    }
    printf("},\n \"nmse_class_max\": [%.17g, %.17g, %.17g], \"table6_f2e\": [",
           R->nmse_class_max[0], R->nmse_class_max[1], R->nmse_class_max[2]);
    double alpha_g, nmse;
    for (int i = 0; abrdf_select_table6(i, &alpha_g, &nmse) == ABRDF_OK; ++i)
        printf("%s[%.17g, %.17g]", i ? ", " : "", alpha_g, nmse);
    printf("]}\n");
}

/* ---- option values -------------------------------------------------------------------- */

static int range_value(const char *opt, const char *s, double lo, double hi, double *out)
{
    if (!s) return cli_fail(CMD, "%s needs a value", opt);
    if (!cli_parse_double(s, out)) return cli_fail(CMD, "%s: '%s' is not a finite number", opt, s);
    if (!(*out >= lo && *out <= hi))
        return cli_fail(CMD, "%s: %s is outside [%g, %g]", opt, s, lo, hi);
    return 0;
}

static int color_value(const char *opt, const char *s, double v[3])
{
    if (!s) return cli_fail(CMD, "%s needs V or R,G,B", opt);
    if (strchr(s, ',')) {
        if (!cli_parse_vec3(s, v))
            return cli_fail(CMD, "%s: '%s' is not R,G,B (finite numbers)", opt, s);
    } else if (cli_parse_double(s, &v[0])) {
        v[1] = v[2] = v[0];
    } else {
        return cli_fail(CMD, "%s: '%s' is not a finite number or R,G,B", opt, s);
    }
    for (int c = 0; c < 3; ++c)
        if (!(v[c] >= 0.0 && v[c] <= 1.0)) return cli_fail(CMD, "%s: %s is outside [0, 1]", opt, s);
    return 0;
}

static int limit_value(const char *opt, const char *s, double *out)
{
    if (s && !strcmp(s, "none")) {
        *out = INFINITY;
        return 0;
    }
    return range_value(opt, s, 0.0, 1e300, out);
}

/* ---- output --------------------------------------------------------------------------- */

static void print_human(const abrdf_selection *s, const abrdf_params *p, const select_trace *trace,
                        const mat_entry *e)
{
    if (e && e->line > 0)
        printf("material  %s (%s; %s:%d)\n", e->name, abrdf_surface_name(s->type), e->file,
               e->line);
    else if (e) /* a glTF or MaterialX material: the file holds no line for it */
        printf("material  %s (%s; %s)\n", e->name, abrdf_surface_name(s->type), e->file);
    else
        printf("material  explicit values (%s)\n", abrdf_surface_name(s->type));
    printf("goal      %s\n", abrdf_goal_name(s->goal));
    printf("diffuse   %s\n", s->diffuse == ABRDF_MODEL_NONE ? "none (part of the specular model)"
                                                            : model_name(s->diffuse));
    printf("specular  %s\n", model_name(s->specular));
    printf("params    kd %g,%g,%g  ks %g,%g,%g  f0 %.4g,%.4g,%.4g  n %g  r %g", p->kd[0], p->kd[1],
           p->kd[2], p->ks[0], p->ks[1], p->ks[2], p->f0[0], p->f0[1], p->f0[2], p->n, p->r);
    if (p->anisotropic > 0.0) printf("  anisotropic %g", p->anisotropic);
    if (s->type == ABRDF_SURFACE_HAIR)
        printf("  eta %g  melanin %g  redness %g", p->eta, p->melanin, p->redness);
    printf("\n");
    if (s->type >= ABRDF_SURFACE_LAYERED_PLASTIC)
        for (int i = 0; i < p->layer_count; ++i)
            printf("layer %d   eta %.4g  kappa %.4g  r %g  depth %g  sigma_a %g,%g,%g\n", i,
                   p->layers[i].eta, p->layers[i].kappa, p->layers[i].r, p->layers[i].depth,
                   p->layers[i].sigma_a[0], p->layers[i].sigma_a[1], p->layers[i].sigma_a[2]);
    if (s->err_rel_pct >= 0.0)
        printf("error     max relative %.3g%%, max absolute %.3g (against Blinn-Phong)\n",
               fabs(s->err_rel_pct) < 1e-9 ? 0.0 : s->err_rel_pct,
               fabs(s->err_abs) < 1e-9 ? 0.0 : s->err_abs);
    else if (s->err_nmse >= 0.0)
        printf("error     NMSE %g against the GGX lobe (paper, Table 6)\n", s->err_nmse);
    else
        printf("error     no prediction (the model is the reference for its surface class)\n");
    char unit[32] = "";
    sscanf(s->cost_unit ? s->cost_unit : "units", "%31s", unit);
    printf("cost      %s ", model_name(s->specular));
    if (s->cost_specular >= 0.0)
        printf("%g %s", s->cost_specular, unit);
    else
        printf("not in the cost table");
    if (s->diffuse != ABRDF_MODEL_NONE) {
        printf("; %s ", model_name(s->diffuse));
        if (s->cost_diffuse >= 0.0)
            printf("%g %s", s->cost_diffuse, unit);
        else
            printf("not in the cost table");
    }
    if (s->cost_total >= 0.0) printf("; total %g %s", s->cost_total, unit);
    printf("  [%s]\n", s->cost_unit ? s->cost_unit : "");
    printf("why:\n");
    for (int i = 0; i < trace->count; ++i) printf("  %2d. %s\n", i + 1, trace->steps[i].text);
    if (e) printf("source: %s\n", e->source);
}

static void advise_print_selection(const abrdf_selection *s, const abrdf_params *p,
                                   const select_trace *trace, const mat_entry *e,
                                   const abrdf_tolerance *tol, int json)
{
    if (json)
        select_json(stdout, s, p, trace, e ? e->name : NULL, e ? e->source : NULL, tol);
    else
        print_human(s, p, trace, e);
}

/* ---- the command line ------------------------------------------------------------------ */

/* Values given on the command line, applied over the table's material (or the defaults). */
typedef struct advise_overrides {
    double n, r, kd[3], ks[3], f0[3], eta, aniso, mel, red;
    int has_n, has_r, has_kd, has_ks, has_f0, has_eta, has_aniso, has_mel, has_red, has_type;
    abrdf_surface type;
} advise_overrides;

/* What the command line asks for. */
typedef struct advise_args {
    int help; /* --help given: print the usage and stop */
    const char *name, *files[MAX_FILES], *costs_file, *plot, *measured;
    int nfiles, list, json, rules, pareto, has_goal;
    select_request rq;   /* --goal, or --budget (rq.by_budget) */
    abrdf_tolerance tol; /* --max-rel-error, --max-abs-error */
    advise_overrides o;
    hair_table_args hair; /* --hair-table[-sizes, -cache]: hair's budget against its table */
} advise_args;

/* A material value at `a` (--n, --kd, --type, ...) with its value v: 1 if it is one (*st: 0,
 * or the exit status after the message), 0 if not. */
static int take_override(advise_overrides *o, const char *a, const char *v, int *st)
{
    const struct {
        const char *name;
        double lo, hi, *slot;
        int *has;
    } ranges[] = {{"--n", 0.0, 1e6, &o->n, &o->has_n},
                  {"--r", 0.0, 1.0, &o->r, &o->has_r},
                  {"--eta", 1.0, 4.0, &o->eta, &o->has_eta},
                  {"--anisotropy", 0.0, 1.0, &o->aniso, &o->has_aniso},
                  {"--melanin", 0.0, 1.0, &o->mel, &o->has_mel},
                  {"--redness", 0.0, 1.0, &o->red, &o->has_red}};
    const struct {
        const char *name;
        double *slot;
        int *has;
    } colors[] = {
        {"--kd", o->kd, &o->has_kd}, {"--ks", o->ks, &o->has_ks}, {"--f0", o->f0, &o->has_f0}};
    for (size_t k = 0; k < sizeof ranges / sizeof ranges[0]; ++k)
        if (!strcmp(a, ranges[k].name)) {
            *st = range_value(a, v, ranges[k].lo, ranges[k].hi, ranges[k].slot);
            *ranges[k].has = 1;
            return 1;
        }
    for (size_t k = 0; k < sizeof colors / sizeof colors[0]; ++k)
        if (!strcmp(a, colors[k].name)) {
            *st = color_value(a, v, colors[k].slot);
            *colors[k].has = 1;
            return 1;
        }
    if (strcmp(a, "--type")) return 0;
    *st = 0;
    if (!v || abrdf_surface_find(v, &o->type) != ABRDF_OK)
        *st = cli_fail(CMD,
                       "--type needs one of general, cloth_rough, cloth_shiny, hair, "
                       "layered_plastic, layered_plate, layered_metal; got '%s'",
                       v ? v : "");
    o->has_type = 1;
    return 1;
}

/* One argument at `a` (v: the next one, or NULL); *takes: whether it took v. 0, or the exit
 * status after the message. */
static int take_option(advise_args *aa, const char *a, const char *v, int *takes)
{
    int st = 0;
    int *flag = !strcmp(a, "--list")     ? &aa->list
                : !strcmp(a, "--rules")  ? &aa->rules
                : !strcmp(a, "--json")   ? &aa->json
                : !strcmp(a, "--pareto") ? &aa->pareto
                                         : NULL;
    *takes = !flag;
    if (flag) {
        *flag = 1;
        return 0;
    }
    if (take_override(&aa->o, a, v, &st)) return st;
    if (!strcmp(a, "--goal")) {
        if (!v || abrdf_goal_find(v, &aa->rq.goal) != ABRDF_OK)
            return cli_fail(CMD, "--goal needs performance or photoreal, got '%s'", v ? v : "");
        aa->has_goal = 1;
    } else if (!strcmp(a, "--budget")) {
        if (!v) return cli_fail(CMD, "--budget needs none, slight, noticeable or an NMSE");
        return select_request_budget(&aa->rq, CMD, v);
    } else if (!strcmp(a, "--measured")) {
        if (!v) return cli_fail(CMD, "--measured needs a file (FILE.binary, FILE.bsdf)");
        aa->measured = v;
    } else if (!strcmp(a, "--plot")) {
        if (!v) return cli_fail(CMD, "--plot needs a file name (FILE.svg)");
        aa->plot = v;
    } else if (!strcmp(a, "--max-rel-error")) {
        st = limit_value(a, v, &aa->tol.max_rel_pct);
    } else if (!strcmp(a, "--max-abs-error")) {
        st = limit_value(a, v, &aa->tol.max_abs);
    } else if (!strcmp(a, "--materials")) {
        if (!v) return cli_fail(CMD, "--materials needs a file");
        if (aa->nfiles == MAX_FILES)
            return cli_fail(CMD, "at most %d --materials files", MAX_FILES);
        aa->files[aa->nfiles++] = v;
    } else if (!strcmp(a, "--costs")) {
        if (!v) return cli_fail(CMD, "--costs needs a file (abrdf calibrate writes one)");
        aa->costs_file = v;
    } else if (a[0] == '-' && a[1] == '-') {
        return cli_fail(CMD, "unknown option '%s' (abrdf advise --help)", a);
    } else {
        if (aa->name) return cli_fail(CMD, "one material at a time ('%s' and '%s')", aa->name, a);
        aa->name = a, *takes = 0;
    }
    return st;
}

/* The command line into aa, the rules between the options checked: 0 (aa->help: print the
 * usage), or the exit status after the message. */
static int advise_args_parse(int argc, char **argv, advise_args *aa)
{
    memset(aa, 0, sizeof *aa);
    aa->rq = (select_request){0, ABRDF_GOAL_PHOTOREAL, 0.0};
    abrdf_tolerance_init(&aa->tol);
    aa->o.type = ABRDF_SURFACE_GENERAL;
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (cli_is_help(a)) {
            aa->help = 1;
            return 0;
        }
        int hair = hair_table_option(&aa->hair, CMD, argc, argv, &i);
        if (hair < 0) return -hair;
        if (hair) continue;
        int takes, st = take_option(aa, a, v, &takes);
        if (st) return st;
        i += takes;
    }
    const select_request *rq = &aa->rq;
    if (rq->by_budget && aa->pareto)
        return cli_fail(CMD, "--budget and --pareto exclude each other");
    if ((rq->by_budget || aa->pareto) && aa->has_goal)
        return cli_fail(CMD,
                        "--goal and --%s exclude each other: the budget's reference is the "
                        "photoreal choice",
                        aa->pareto ? "pareto" : "budget");
    if (aa->plot && !aa->pareto) return cli_fail(CMD, "--plot draws the front of --pareto");
    int hrc = hair_table_check(&aa->hair, CMD);
    if (hrc) return hrc;
    if (aa->hair.sizes[0] &&
        (!(rq->by_budget || aa->pareto) || aa->measured || (aa->name && advise_is_asset(aa->name))))
        return cli_fail(CMD, "--hair-table goes with --budget or --pareto for one material of the "
                             "table (or given by values)");
    if (aa->measured) {
        const advise_overrides *o = &aa->o;
        int material = aa->name || o->has_n || o->has_r || o->has_kd || o->has_ks || o->has_f0 ||
                       o->has_eta || o->has_aniso || o->has_mel || o->has_red || o->has_type;
        if (!rq->by_budget)
            return cli_fail(CMD, "--measured needs --budget none|slight|noticeable|NMSE");
        if (material || aa->pareto || aa->has_goal || aa->list || aa->rules || aa->nfiles ||
            aa->costs_file)
            return cli_fail(CMD, "--measured FILE is the material and the reference: it takes "
                                 "--budget and --json only (costs: the built-in table)");
    }
    if (aa->plot) { /* the plot never replaces an input */
        char tpath[1024], perr[1024];
        data_path_find("materials.csv", tpath, sizeof tpath);
        const char *out_role = "--plot file", *ins[MAX_FILES + 2] = {tpath, aa->costs_file},
                   *in_roles[MAX_FILES + 2] = {"material table", "--costs file"};
        for (int i = 0; i < aa->nfiles; ++i)
            ins[2 + i] = aa->files[i], in_roles[2 + i] = "--materials file";
        if (out_files_distinct(&aa->plot, &out_role, 1, ins, in_roles, 2 + aa->nfiles, perr,
                               sizeof perr))
            return cli_fail(CMD, "%s", perr);
    }
    return 0;
}

/* ---- the material --------------------------------------------------------------------- */

/* Table entry `name` into *m (*e: the entry), or with no name the defaults; "unknown
 * material" names the nearest. 0, or the exit status after the message. */
static int material_find(const mat_table *table, const advise_args *aa, abrdf_material *m,
                         const mat_entry **e)
{
    *e = NULL;
    if (!aa->name) {
        abrdf_material_init(m);
        if (!aa->o.has_n && !aa->o.has_r)
            return cli_fail(CMD,
                            "give a MATERIAL name or at least --n or --r (abrdf advise --help)");
        return 0;
    }
    *e = mat_table_find(table, aa->name);
    if (!*e) {
        const char *near[5];
        int k = mat_table_nearest(table, aa->name, near, 5);
        char hint[256] = "";
        for (int i = 0; i < k; ++i) strcat(strcat(hint, i ? ", " : ""), near[i]);
        return k ? cli_fail(CMD, "unknown material '%s'; did you mean: %s? (abrdf advise --list)",
                            aa->name, hint)
                 : cli_fail(CMD,
                            "unknown material '%s'; abrdf advise --list shows the %d known ones",
                            aa->name, table->count);
    }
    *m = (*e)->m;
    return 0;
}

/* The command line's values over m; a photoreal special model with a narrower r range than
 * --r or --n gives is refused by the option that left it. 0, or the exit status after the
 * message. */
static int overrides_apply(const advise_overrides *o, abrdf_goal goal, abrdf_material *m)
{
    if (o->has_n) m->n = o->n;
    if (o->has_r) m->r = o->r;
    if (o->has_kd) memcpy(m->kd, o->kd, sizeof o->kd);
    if (o->has_ks) memcpy(m->ks, o->ks, sizeof o->ks);
    if (o->has_f0) memcpy(m->f0, o->f0, sizeof o->f0), m->eta = -1.0;
    if (o->has_eta) m->eta = o->eta;
    if (o->has_aniso) m->anisotropy = o->aniso;
    if (o->has_mel) m->melanin = o->mel;
    if (o->has_red) m->redness = o->red;
    if (o->has_type) m->type = o->type;
    const char *special;
    double rlo, rhi;
    if (!(goal == ABRDF_GOAL_PHOTOREAL && special_r_range(m->type, &special, &rlo, &rhi) &&
          (o->has_r || (o->has_n && !(m->r >= 0.0)))))
        return 0;
    double r_eff = o->has_r ? o->r : abrdf_alpha_g_to_r(abrdf_n_to_alpha_g(o->n));
    if (r_eff >= rlo && r_eff <= rhi) return 0;
    if (o->has_r)
        return cli_fail(CMD, "--r %g is outside [%g, %g]: photoreal %s uses %s", o->r, rlo, rhi,
                        abrdf_surface_name(m->type), special);
    return cli_fail(CMD,
                    "--n %g gives r = %.9g, outside [%g, %g]: photoreal %s uses %s; "
                    "give n <= %.0f",
                    o->n, r_eff, rlo, rhi, abrdf_surface_name(m->type), special, n_max_for_r(rlo));
}

/* ---- the command ---------------------------------------------------------------------- */

/* The flowchart's choice for m, printed with its trace. Returns the exit status. */
static int advise_flowchart(const advise_args *aa, const abrdf_material *m, const mat_entry *e,
                            const abrdf_costs *costs)
{
    int rc = 0;
    abrdf_selection sel;
    abrdf_params params;
    select_trace trace = SELECT_TRACE_INIT;
    abrdf_selection_init(&sel);
    abrdf_params_init(ABRDF_MODEL_NONE, &params);
    if (abrdf_select(m, aa->rq.goal, &aa->tol, costs, &sel, &params, select_trace_keep, &trace) !=
        ABRDF_OK) {
        rc = cli_fail(CMD, "%s", sel.message);
    } else if (trace.lost) {
        rc = cli_fail(CMD, "out of memory");
    } else {
        advise_print_selection(&sel, &params, &trace, e, &aa->tol, aa->json);
    }
    select_trace_free(&trace);
    return rc;
}

/* The material's choice (the flowchart's, or the budget's, or the --pareto front) from the
 * loaded tables. Returns the exit status. */
static int advise_material(const advise_args *aa, const mat_table *table)
{
    abrdf_material m;
    const mat_entry *e;
    int rc = material_find(table, aa, &m, &e);
    if (!rc) rc = overrides_apply(&aa->o, aa->rq.goal, &m);
    if (rc) return rc;
    abrdf_costs costs;
    if (aa->costs_file) {
        char err[512];
        if (costs_load(aa->costs_file, &costs, NULL, err, sizeof err))
            return cli_fail(CMD, "%s", err);
    }
    const abrdf_costs *c = aa->costs_file ? &costs : NULL;
    if (!(aa->rq.by_budget || aa->pareto)) return advise_flowchart(aa, &m, e, c);
    hair_store tables;
    if (aa->hair.sizes[0]) {
        long cpus = sysconf(_SC_NPROCESSORS_ONLN);
        hair_store_init(&tables, aa->hair.sizes, aa->hair.cache,
                        cpus > 0 ? (int)(cpus < 64 ? cpus : 64) : 1);
    }
    rc = advise_budget(&m, e, aa->rq.max_nmse, c, aa->json, aa->pareto, aa->plot,
                       aa->hair.sizes[0] ? &tables : NULL);
    if (aa->hair.sizes[0]) hair_store_free(&tables);
    return rc;
}

/* `abrdf advise FILE.gltf|.glb|.mtlx|.scene`: every pbr material of the file. Returns the
 * exit status. */
static int advise_file(const advise_args *aa)
{
    const advise_overrides *o = &aa->o;
    if (o->has_n || o->has_r || o->has_kd || o->has_ks || o->has_f0 || o->has_eta || o->has_aniso ||
        o->has_mel || o->has_red || o->has_type || aa->pareto || aa->list || aa->nfiles || aa->plot)
        return cli_fail(CMD,
                        "%s: a file's materials take --goal or --budget, --max-rel-error, "
                        "--max-abs-error, --costs and --json only",
                        aa->name);
    abrdf_costs costs;
    if (aa->costs_file) {
        char err[512];
        if (costs_load(aa->costs_file, &costs, NULL, err, sizeof err))
            return cli_fail(CMD, "%s", err);
    }
    return advise_asset(aa->name, &aa->rq, &aa->tol, aa->costs_file ? &costs : NULL, aa->json,
                        advise_print_selection);
}

int cmd_advise(int argc, char **argv)
{
    advise_args aa;
    int rc = advise_args_parse(argc, argv, &aa);
    if (aa.help) usage(stdout);
    if (rc || aa.help) return rc;
    if (aa.rules) {
        print_rules(aa.json);
        return 0;
    }
    if (aa.measured) return advise_measured(aa.measured, aa.rq.max_nmse, aa.json);
    if (aa.name && advise_is_asset(aa.name)) return advise_file(&aa);
    mat_table table = {NULL, 0, 0};
    rc = load_tables(&table, aa.files, aa.nfiles);
    if (!rc && aa.list)
        list_materials(&table, aa.json);
    else if (!rc)
        rc = advise_material(&aa, &table);
    mat_table_free(&table);
    return rc;
}
