/* advise_measured.c - `abrdf advise --measured FILE --budget CLASS|NMSE`: the budget mode
 * (docs/SELECTION.md, "The budget mode") with a measured table as the photoreal reference:
 * every general candidate fitted to the table (abrdf_fit_to, metric auto, as the budget mode
 * fits), its image NMSE predicted against it, its cost read from the built-in table; the
 * cheapest within the budget wins, costs within 15 % of it counting as equal (of those, the
 * lowest predicted NMSE), as abrdf_select_budget decides; the choice is then proved on the
 * image: the built-in renderer renders a lit sphere with the table and with the stand-in. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "budget_run.h"
#include "cli.h"
#include "measured_ref.h"
#include "metrics.h"
#include "render.h"
#include "scene.h"

#define CMD "advise"
#define NONE ABRDF_MODEL_NONE
/* abrdf_select_budget's COST_TIE (budget.c): calibrations move cost ratios by up to 15 %. */
#define COST_TIE 0.15
#define CAND_MAX 96
#define PROOF_SIZE 128 /* the proof's image (render_proof), pixels across */
#define PROOF_SPP 4    /* ... and its samples per pixel */

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
                       double secs, const abrdf_costs *costs, double proof)
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
    printf(", \"cost\": ");
    json_cost(abrdf_costs_get(costs, ABRDF_MEASURED));
    printf("},\n \"diffuse\": ");
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
    printf("},\n \"rendered\": ");
    if (proof >= 0.0) {
        printf("{\"nmse\": ");
        cli_json_number(stdout, proof);
        printf(", \"class\": \"%s\", \"width\": %d, \"height\": %d, \"spp\": %d}",
               abrdf_nmse_class(proof), PROOF_SIZE, PROOF_SIZE, PROOF_SPP);
    } else {
        printf("null");
    }
    printf(", \"seconds\": %.3f,\n \"candidates\": [", secs);
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
                        double secs, const abrdf_costs *costs, double proof)
{
    char desc[1400], nm[128], line[512];
    const char *bc = class_name(max);
    measured_ref_describe(ref, desc, sizeof desc);
    printf("measured   %s\n", desc);
    double table_cost = abrdf_costs_get(costs, ABRDF_MEASURED);
    if (table_cost > 0.0)
        printf("reference  measured (the table: the photoreal reference), %.3g ns/eval\n",
               table_cost);
    else
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
        printf("cost       %.3g ns/eval  [%s]", w->cost, costs->unit);
        if (table_cost > 0.0 && w->cost > 0.0)
            printf("; the table's lookup costs %.3gx as much", table_cost / w->cost);
        printf("\nrendered   NMSE %.3g (%s) against the table: abrdf's renderer, a %d x %d sphere "
               "under two lights, %d samples per pixel\n",
               proof, abrdf_nmse_class(proof), PROOF_SIZE, PROOF_SIZE, PROOF_SPP);
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

/* The proof: the prediction's default sphere as a renderer sees it (scenes/sphere.scene's
 * camera and key light, the prediction's fill light), rendered by abrdf's ray tracer with the
 * table and with the stand-in. */
static const char proof_scene[] =
    "camera position=0,0,4 look_at=0,0,0 up=0,1,0 fov=30 resolution=128,128\n"
    "light directional direction=-1,1,1 color=1,1,1 intensity=3\n"
    "light directional direction=1,0.3,0.5 color=1,1,1 intensity=1\n"
    "ambient 0\n"
    "material m model=lambert\n"
    "sphere material=m radius=1\n";

static int render_into(const scene *s, float *rgb, char *err, size_t err_size)
{
    render_options o;
    memset(&o, 0, sizeof o);
    o.width = o.height = PROOF_SIZE;
    o.spp = PROOF_SPP;
    o.threads = 1;
    render_scene rs;
    if (render_prepare(s, &o, &rs, err, err_size)) return -1;
    int rc = render_image(&rs, &o, rgb, NULL);
    render_release(&rs);
    if (rc) snprintf(err, err_size, "the proof's render failed");
    return rc;
}

/* The image NMSE of the stand-in w against the table: 0, or -1 with the message. The scene's
 * one material is the stand-in, then the table of ref (lent to the scene for the render and
 * taken back: the scene does not own it). */
static int render_proof(const measured_ref *ref, const measured_fit *w, double *nmse, char *err,
                        size_t err_size)
{
    scene s;
    if (scene_parse_text("(proof)", proof_scene, sizeof proof_scene - 1, &s, err, err_size))
        return -1;
    size_t n = (size_t)PROOF_SIZE * PROOF_SIZE * 3;
    float *a = malloc(n * sizeof *a), *b = malloc(n * sizeof *b);
    int rc = -1;
    if (!a || !b) {
        snprintf(err, err_size, "out of memory");
        goto done;
    }
    scene_material *m = &s.materials[0];
    m->lobe_count = 0;
    if (w->diffuse != NONE) m->lobes[m->lobe_count++] = w->diffuse;
    m->lobes[m->lobe_count++] = w->specular;
    m->params = w->params;
    if (render_into(&s, b, err, err_size)) goto done;
    scene_measured lent = {(char *)ref->path, ref->format, ref->table};
    s.measured = &lent;
    s.measured_count = 1;
    m->lobes[0] = ABRDF_MEASURED;
    m->lobe_count = 1;
    m->measured = 0;
    int failed = render_into(&s, a, err, err_size);
    s.measured = NULL; /* taken back before scene_free */
    s.measured_count = 0;
    if (failed) goto done;
    abrdf_metrics mt;
    abrdf_metrics_compute(b, a, PROOF_SIZE, PROOF_SIZE, 3, &mt);
    *nmse = mt.nmse;
    rc = 0;
done:
    free(a);
    free(b);
    scene_free(&s);
    return rc;
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
    double proof = -1.0;
    char err[1024];
    if (win >= 0 && render_proof(&ref, &c[win], &proof, err, sizeof err)) {
        fprintf(stderr, "abrdf %s: %s\n", CMD, err);
        free(work);
        free(c);
        measured_ref_free(&ref);
        return 1;
    }
    if (json)
        print_json(&ref, max_nmse, c, n, win, secs, &costs, proof);
    else
        print_human(&ref, max_nmse, c, n, win, secs, &costs, proof);
    free(work);
    free(c);
    measured_ref_free(&ref);
    return 0;
}
