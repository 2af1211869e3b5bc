/* cmd_bench.c - `abrdf bench`: for every model, its cost per evaluation on the float batch
 * path and on the double scalar path, as ratios to a powf Blinn-Phong loop timed in the
 * same run (tools/bench/measure.c), and its accuracy against the reference it replaces: NMSE on
 * a robot render, and for the Table-1 approximations the Table-2/3 errors. Prints a table
 * or JSON and can write the Pareto plot (error vs cost) as SVG. docs/BENCHMARKS.md. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "bench.h"
#include "bench_budget.h"
#include "cli.h"
#include "hair_table_args.h"
#include "measure.h"
#include "metrics.h"
#include "out_file.h"
#include "plot_grid.h"

/* The accuracy experiments (docs/BENCHMARKS.md, "Accuracy"). */
#define APPROX_N 100.0   /* exponent of Blinn-Phong and its Table-1 approximations */
#define SPEC_ALPHA_G 0.1 /* roughness of the Disney GGX reference for the Table-5 lobes */
#define SPEC_F0 0.04     /* F0 of the GGX reference (a dielectric) */
#define LAMBERT_KD 0.5   /* diffuse albedo under the specular lobes, and of the diffuse models */
#define DIFFUSE_R 0.5    /* roughness of the Disney diffuse reference */
/* The exponents searched for the Table-5 lobes (the paper's list, Sec. 4). */
static const double paper_n[] = {1,   5,   10,  20,  40,  60,  80,  100, 200,
                                 300, 400, 500, 600, 700, 800, 900, 950, 1000};
static const double quick_n[] = {10, 100, 1000};

typedef enum ref_kind {
    REF_NONE,
    REF_BLINN_PHONG,
    REF_DISNEY_SPECULAR,
    REF_DISNEY_DIFFUSE,
    REF_SELF
} ref_kind;
static const char *const ref_name[] = {"", "blinn_phong", "disney_specular", "disney_diffuse",
                                       "(reference)"};

typedef struct row {
    const abrdf_model_info *m;
    char vary; /* 'n', 'r' or 0: the parameter the cost is swept over */
    double vals[3];
    int nvals;
    double f_ns[3], d_ns[3]; /* per swept value (index 0 = default parameters when nvals = 1) */
    double f_def, d_def;     /* at the model's default parameters */
    double p_def;            /* ... on the prepared double path (abrdf_eval_prepared) */
    double u_def;            /* ... through abrdf_eval_prepared_unit */
    double o_def;            /* ... through abrdf_eval_prepared_float (one pair in float) */
    double i_def;            /* ... inlined (abrdf_inline.h): disney_specular only, else NAN */
    ref_kind ref;
    double nmse;           /* robot NMSE vs the reference, NAN if none */
    double best_n;         /* argmin n of the search (Table-5 lobes), NAN otherwise */
    double t2_rel, t3_abs; /* Table-2 max relative error (%) and Table-3 max abs error */
} row;

static int usage(void)
{
    printf("usage: abrdf bench [--json] [--plot OUT.svg] [--quick] [--render] [--size N]\n"
           "                   [--threads N] [--reps N]\n\n"
           "For every model: ns/eval of the float batch path (abrdf_eval_batch) and of the\n"
           "double scalar path (abrdf_eval, local frame; 'prepared': abrdf_eval_prepared after\n"
           "one abrdf_prepare; 'unit': abrdf_eval_prepared_unit on the same unit local\n"
           "directions; 'float1': abrdf_eval_prepared_float, one pair in float; disney_specular\n"
           "also inlined, abrdf_inline.h's abrdf_ggx_float_eval), as ratios\n"
           "to a powf Blinn-Phong loop on the\n"
           "same structure-of-arrays data timed in the same run (warm cache, median of the\n"
           "repetitions, swept over n or r where the model reads them), and the accuracy\n"
           "against the model it replaces: NMSE on a robot render (Table-1 approximations vs\n"
           "blinn_phong at n = 100, Table-5 lobes and cook_torrance vs disney_specular at\n"
           "alpha_g = 0.1 minimised over the paper's n, diffuse models vs disney_diffuse) and\n"
           "the Table-2/3 errors of the approximations. Then the hair reference (huang) per\n"
           "evaluation and per light, its lights sharing one view as in a render.\n"
           "  --json         JSON instead of the table\n"
           "  --plot FILE    write the Pareto plot (robot NMSE vs float cost) as SVG\n"
           "  --quick        fewer and shorter repetitions, small renders (for tests)\n"
           "  --render       instead: robot with full Disney vs adaptive photoreal and\n"
           "                 performance: render time ratios and NMSE per material; then\n"
           "                 each lobe's cost in a 16-light robot render (1 thread, 256x256)\n"
           "                 beside its per-eval cost, and the BRDFs' share of render time\n"
           "  --budget       instead: the mixed scene, photoreal vs the budget mode per\n"
           "                 Table-8 class: time ratios, image and per-material NMSE\n"
           "  --hair-table [--hair-table-sizes NT,NV,NP,SETS] [--hair-table-cache DIR]\n"
           "                 with --budget: huang from its table (built before the renders),\n"
           "                 photoreal's hair and the budgets' reference, beside photoreal\n"
           "                 with huang per call\n"
           "  --size N       image size of the renders (default 128; --render: the scene's)\n"
           "  --threads N    render threads (default: online CPUs)\n"
           "  --reps N       timed repetitions (default 7, quick 3)\n");
    return 0;
}

static void sweep(row *r, int quick)
{
    int pn, pr;
    abrdf_param_find("n", &pn);
    abrdf_param_find("r", &pr);
    r->nvals = 0;
    r->vary = 0;
    if (r->m->needs & ABRDF_NEEDS_INTEGRATION) return; /* default parameters only: slow */
    static const double nv[3] = {10, 100, 1000}, rv[3] = {0.1, 0.4, 0.9};
    for (int i = 0; i < r->m->param_count; ++i) {
        const abrdf_model_param *mp = &r->m->params[i];
        const double *v = mp->id == pn ? nv : mp->id == pr ? rv : NULL;
        if (!v) continue;
        r->vary = mp->id == pn ? 'n' : 'r';
        for (int k = 0; k < (quick ? 2 : 3); ++k) {
            double x = v[k] < mp->min ? mp->min : v[k] > mp->max ? mp->max : v[k];
            if (r->nvals == 0 || r->vals[r->nvals - 1] != x) r->vals[r->nvals++] = x;
        }
        return;
    }
}

static void set_vary(abrdf_params *p, char vary, double x)
{
    if (vary == 'n') p->n = x;
    if (vary == 'r') p->r = x;
}

static ref_kind reference_of(abrdf_model id)
{
    switch (id) {
    case ABRDF_F2:
    case ABRDF_F4:
    case ABRDF_F8:
    case ABRDF_F16:
    case ABRDF_FS:
    case ABRDF_FKV:
    case ABRDF_FKUB: return REF_BLINN_PHONG;
    case ABRDF_F_PHE:
    case ABRDF_F_BE:
    case ABRDF_F_2E:
    case ABRDF_F_16E:
    case ABRDF_F_GE:
    case ABRDF_F_CTPHE:
    case ABRDF_F_CT2E:
    case ABRDF_F_CT16E:
    case ABRDF_COOK_TORRANCE: return REF_DISNEY_SPECULAR;
    case ABRDF_LAMBERT:
    case ABRDF_LAMBERT_FRESNEL:
    case ABRDF_OREN_NAYAR: return REF_DISNEY_DIFFUSE;
    case ABRDF_BLINN_PHONG:
    case ABRDF_DISNEY_SPECULAR:
    case ABRDF_DISNEY_DIFFUSE: return REF_SELF;
    default: return REF_NONE;
    }
}

/* Parameters of a candidate or reference in the accuracy renders. */
static void accuracy_params(abrdf_model id, ref_kind ref, abrdf_params *p)
{
    abrdf_params_init(id, p);
    for (int c = 0; c < 3; ++c) p->kd[c] = LAMBERT_KD;
    if (ref == REF_BLINN_PHONG) {
        p->n = APPROX_N;
        for (int c = 0; c < 3; ++c) p->ks[c] = 0.5;
    } else if (ref == REF_DISNEY_SPECULAR) {
        /* Like Tables 6-7: lobes with a Fresnel factor get ks = 1 and F0; lobes without one
         * get ks = F0, the reference's reflectance at normal incidence. */
        int fresnel = (abrdf_model_get(id)->needs & ABRDF_NEEDS_FRESNEL) != 0;
        for (int c = 0; c < 3; ++c) p->ks[c] = fresnel ? 1.0 : SPEC_F0, p->f0[c] = SPEC_F0;
        p->r = sqrt(SPEC_ALPHA_G);
    } else if (ref == REF_DISNEY_DIFFUSE) {
        p->r = DIFFUSE_R;
    }
}

static int render_one(scene *s, int size, int threads, abrdf_model id, ref_kind ref,
                      const abrdf_params *p, float *rgb, char *err, size_t n)
{
    if (ref == REF_DISNEY_DIFFUSE)
        return bench_robot_lobes(s, size, threads, id, ABRDF_MODEL_NONE, p, rgb, NULL, err, n);
    return bench_robot_lobes(s, size, threads, ABRDF_LAMBERT, id, p, rgb, NULL, err, n);
}

static int accuracy(row *rows, int count, int size, int threads, int quick, char *err, size_t n)
{
    scene s;
    if (bench_robot_parse(&s, err, n)) return -1;
    size_t px = (size_t)size * (size_t)size * 3;
    float *ref[4] = {NULL}, *img = malloc(px * sizeof *img);
    int rc = -1;
    if (!img) goto out;
    static const abrdf_model ref_model[4] = {ABRDF_MODEL_NONE, ABRDF_BLINN_PHONG,
                                             ABRDF_DISNEY_SPECULAR, ABRDF_DISNEY_DIFFUSE};
    for (int k = 1; k < 4; ++k) {
        abrdf_params p;
        accuracy_params(ref_model[k], (ref_kind)k, &p);
        if (!(ref[k] = malloc(px * sizeof *ref[k]))) goto out;
        if (render_one(&s, size, threads, ref_model[k], (ref_kind)k, &p, ref[k], err, n)) goto out;
    }
    const double *ns = quick ? quick_n : paper_n;
    int nn = quick ? 3 : (int)(sizeof paper_n / sizeof *paper_n);
    for (int i = 0; i < count; ++i) {
        row *r = &rows[i];
        if (r->ref == REF_SELF) r->nmse = 0;
        if (r->ref == REF_NONE || r->ref == REF_SELF) continue;
        abrdf_params p;
        accuracy_params(r->m->id, r->ref, &p);
        int search = r->ref == REF_DISNEY_SPECULAR && r->m->id != ABRDF_COOK_TORRANCE;
        r->nmse = INFINITY;
        for (int j = 0; j < (search ? nn : 1); ++j) {
            if (search) p.n = ns[j];
            if (abrdf_params_check(r->m->id, &p, NULL, 0) != ABRDF_OK)
                continue; /* n out of range */
            if (render_one(&s, size, threads, r->m->id, r->ref, &p, img, err, n)) goto out;
            abrdf_metrics mt;
            if (abrdf_metrics_compute(img, ref[r->ref], size, size, 3, &mt) != ABRDF_METRICS_OK ||
                !mt.nmse_defined) {
                snprintf(err, n, "no NMSE for %s", r->m->name);
                goto out;
            }
            if (mt.nmse < r->nmse) r->nmse = mt.nmse, r->best_n = search ? ns[j] : NAN;
        }
        if (r->ref == REF_BLINN_PHONG) {
            abrdf_approx_error e;
            if (abrdf_approx_error_eval(r->m->id, APPROX_N, &e) == ABRDF_OK)
                r->t2_rel = e.max_rel_pct, r->t3_abs = e.max_abs;
        }
    }
    rc = 0;
out:
    if (rc && !err[0]) snprintf(err, n, "out of memory");
    for (int k = 0; k < 4; ++k) free(ref[k]);
    free(img);
    scene_free(&s);
    return rc;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* ---- output --------------------------------------------------------------------------- */

static void json_num(FILE *f, double v)
{
    if (isfinite(v))
        fprintf(f, "%.6g", v);
    else
        fputs("null", f);
}

/* The batch-path targets (docs/BENCHMARKS.md): slowest Table-1 approximation's speedup,
 * f_2e's, and full Disney (disney_diffuse + disney_specular) float cost in units. */
typedef struct targets {
    double approx_min_speedup, approx_max_speedup, f2e_speedup, disney_full_ratio;
    const char *approx_min_name, *approx_max_name;
} targets;

static targets compute_targets(const row *rows, int count, double unit_ns)
{
    targets t = {INFINITY, 0, NAN, 0, "", ""};
    for (int i = 0; i < count; ++i) {
        const row *r = &rows[i];
        double sp = unit_ns / r->f_def;
        if (r->ref == REF_BLINN_PHONG && sp < t.approx_min_speedup)
            t.approx_min_speedup = sp, t.approx_min_name = r->m->name;
        if (r->ref == REF_BLINN_PHONG && sp > t.approx_max_speedup)
            t.approx_max_speedup = sp, t.approx_max_name = r->m->name;
        if (r->m->id == ABRDF_F_2E) t.f2e_speedup = unit_ns / r->f_def;
        if (r->m->id == ABRDF_DISNEY_DIFFUSE || r->m->id == ABRDF_DISNEY_SPECULAR)
            t.disney_full_ratio += r->f_def / unit_ns;
    }
    return t;
}

/* The hair reference per evaluation and per light: huang at its defaults on the float batch
 * path, pairs in runs of one view (HAIR_LIGHTS lights per view, as a renderer hands a shading
 * point's lights over, against one light per view), on the same views. */
#define HAIR_LIGHTS 4
typedef struct hair_cost {
    double eval_ns;  /* one light per view */
    double light_ns; /* HAIR_LIGHTS lights per view: ns per light */
} hair_cost;

static int time_hair(const measure_opts *mo, hair_cost *h)
{
    abrdf_params p;
    abrdf_params_init(ABRDF_HUANG, &p);
    fprintf(stderr, " huang (per light)");
    h->eval_ns = measure_shared_view_ns(ABRDF_HUANG, &p, 1, HAIR_LIGHTS, mo);
    h->light_ns = measure_shared_view_ns(ABRDF_HUANG, &p, HAIR_LIGHTS, HAIR_LIGHTS, mo);
    return h->eval_ns > 0.0 && h->light_ns > 0.0 ? 0 : -1;
}

static void print_json(FILE *f, const row *rows, int count, double unit_ns, double drift,
                       const measure_opts *mo, int size, const hair_cost *h)
{
    fprintf(f,
            "{\"unit\": \"powf_blinn_phong\", \"unit_spread\": %.4g, \"pairs\": %zu, \"reps\": %d, "
            "\"robot_size\": %d, \"approx_n\": %g, \"spec_alpha_g\": %g,\n \"unit_ns\": %.4g,\n "
            "\"models\": [",
            drift, mo->pairs, mo->reps, size, APPROX_N, SPEC_ALPHA_G, unit_ns);
    for (int i = 0; i < count; ++i) {
        const row *r = &rows[i];
        fprintf(f,
                "%s\n  {\"name\": \"%s\", \"float_ratio\": %.6g, \"double_ratio\": %.6g, "
                "\"prepared_ratio\": %.6g, \"prepared_unit_ratio\": %.6g, "
                "\"prepared_float_ratio\": %.6g, \"float_speedup\": %.6g, ",
                i ? "," : "", r->m->name, r->f_def / unit_ns, r->d_def / unit_ns,
                r->p_def / unit_ns, r->u_def / unit_ns, r->o_def / unit_ns, unit_ns / r->f_def);
        if (isfinite(r->i_def))
            fprintf(f, "\"inline_ratio\": %.6g, \"sweep\": ", r->i_def / unit_ns);
        else
            fprintf(f, "\"inline_ratio\": null, \"sweep\": ");
        if (r->vary) {
            fprintf(f, "{\"param\": \"%c\", \"values\": [", r->vary);
            for (int k = 0; k < r->nvals; ++k) fprintf(f, "%s%g", k ? ", " : "", r->vals[k]);
            fprintf(f, "], \"float_ratio\": [");
            for (int k = 0; k < r->nvals; ++k)
                fprintf(f, "%s%.6g", k ? ", " : "", r->f_ns[k] / unit_ns);
            fprintf(f, "], \"double_ratio\": [");
            for (int k = 0; k < r->nvals; ++k)
                fprintf(f, "%s%.6g", k ? ", " : "", r->d_ns[k] / unit_ns);
            fprintf(f, "]}");
        } else {
            fprintf(f, "null");
        }
        fprintf(f, ", \"reference\": ");
        if (r->ref == REF_NONE)
            fputs("null", f);
        else
            fprintf(f, "\"%s\"", ref_name[r->ref]);
        fprintf(f, ", \"robot_nmse\": ");
        json_num(f, r->nmse);
        fprintf(f, ", \"best_n\": ");
        json_num(f, r->best_n);
        fprintf(f, ", \"table2_max_rel_pct\": ");
        json_num(f, r->t2_rel);
        fprintf(f, ", \"table3_max_abs\": ");
        json_num(f, r->t3_abs);
        fputc('}', f);
    }
    targets t = compute_targets(rows, count, unit_ns);
    fprintf(f,
            "\n], \"huang_shared_view\": {\"lights\": %d, \"ns_per_eval\": %.6g, "
            "\"ns_per_light\": %.6g},\n \"targets\": {\"approx_min_speedup\": %.6g, "
            "\"approx_max_speedup\": %.6g, \"approx_target\": 20, \"f_2e_speedup\": %.6g, "
            "\"f_2e_target\": 10, \"full_disney_ratio\": %.6g, \"full_disney_target\": 3}}\n",
            HAIR_LIGHTS, h->eval_ns, h->light_ns, t.approx_min_speedup, t.approx_max_speedup,
            t.f2e_speedup, t.disney_full_ratio);
}

static void print_table(FILE *f, const row *rows, int count, double unit_ns, double drift,
                        const measure_opts *mo, int size, const hair_cost *h)
{
    fprintf(
        f,
        "Cost: ns/eval as a ratio to powf Blinn-Phong (the unit), each model divided by the unit\n"
        "timed just before it (spread of the unit's timings (max - min) / median: %.1f%%),\n"
        "%zu pairs, median of %d. 'speedup' = unit / float cost; 'double' = abrdf_eval per pair,\n"
        "'prepared' = abrdf_eval_prepared per pair (prepared once), 'unit' = "
        "abrdf_eval_prepared_unit, 'float1' = abrdf_eval_prepared_float.\n"
        "Accuracy: robot %dx%d NMSE vs the reference; Table 2 = max rel. error %% in the "
        "highlight\n"
        "zone, Table 3 = max abs. error, both at n = %g.\n\n",
        100 * drift, mo->pairs, mo->reps, size, size, APPROX_N);
    fprintf(f, "%-22s %8s %8s %8s %8s %8s %8s %-14s %-16s %10s %6s %8s %8s\n", "model", "float",
            "speedup", "double", "prepared", "unit", "float1", "float range", "reference",
            "robot NMSE", "n", "Table 2", "Table 3");
    for (int i = 0; i < count; ++i) {
        const row *r = &rows[i];
        char range[32] = "", nm[16] = "", bn[16] = "", t2[16] = "", t3[16] = "";
        if (r->vary) {
            double lo = INFINITY, hi = 0;
            for (int k = 0; k < r->nvals; ++k) lo = fmin(lo, r->f_ns[k]), hi = fmax(hi, r->f_ns[k]);
            snprintf(range, sizeof range, "%.3g-%.3g %c", lo / unit_ns, hi / unit_ns, r->vary);
        }
        if (isfinite(r->nmse)) snprintf(nm, sizeof nm, "%.3g", r->nmse);
        if (isfinite(r->best_n)) snprintf(bn, sizeof bn, "%g", r->best_n);
        if (isfinite(r->t2_rel)) snprintf(t2, sizeof t2, "%.3g", r->t2_rel);
        if (isfinite(r->t3_abs)) snprintf(t3, sizeof t3, "%.3g", r->t3_abs);
        fprintf(f, "%-22s %8.3f %8.2f %8.3f %8.3f %8.3f %8.3f %-14s %-16s %10s %6s %8s %8s\n",
                r->m->name, r->f_def / unit_ns, unit_ns / r->f_def, r->d_def / unit_ns,
                r->p_def / unit_ns, r->u_def / unit_ns, r->o_def / unit_ns, range, ref_name[r->ref],
                nm, bn, t2, t3);
    }
    for (int i = 0; i < count; ++i)
        if (isfinite(rows[i].i_def))
            fprintf(f, "%s inlined (abrdf_inline.h, abrdf_ggx_float_eval per pair): %.3f\n",
                    rows[i].m->name, rows[i].i_def / unit_ns);
    targets t = compute_targets(rows, count, unit_ns);
    fprintf(f,
            "\nTargets (float batch path vs the unit):\n"
            "  Table-1 approximations >= 20x faster: %.2fx (%s) to %.2fx (%s)  %s\n"
            "  f_2e >= 10x faster: %.2fx  %s\n"
            "  full Disney (disney_diffuse + disney_specular) <= 3x the unit: %.2fx  %s\n",
            t.approx_min_speedup, t.approx_min_name, t.approx_max_speedup, t.approx_max_name,
            t.approx_min_speedup >= 20 ? "met" : "missed", t.f2e_speedup,
            t.f2e_speedup >= 10 ? "met" : "missed", t.disney_full_ratio,
            t.disney_full_ratio <= 3 ? "met" : "missed");
    fprintf(f,
            "\nHair (huang, defaults, float batch path): %.1f us per evaluation with one light per "
            "view;\n%.1f us per light with %d lights per view (a shading point's lights, one run "
            "of wo):\n%.2fx less per light (tools/bench/hair_cost.sh compares renders with an "
            "older build).\n",
            1e-3 * h->eval_ns, 1e-3 * h->light_ns, HAIR_LIGHTS, h->eval_ns / h->light_ns);
}

/* Pareto plot: robot NMSE (log) vs float cost ratio (log), one colour per reference, the
 * reference's own cost as a dashed line, each group's Pareto front as a staircase. */
static void write_plot(FILE *f, const row *rows, int count, double unit_ns)
{
    const double W = 760, H = 520, L = 70, Rm = 170, T = 30, B = 60;
    double x0 = 1e9, x1 = 0, y0 = 1e9, y1 = 0;
    for (int i = 0; i < count; ++i) {
        const row *r = &rows[i];
        if (r->ref == REF_NONE) continue;
        double x = r->f_def / unit_ns;
        x0 = fmin(x0, x), x1 = fmax(x1, x);
        if (r->ref != REF_SELF && r->nmse > 0 && isfinite(r->nmse))
            y0 = fmin(y0, r->nmse), y1 = fmax(y1, r->nmse);
    }
    if (!(x1 > 0) || !(y1 > 0)) y0 = 1e-6, y1 = 1;
    double lx0 = floor(log10(x0)), lx1 = ceil(log10(x1)), ly0 = floor(log10(y0)),
           ly1 = ceil(log10(y1));
    if (lx1 <= lx0) lx1 = lx0 + 1;
    if (ly1 <= ly0) ly1 = ly0 + 1;
#define PX(v) (L + (log10(v) - lx0) / (lx1 - lx0) * (W - L - Rm))
#define PY(v) (H - B - (log10(v) - ly0) / (ly1 - ly0) * (H - T - B))
    fprintf(f,
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%g\" height=\"%g\" "
            "font-family=\"sans-serif\" font-size=\"11\">\n"
            "<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n",
            W, H);
    plot_grid g = {W, H, L, Rm, T, B, lx0, lx1, ly0, ly1, -INFINITY, INFINITY};
    plot_grid_write(f, &g);
    fprintf(f,
            "<rect x=\"%g\" y=\"%g\" width=\"%g\" height=\"%g\" fill=\"none\" stroke=\"black\"/>\n",
            L, T, W - L - Rm, H - T - B);
    fprintf(f,
            "<text x=\"%g\" y=\"%g\" text-anchor=\"middle\">cost per evaluation, float batch path "
            "(x powf Blinn-Phong)</text>\n",
            (L + W - Rm) / 2, H - 20);
    fprintf(f,
            "<text transform=\"translate(18,%g) rotate(-90)\" text-anchor=\"middle\">robot NMSE vs "
            "reference</text>\n",
            (T + H - B) / 2);
    /* The paper's Table-8 classes as horizontal lines, where they fall in range. */
    const double cls[3] = {ABRDF_NMSE_SLIGHT, ABRDF_NMSE_NOTICEABLE, ABRDF_NMSE_SIGNIFICANT};
    for (int k = 0; k < 3; ++k)
        if (log10(cls[k]) >= ly0 && log10(cls[k]) <= ly1)
            fprintf(f,
                    "<line x1=\"%g\" y1=\"%.1f\" x2=\"%g\" y2=\"%.1f\" stroke=\"#c80\" "
                    "stroke-dasharray=\"2,3\"/>"
                    "<text x=\"%g\" y=\"%.1f\" fill=\"#c80\">%s</text>\n",
                    L, PY(cls[k]), W - Rm, PY(cls[k]), W - Rm + 4, PY(cls[k]) + 4,
                    abrdf_nmse_class(cls[k]));
    static const char *const colour[] = {"", "#1f77b4", "#d62728", "#2ca02c"};
    for (int g = 1; g <= 3; ++g) {
        /* the reference's cost */
        for (int i = 0; i < count; ++i)
            if (rows[i].ref == REF_SELF && !strcmp(rows[i].m->name, ref_name[g])) {
                double x = PX(rows[i].f_def / unit_ns);
                fprintf(f,
                        "<line x1=\"%.1f\" y1=\"%g\" x2=\"%.1f\" y2=\"%g\" stroke=\"%s\" "
                        "stroke-dasharray=\"6,4\"/>"
                        "<text x=\"%.1f\" y=\"%g\" fill=\"%s\" transform=\"rotate(-90 %.1f "
                        "%g)\">%s (reference)</text>\n",
                        x, T, x, H - B, colour[g], x - 3, H - B - 5, colour[g], x - 3, H - B - 5,
                        ref_name[g]);
            }
        /* Pareto front: sorted by cost, keep points that lower the error */
        int idx[64], n = 0;
        for (int i = 0; i < count && n < 64; ++i)
            if ((int)rows[i].ref == g && rows[i].nmse > 0 && isfinite(rows[i].nmse)) idx[n++] = i;
        for (int a = 1; a < n; ++a)
            for (int b = a; b > 0 && rows[idx[b]].f_def < rows[idx[b - 1]].f_def; --b) {
                int t = idx[b];
                idx[b] = idx[b - 1];
                idx[b - 1] = t;
            }
        double best = INFINITY;
        fprintf(f, "<polyline fill=\"none\" stroke=\"%s\" stroke-opacity=\"0.5\" points=\"",
                colour[g]);
        double py = 0;
        int first = 1;
        for (int a = 0; a < n; ++a) {
            const row *r = &rows[idx[a]];
            if (r->nmse >= best) continue;
            double x = PX(r->f_def / unit_ns), y = PY(r->nmse);
            if (!first) fprintf(f, "%.1f,%.1f ", x, py);
            fprintf(f, "%.1f,%.1f ", x, y);
            py = y, first = 0, best = r->nmse;
        }
        fprintf(f, "\"/>\n");
        for (int a = 0; a < n; ++a) {
            const row *r = &rows[idx[a]];
            double x = PX(r->f_def / unit_ns), y = PY(r->nmse);
            fprintf(f,
                    "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"4\" fill=\"%s\"/><text x=\"%.1f\" "
                    "y=\"%.1f\">%s</text>\n",
                    x, y, colour[g], x + 6, y - 4, r->m->name);
        }
        fprintf(f,
                "<circle cx=\"%g\" cy=\"%g\" r=\"4\" fill=\"%s\"/><text x=\"%g\" y=\"%g\">vs "
                "%s</text>\n",
                W - Rm + 10, T + 80 + 18.0 * g, colour[g], W - Rm + 18, T + 84 + 18.0 * g,
                ref_name[g]);
    }
#undef PX
#undef PY
    fprintf(f, "</svg>\n");
}

/* ---- the command ------------------------------------------------------------------------ */

#define CMD "bench"

/* What the command line asks for. */
typedef struct bench_args {
    int help; /* --help given: print the usage and stop */
    int json, quick, render, budget;
    hair_table_args hair;     /* --hair-table[-sizes, -cache] (with --budget) */
    const char *plot;         /* --plot FILE, or NULL */
    long size, threads, reps; /* 0: the defaults (threads: online CPUs, after parsing) */
} bench_args;

/* The command line into ba: 0 (ba->help: print the usage), or the exit status after the
 * message. */
static int bench_args_parse(int argc, char **argv, bench_args *ba)
{
    memset(ba, 0, sizeof *ba);
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        if (cli_is_help(a)) {
            ba->help = 1;
            return 0;
        }
        int hair = hair_table_option(&ba->hair, CMD, argc, argv, &i);
        if (hair < 0) return -hair;
        if (hair) continue;
        if (!strcmp(a, "--json"))
            ba->json = 1;
        else if (!strcmp(a, "--quick"))
            ba->quick = 1;
        else if (!strcmp(a, "--render"))
            ba->render = 1;
        else if (!strcmp(a, "--budget"))
            ba->budget = 1;
        else if (!strcmp(a, "--plot")) {
            if (i + 1 >= argc) return cli_fail(CMD, "--plot needs a file name");
            ba->plot = argv[++i];
        } else if (!strcmp(a, "--size")) {
            if (i + 1 >= argc || !cli_parse_int(argv[++i], 8, 8192, &ba->size))
                return cli_fail(CMD, "--size needs a whole number in [8, 8192]");
        } else if (!strcmp(a, "--threads")) {
            if (i + 1 >= argc || !cli_parse_int(argv[++i], 1, 256, &ba->threads))
                return cli_fail(CMD, "--threads needs a whole number in [1, 256]");
        } else if (!strcmp(a, "--reps")) {
            if (i + 1 >= argc || !cli_parse_int(argv[++i], 1, 1000, &ba->reps))
                return cli_fail(CMD, "--reps needs a whole number in [1, 1000]");
        } else {
            return cli_fail(CMD,
                            "unknown argument '%s'; options: --json --plot FILE --quick --render "
                            "--budget --size N --threads N --reps N --hair-table "
                            "--hair-table-sizes S --hair-table-cache DIR",
                            a);
        }
    }
    if (ba->render && ba->plot)
        return cli_fail(CMD, "--plot draws the model benchmark; it does not go with --render");
    int rc = hair_table_check(&ba->hair, CMD);
    if (rc) return rc;
    if (ba->hair.sizes[0] && !ba->budget)
        return cli_fail(CMD, "--hair-table goes with --budget (abrdf render takes it too)");
    if (ba->threads == 0) {
        long cpus = sysconf(_SC_NPROCESSORS_ONLN);
        ba->threads = cpus > 0 ? (cpus < 64 ? cpus : 64) : 1;
    }
    return 0;
}

/* A row per registered model, its reference and sweep set (the measurements NaN): the count. */
static int rows_fill(row *rows, int quick)
{
    int count = 0;
    for (int i = 0; i < abrdf_model_count(); ++i) {
        const abrdf_model_info *m = abrdf_model_get((abrdf_model)i);
        if (!m) continue;
        row *r = &rows[count++];
        r->m = m;
        r->ref = reference_of(m->id);
        r->nmse = r->best_n = r->t2_rel = r->t3_abs = NAN;
        sweep(r, quick);
    }
    return count;
}

/* Every model's costs into rows, ns per evaluation; *unit_ns: the median unit, *drift: the
 * units' spread relative to it. 0, or -1 out of memory. */
static int time_models(row *rows, int count, measure_set *set, const measure_opts *mo,
                       double *unit_ns, double *drift)
{
    /* Cost: the unit is timed again just before each model, and each model's ns are
     * divided by that neighbouring unit, so that a change of the machine's load or clock
     * during the run cancels in the ratios. Stored below as ns in units of the median unit. */
    fprintf(stderr, "abrdf bench: timing");
    measure_unit_ns(set, mo); /* warm-up: clock frequency, page faults, caches */
    double *units = malloc(sizeof(double) * (size_t)count);
    if (!units) return -1;
    for (int i = 0; i < count; ++i) {
        row *r = &rows[i];
        fprintf(stderr, " %s", r->m->name);
        double u = units[i] = measure_unit_ns(set, mo);
        abrdf_params p;
        abrdf_params_init(r->m->id, &p);
        r->f_def = measure_model_params_ns(set, r->m->id, &p, 0, mo) / u;
        r->d_def = measure_model_params_ns(set, r->m->id, &p, 1, mo) / u;
        r->p_def = measure_model_params_ns(set, r->m->id, &p, 2, mo) / u;
        r->u_def = measure_model_params_ns(set, r->m->id, &p, 3, mo) / u;
        r->o_def = measure_model_params_ns(set, r->m->id, &p, 4, mo) / u;
        r->i_def = r->m->id == ABRDF_DISNEY_SPECULAR
                       ? measure_model_params_ns(set, r->m->id, &p, 5, mo) / u
                       : NAN;
        for (int k = 0; k < r->nvals; ++k) {
            set_vary(&p, r->vary, r->vals[k]);
            r->f_ns[k] = measure_model_params_ns(set, r->m->id, &p, 0, mo) / u;
            r->d_ns[k] = measure_model_params_ns(set, r->m->id, &p, 1, mo) / u;
        }
    }
    double umin = INFINITY, umax = 0;
    for (int i = 0; i < count; ++i) umin = fmin(umin, units[i]), umax = fmax(umax, units[i]);
    qsort(units, (size_t)count, sizeof(double), cmp_double);
    double u = units[count / 2];
    *unit_ns = u;
    *drift = (umax - umin) / u;
    free(units);
    for (int i = 0; i < count; ++i) { /* back to ns of the median unit */
        row *r = &rows[i];
        r->f_def *= u, r->d_def *= u, r->p_def *= u, r->u_def *= u, r->o_def *= u, r->i_def *= u;
        for (int k = 0; k < r->nvals; ++k) r->f_ns[k] *= u, r->d_ns[k] *= u;
    }
    return 0;
}

/* The model benchmark: costs, then accuracy on robot renders; the table or JSON, and the
 * plot. Returns the exit status. */
static int bench_models(const bench_args *ba)
{
    long size = ba->size ? ba->size : ba->quick ? 48 : 128;
    /* The plot exists (as a temporary file) before the measurement: a directory that is
     * missing or read-only fails now. */
    char err[1024] = "";
    out_file plot_out = OUT_FILE_INIT;
    out_file *const plot_files[1] = {&plot_out};
    if (ba->plot && out_file_open(&plot_out, ba->plot, err, sizeof err)) {
        fprintf(stderr, "abrdf bench: %s\n", err);
        return 1;
    }
    measure_opts mo;
    measure_defaults(&mo, ba->quick);
    if (ba->quick) mo.pairs = 1024, mo.integrating_pairs = 16;
    if (ba->reps) mo.reps = (int)ba->reps;
    measure_set *set = measure_set_new(mo.pairs);
    row *rows = calloc((size_t)abrdf_model_count(), sizeof *rows);
    int count = set && rows ? rows_fill(rows, ba->quick) : 0;
    double unit_ns = 0.0, drift = 0.0;
    hair_cost hair = {0.0, 0.0};
    if (!set || !rows || time_models(rows, count, set, &mo, &unit_ns, &drift) ||
        time_hair(&mo, &hair)) {
        measure_set_free(set);
        free(rows);
        out_file_discard(&plot_out);
        fprintf(stderr, "abrdf bench: out of memory\n");
        return 1;
    }
    measure_set_free(set);
    fprintf(stderr, "\nabrdf bench: robot renders\n");
    int rc = 0;
    if (accuracy(rows, count, (int)size, (int)ba->threads, ba->quick, err, sizeof err)) {
        fprintf(stderr, "abrdf bench: %s\n", err);
        rc = 1;
    } else {
        if (ba->json)
            print_json(stdout, rows, count, unit_ns, drift, &mo, (int)size, &hair);
        else
            print_table(stdout, rows, count, unit_ns, drift, &mo, (int)size, &hair);
        if (ba->plot) {
            write_plot(plot_out.f, rows, count, unit_ns);
            if (out_file_close(&plot_out, err, sizeof err) ||
                out_file_commit(plot_files, 1, err, sizeof err)) {
                fprintf(stderr, "abrdf bench: %s\n", err);
                rc = 1;
            }
        }
    }
    out_file_discard(&plot_out);
    free(rows);
    return rc;
}

int cmd_bench(int argc, char **argv)
{
    bench_args ba;
    int rc = bench_args_parse(argc, argv, &ba);
    if (rc || ba.help) return ba.help ? usage() : rc;
    int quick = ba.quick;
    long size = ba.size, reps = ba.reps;
    if (ba.budget) { /* bench_budget.c: the budget mode on the mixed scene */
        hair_store tables;
        if (ba.hair.sizes[0])
            hair_store_init(&tables, ba.hair.sizes, ba.hair.cache, (int)ba.threads);
        rc = bench_budget_report(stdout, ba.json,
                                 (int)(size    ? size
                                       : quick ? 128
                                               : 0),
                                 1,
                                 (int)(reps    ? reps
                                       : quick ? 1
                                               : 3),
                                 (int)ba.threads, ba.hair.sizes[0] ? &tables : NULL);
        if (ba.hair.sizes[0]) hair_store_free(&tables);
        return rc;
    }
    if (ba.render)
        return bench_render_report(stdout, ba.json,
                                   (int)(size    ? size
                                         : quick ? 64
                                                 : 0),
                                   (int)(reps    ? reps
                                         : quick ? 1
                                                 : 5),
                                   (int)ba.threads, quick ? 24 : 256, quick);
    return bench_models(&ba);
}
