/* test_budget.c - the selection's budget mode (abrdf_select_budget, abrdf_fit.h) by property:
 * the reference is the flowchart's photoreal choice (whose steps come first, unchanged); the
 * trace lists every candidate with its fitted block, predicted NMSE and cost; the winner is
 * the cheapest within the budget, costs within COST_TIE of the cheapest counted equal and
 * the lowest NMSE of those winning (recomputed here from the trace); a looser class never
 * costs more than that tolerance above a tighter one; the candidates follow the surface
 * class; bad budgets are rejected. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "abrdf_fit.h"
#include "test_util.h"

#define MAX_STEPS 160

typedef struct kept {
    abrdf_step_kind kind;
    abrdf_model model, diffuse;
    double value, threshold, cost;
    int passed, has_params;
    abrdf_params params;
} kept;

typedef struct run {
    abrdf_selection sel;
    abrdf_params params;
    int status, count;
    kept steps[MAX_STEPS];
} run;

static void keep(void *user, const abrdf_select_step *s)
{
    run *r = user;
    ck_assert_int_lt(r->count, MAX_STEPS);
    kept *k = &r->steps[r->count++];
    k->kind = s->kind;
    k->model = s->model;
    k->diffuse = s->diffuse;
    k->value = s->value;
    k->threshold = s->threshold;
    k->cost = s->cost;
    k->passed = s->passed;
    k->has_params = s->params != NULL;
    if (s->params) k->params = *s->params;
    ck_assert_ptr_nonnull(s->text);
}

/* metric: ABRDF_FIT_AUTO is the default; the tests that need many fits use L2 (a third of
 * the work; the selection's rules are the same). costs: NULL for the built-in table.
 * The sanitizer build (BUDGET_QUICK) fits on the coarsest direction set and predicts on a
 * sphere 16 samples across: the same code on a fraction of the work (minutes otherwise); the
 * Release build runs the defaults, whose values the checks were written for. */
/* The sanitizer build's quicker prediction (BUDGET_QUICK: budget_run_to says why) into b,
 * its view in v; the Release build keeps b's defaults. */
static void quick_view(abrdf_budget *b, abrdf_view *v)
{
#ifdef BUDGET_QUICK
    b->resolution = 1;
    abrdf_view_init(v);
    v->resolution = 16;
    b->view = v;
#else
    (void)b, (void)v;
#endif
}

static run *budget_run_to(const abrdf_material *m, double max_nmse, abrdf_fit_metric metric,
                          const abrdf_costs *costs, const abrdf_prepared *reference,
                          double reference_cost)
{
    run *r = calloc(1, sizeof *r);
    abrdf_budget b;
    abrdf_budget_init(&b);
    ck_assert_ptr_null(b.reference);
    ck_assert_double_eq(b.reference_cost, -1.0);
    b.max_nmse = max_nmse;
    b.metric = metric;
    b.reference = reference;
    b.reference_cost = reference_cost;
    abrdf_view v;
    quick_view(&b, &v);
    size_t ws = abrdf_fit_workspace_size(NULL, b.view);
    void *w = malloc(ws);
    abrdf_selection_init(&r->sel);
    abrdf_params_init(ABRDF_MODEL_NONE, &r->params);
    r->status = abrdf_select_budget(m, &b, costs, &r->sel, &r->params, keep, r, w, ws);
    free(w);
    return r;
}

static run *budget_run(const abrdf_material *m, double max_nmse, abrdf_fit_metric metric,
                       const abrdf_costs *costs)
{
    return budget_run_to(m, max_nmse, metric, costs, NULL, -1.0);
}

static run *budget_metric(const abrdf_material *m, double max_nmse, abrdf_fit_metric metric)
{
    return budget_run(m, max_nmse, metric, NULL);
}

static run *budget(const abrdf_material *m, double max_nmse)
{
    return budget_metric(m, max_nmse, ABRDF_FIT_AUTO);
}

static abrdf_material plastic(void)
{
    abrdf_material m;
    abrdf_material_init(&m);
    m.r = 0.3;
    m.eta = 1.5;
    m.kd[0] = 0.5, m.kd[1] = 0.1, m.kd[2] = 0.05;
    return m;
}

/* Costs closer than this fraction are one cost to the budget (budget.c, docs/SELECTION.md). */
#define COST_TIE 0.15

static int within(const kept *k, double max_nmse)
{
    return k->kind == ABRDF_STEP_FIT && k->cost >= 0.0 && k->value < max_nmse;
}

/* The winner, recomputed from the trace: of the FIT steps with a known cost below the budget
 * that cost at most (1 + COST_TIE) x the cheapest of them, the smallest NMSE (then the
 * smaller cost). */
static const kept *expected_winner(const run *r, double max_nmse)
{
    double cheapest = INFINITY;
    for (int i = 0; i < r->count; ++i)
        if (within(&r->steps[i], max_nmse) && r->steps[i].cost < cheapest)
            cheapest = r->steps[i].cost;
    const kept *best = NULL;
    for (int i = 0; i < r->count; ++i) {
        const kept *k = &r->steps[i];
        if (!within(k, max_nmse) || k->cost > cheapest * (1.0 + COST_TIE)) continue;
        if (!best || k->value < best->value || (k->value == best->value && k->cost < best->cost))
            best = k;
    }
    return best;
}

START_TEST(winner_is_cheapest_within_budget)
{
    abrdf_material m = plastic();
    double max = 2.5e-4;
    run *r = budget_metric(&m, max, ABRDF_FIT_L2);
    ck_assert_int_eq(r->status, ABRDF_OK);
    const kept *w = expected_winner(r, max);
    ck_assert_ptr_nonnull(w);
    ck_assert_int_eq(r->sel.specular, w->model);
    ck_assert_int_eq(r->sel.diffuse, w->diffuse);
    ck_assert_double_eq(r->sel.err_nmse, w->value);
    ck_assert_double_lt(r->sel.err_nmse, max);
    ck_assert_double_eq(r->sel.cost_total, w->cost);
    ck_assert_mem_eq(r->params.kd, w->params.kd, sizeof r->params.kd);
    /* every candidate's block is valid for its models (kept in the registry's ranges) */
    int fits = 0;
    for (int i = 0; i < r->count; ++i) {
        const kept *k = &r->steps[i];
        if (k->kind != ABRDF_STEP_FIT) continue;
        ++fits;
        ck_assert(k->has_params);
        ck_assert_int_eq(abrdf_params_check(k->model, &k->params, NULL, 0), ABRDF_OK);
        if (k->diffuse != ABRDF_MODEL_NONE)
            ck_assert_int_eq(abrdf_params_check(k->diffuse, &k->params, NULL, 0), ABRDF_OK);
        ck_assert_int_eq(k->passed, k->value < max && k->cost >= 0.0);
        ck_assert_double_eq(k->threshold, max);
    }
    ck_assert_int_gt(fits, 20);
    ck_assert_int_eq(r->sel.step_count, r->count);
    free(r);
}
END_TEST

/* The trace: the flowchart's photoreal steps as abrdf_select gives them, the reference, one
 * fit per candidate (the reference's own first, NMSE 0), the winner last. */
START_TEST(trace_order_and_reference)
{
    abrdf_material m = plastic();
    run *r = budget_metric(&m, 1e-3, ABRDF_FIT_L2);
    ck_assert_int_eq(r->status, ABRDF_OK);
    abrdf_selection photo;
    abrdf_params pp;
    abrdf_selection_init(&photo);
    abrdf_params_init(ABRDF_MODEL_NONE, &pp);
    ck_assert_int_eq(abrdf_select(&m, ABRDF_GOAL_PHOTOREAL, NULL, NULL, &photo, &pp, NULL, NULL),
                     ABRDF_OK);
    int i = 0;
    for (; i < photo.step_count; ++i) ck_assert_int_lt(r->steps[i].kind, ABRDF_STEP_REFERENCE);
    ck_assert_int_eq(r->steps[i].kind, ABRDF_STEP_REFERENCE);
    ck_assert_int_eq(r->steps[i].model, photo.specular);
    ck_assert_int_eq(r->steps[i].diffuse, photo.diffuse);
    ck_assert_int_eq(r->steps[i + 1].kind, ABRDF_STEP_FIT);
    ck_assert_int_eq(r->steps[i + 1].model, photo.specular);
    ck_assert_double_eq(r->steps[i + 1].value, 0.0);
    ck_assert_int_eq(r->steps[r->count - 1].kind, ABRDF_STEP_BUDGET);
    ck_assert_str_eq(abrdf_step_name(ABRDF_STEP_FIT), "fit");
    free(r);
}
END_TEST

/* Every budget sees the same fits, so a looser class never costs more: the choice at "none"
 * is the one the "noticeable" run's trace gives for 1e-4, and costs at least as much. A metal
 * needs no diffuse lobe (the default metric, AUTO). */
START_TEST(looser_budget_never_costs_more)
{
    abrdf_material m = plastic();
    run *loose = budget_metric(&m, 1e-3, ABRDF_FIT_L2);
    run *tight = budget_metric(&m, 1e-4, ABRDF_FIT_L2);
    ck_assert_int_eq(loose->status, ABRDF_OK);
    ck_assert_int_eq(tight->status, ABRDF_OK);
    ck_assert_double_le(loose->sel.cost_total, tight->sel.cost_total * (1.0 + COST_TIE));
    const kept *w = expected_winner(loose, 1e-4);
    ck_assert_ptr_nonnull(w);
    ck_assert_int_eq(tight->sel.specular, w->model);
    ck_assert_int_eq(tight->sel.diffuse, w->diffuse);
    ck_assert_double_eq(tight->sel.err_nmse, w->value);
    free(loose);
    free(tight);
    abrdf_material gold;
    abrdf_material_init(&gold);
    gold.r = 0.2;
    gold.kd[0] = gold.kd[1] = gold.kd[2] = 0.0;
    gold.f0[0] = 0.957, gold.f0[1] = 0.792, gold.f0[2] = 0.408;
    run *r = budget(&gold, 1e-4);
    ck_assert_int_eq(r->status, ABRDF_OK);
    ck_assert_int_eq(r->sel.diffuse, ABRDF_MODEL_NONE);
    ck_assert_int_eq(r->sel.specular, ABRDF_DISNEY_SPECULAR);
    ck_assert_double_lt(r->sel.err_nmse, 1e-12);
    free(r);
}
END_TEST

static int has_candidate(const abrdf_material *m, abrdf_model d, abrdf_model s)
{
    abrdf_model cd, cs;
    for (int i = 0; abrdf_budget_candidate(m, i, &cd, &cs) == ABRDF_OK; ++i)
        if (cd == d && cs == s) return 1;
    return 0;
}

/* Huang hair of data/materials.csv's hair_brown. */
static abrdf_material hair_brown(void)
{
    abrdf_material m;
    abrdf_material_init(&m);
    m.type = ABRDF_SURFACE_HAIR;
    m.r = 0.3;
    m.eta = 1.55;
    m.melanin = 0.73;
    return m;
}

START_TEST(candidates_follow_the_class)
{
    abrdf_material hair = hair_brown();
    abrdf_model d, s;
    ck_assert_int_eq(abrdf_budget_candidate(&hair, 0, &d, &s), ABRDF_OK);
    ck_assert_int_eq(s, ABRDF_HUANG); /* the reference first */
    ck_assert(has_candidate(&hair, ABRDF_MODEL_NONE, ABRDF_MARSCHNER));
    ck_assert(has_candidate(&hair, ABRDF_MODEL_NONE, ABRDF_KAJIYA_KAY));
    ck_assert(!has_candidate(&hair, ABRDF_LAMBERT, ABRDF_BLINN_PHONG));
    ck_assert_int_eq(abrdf_budget_candidate(&hair, 3, &d, &s), ABRDF_E_RANGE);
    abrdf_material m = plastic();
    ck_assert(has_candidate(&m, ABRDF_LAMBERT, ABRDF_F2));
    ck_assert(has_candidate(&m, ABRDF_LAMBERT, ABRDF_DISNEY_SPECULAR));
    ck_assert(!has_candidate(&m, ABRDF_MODEL_NONE, ABRDF_F2)); /* kd > 0 keeps a diffuse lobe */
    ck_assert(!has_candidate(&m, ABRDF_MODEL_NONE, ABRDF_MARSCHNER));
    abrdf_material metal;
    abrdf_material_init(&metal);
    metal.type = ABRDF_SURFACE_LAYERED_METAL;
    metal.r = 0.02;
    metal.kd[0] = metal.kd[1] = metal.kd[2] = 0.0;
    metal.layer_count = 2;
    metal.layers[0] = (abrdf_layer){1.5, 0.0, 0.3, {0, 0, 0}, 0.03};
    metal.layers[1] = (abrdf_layer){1.36, 2.45, 0.02, {0, 0, 0}, 0.0};
    ck_assert(has_candidate(&metal, ABRDF_DISNEY_SPECULAR, ABRDF_DISNEY_CLEARCOAT));
    ck_assert(has_candidate(&metal, ABRDF_MODEL_NONE, ABRDF_F_GE));
}
END_TEST

/* Hair: besides the fitted models, the reference at coarser entry grids (huang's quadrature,
 * docs/MODELS.md, "Convergence on an image"): entry_grid 5, 4, 3, 2, every other parameter the
 * reference's, costed by their VNDF nodes n1^2 (1 + n2^2) relative to the reference's; under
 * "slight" the winner is one of them (the fitted fibre models are predicted "significant"). */
START_TEST(hair_offers_coarser_quadratures)
{
    abrdf_material m = hair_brown();
    double max = 2.5e-4;
    run *r = budget_metric(&m, max, ABRDF_FIT_L2);
    ck_assert_int_eq(r->status, ABRDF_OK);
    const kept *ref = NULL, *grid[7] = {NULL};
    for (int i = 0; i < r->count; ++i) {
        const kept *k = &r->steps[i];
        if (k->kind != ABRDF_STEP_FIT || k->model != ABRDF_HUANG) continue;
        if (!ref) {
            ref = k; /* the reference's own step comes first */
            continue;
        }
        ck_assert_int_ge(k->params.entry_grid, 2);
        ck_assert_int_lt(k->params.entry_grid, ref->params.entry_grid);
        ck_assert_ptr_null(grid[k->params.entry_grid]);
        grid[k->params.entry_grid] = k;
        abrdf_params same = k->params;
        same.entry_grid = ref->params.entry_grid;
        ck_assert_mem_eq(&same, &ref->params, sizeof same);
        double n1 = k->params.entry_grid, n2 = k->params.internal_grid;
        ck_assert_double_eq_tol(k->cost, ref->cost * n1 * n1 * (1 + n2 * n2) / 360.0,
                                1e-12 * ref->cost);
    }
    ck_assert_ptr_nonnull(ref);
    ck_assert_int_eq(ref->params.entry_grid, 6);
    ck_assert_int_eq(ref->params.internal_grid, 3);
    for (int n1 = 2; n1 <= 5; ++n1) ck_assert_ptr_nonnull(grid[n1]);
    ck_assert_double_gt(grid[2]->value, grid[5]->value); /* coarser, further */
    const kept *w = expected_winner(r, max);
    ck_assert_ptr_nonnull(w);
    ck_assert_int_eq(w->model, ABRDF_HUANG);
    ck_assert_int_lt(w->params.entry_grid, 6);
    ck_assert_int_eq(r->params.entry_grid, w->params.entry_grid);
    ck_assert_double_lt(r->sel.cost_total, ref->cost);
    free(r);
}
END_TEST

/* Hair's photoreal choice tabulated (a small table: the checks are the budget's, not the
 * table's accuracy) and prepared, in values (n doubles, the caller frees) and *pr; *block
 * receives the choice's parameters. */
static double *hair_table(const abrdf_material *m, abrdf_params *block, abrdf_prepared *pr)
{
    abrdf_selection sel;
    abrdf_selection_init(&sel);
    abrdf_params_init(ABRDF_MODEL_NONE, block);
    ck_assert_int_eq(abrdf_select(m, ABRDF_GOAL_PHOTOREAL, NULL, NULL, &sel, block, NULL, NULL),
                     ABRDF_OK);
    ck_assert_int_eq(sel.specular, ABRDF_HUANG);
    const int sizes[4] = {6, 2, 8, 1};
    long n = 0;
    int rows = 0;
    ck_assert_int_eq(abrdf_huang_table_size(block, sizes, &n, &rows), ABRDF_OK);
    double *v = malloc((size_t)n * sizeof *v);
    ck_assert_int_eq(abrdf_huang_table_build(block, sizes, 0, rows, v), ABRDF_OK);
    ck_assert_int_eq(abrdf_prepare_huang_table(block, sizes, v, pr), ABRDF_OK);
    return v;
}

/* abrdf_budget.reference: a caller's prepared form of the photoreal choice (here huang from
 * a table) is what every candidate is predicted against, and candidate 0 at the caller's
 * cost. A coarser quadrature's trace value is its abrdf_predict_nmse_to against the table
 * (so the table, not the per-call quadrature, is the reference); at a cost below every other
 * candidate's the table itself wins, with NMSE 0 and the photoreal block; at an unknown cost
 * it cannot. A prepared object of another material or model is refused, naming why. */
START_TEST(caller_prepared_reference)
{
    abrdf_material m = hair_brown();
    abrdf_params block;
    abrdf_prepared table;
    double *v = hair_table(&m, &block, &table);
    run *r = budget_run_to(&m, 1.0, ABRDF_FIT_L2, NULL, &table, 1.0);
    ck_assert_int_eq(r->status, ABRDF_OK);
    ck_assert_int_eq(r->sel.specular, ABRDF_HUANG);
    ck_assert_int_eq(r->sel.diffuse, ABRDF_MODEL_NONE);
    ck_assert_double_eq(r->sel.err_nmse, 0.0);
    ck_assert_double_eq(r->sel.cost_total, 1.0);
    ck_assert_int_eq(r->params.entry_grid, block.entry_grid);
    ck_assert_double_eq(r->params.melanin, block.melanin);
    int coarser = 0;
    abrdf_budget b;
    abrdf_budget_init(&b);
    abrdf_view view;
    quick_view(&b, &view);
    size_t ws = abrdf_fit_workspace_size(NULL, b.view);
    void *w = malloc(ws);
    for (int i = 0; i < r->count; ++i) {
        const kept *k = &r->steps[i];
        if (k->kind != ABRDF_STEP_FIT || k->model != ABRDF_HUANG ||
            k->params.entry_grid == block.entry_grid)
            continue;
        double nmse = -1.0;
        ck_assert_int_eq(abrdf_predict_nmse_to(&table, ABRDF_MODEL_NONE, ABRDF_HUANG, &k->params,
                                               b.view, &nmse, w, ws),
                         ABRDF_OK);
        ck_assert_double_eq(k->value, nmse);
        ck_assert_double_gt(k->value, 0.0);
        ++coarser;
    }
    ck_assert_int_eq(coarser, 4);
    free(r);
    /* an unknown cost: some other candidate, with a cost and an error */
    r = budget_run_to(&m, 1.0, ABRDF_FIT_L2, NULL, &table, -1.0);
    ck_assert_int_eq(r->status, ABRDF_OK);
    ck_assert_double_gt(r->sel.err_nmse, 0.0);
    ck_assert_double_ge(r->sel.cost_total, 0.0);
    free(r);
    /* another material's table */
    abrdf_material other = hair_brown();
    other.melanin = 0.2;
    abrdf_params other_block;
    abrdf_prepared other_table;
    double *v2 = hair_table(&other, &other_block, &other_table);
    r = budget_run_to(&m, 1.0, ABRDF_FIT_L2, NULL, &other_table, 1.0);
    ck_assert_int_eq(r->status, ABRDF_E_MODEL);
    ck_assert_ptr_nonnull(strstr(r->sel.message, "melanin"));
    free(r);
    /* another model, and a photoreal pair */
    abrdf_params lp;
    abrdf_params_init(ABRDF_LAMBERT, &lp);
    abrdf_prepared lambert;
    ck_assert_int_eq(abrdf_prepare(ABRDF_LAMBERT, &lp, &lambert), ABRDF_OK);
    r = budget_run_to(&m, 1.0, ABRDF_FIT_L2, NULL, &lambert, 1.0);
    ck_assert_int_eq(r->status, ABRDF_E_MODEL);
    ck_assert_ptr_nonnull(strstr(r->sel.message, "prepared for lambert"));
    free(r);
    abrdf_material pm = plastic();
    r = budget_run_to(&pm, 1.0, ABRDF_FIT_L2, NULL, &lambert, 1.0);
    ck_assert_int_eq(r->status, ABRDF_E_MODEL);
    ck_assert_ptr_nonnull(strstr(r->sel.message, "disney_diffuse + disney_specular"));
    free(r);
    free(w);
    free(v);
    free(v2);
}
END_TEST

/* The tie rule on a cost table of its own: with every model at one cost the reference itself
 * (NMSE 0) wins; with the pairs on a cheaper diffuse lobe 12 % cheaper than the reference it
 * still does (a saving below COST_TIE is not one); at 20 % cheaper such a pair wins. */
START_TEST(costs_within_the_tie_are_one_cost)
{
    abrdf_material m = plastic();
    double max = 1e-3;
    abrdf_costs c;
    abrdf_costs_init(&c, "ns/eval (test)");
    for (int i = 0; i < abrdf_model_count(); ++i) abrdf_costs_set(&c, (abrdf_model)i, 1.0);
    run *r = budget_run(&m, max, ABRDF_FIT_L2, &c);
    ck_assert_int_eq(r->status, ABRDF_OK);
    ck_assert_int_eq(r->sel.diffuse, ABRDF_DISNEY_DIFFUSE); /* the flowchart's photoreal pair */
    ck_assert_int_eq(r->sel.specular, ABRDF_DISNEY_SPECULAR);
    ck_assert_double_eq(r->sel.err_nmse, 0.0);
    free(r);
    /* lambert at 0.76: the reference pair costs 2, lambert + a specular lobe 1.76 (2 is
     * within 15 % above 1.76) */
    abrdf_costs_set(&c, ABRDF_LAMBERT, 0.76);
    r = budget_run(&m, max, ABRDF_FIT_L2, &c);
    ck_assert_int_eq(r->sel.diffuse, ABRDF_DISNEY_DIFFUSE);
    ck_assert_double_eq(r->sel.err_nmse, 0.0);
    free(r);
    /* lambert at 0.6: the pairs with it cost 1.6, 20 % below 2; one of them within the budget */
    abrdf_costs_set(&c, ABRDF_LAMBERT, 0.6);
    r = budget_run(&m, max, ABRDF_FIT_L2, &c);
    ck_assert_int_eq(r->status, ABRDF_OK);
    ck_assert_int_eq(r->sel.diffuse, ABRDF_LAMBERT);
    ck_assert_double_eq(r->sel.cost_total, 1.6);
    const kept *w = expected_winner(r, max);
    ck_assert_ptr_nonnull(w);
    ck_assert_int_eq(r->sel.specular, w->model);
    ck_assert_double_eq(r->sel.err_nmse, w->value);
    ck_assert_double_gt(r->sel.err_nmse, 0.0);
    free(r);
}
END_TEST

START_TEST(bad_budget)
{
    abrdf_material m = plastic();
    double bad[] = {0.0, -1e-4, NAN, 2.0, INFINITY};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        run *r = budget(&m, bad[i]);
        ck_assert_int_eq(r->status, ABRDF_E_RANGE);
        ck_assert_ptr_nonnull(strstr(r->sel.message, "budget NMSE"));
        free(r);
    }
    double v;
    ck_assert_int_eq(abrdf_budget_class_find("slight", &v), ABRDF_OK);
    ck_assert_double_eq(v, 2.5e-4);
    ck_assert_int_eq(abrdf_budget_class_find("significant", &v), ABRDF_E_RANGE);
    abrdf_selection s;
    abrdf_selection_init(&s);
    char small[16];
    ck_assert_int_eq(abrdf_select_budget(&m, NULL, NULL, &s, NULL, NULL, NULL, small, sizeof small),
                     ABRDF_E_SIZE);
    ck_assert_ptr_nonnull(strstr(s.message, "workspace"));
}
END_TEST

int main(void)
{
    Suite *s = suite_create("budget");
    TCase *tc = tcase_create("budget");
    tcase_set_timeout(tc, 900);
    tcase_add_test(tc, winner_is_cheapest_within_budget);
    tcase_add_test(tc, trace_order_and_reference);
    tcase_add_test(tc, looser_budget_never_costs_more);
    tcase_add_test(tc, candidates_follow_the_class);
    tcase_add_test(tc, hair_offers_coarser_quadratures);
    tcase_add_test(tc, caller_prepared_reference);
    tcase_add_test(tc, costs_within_the_tie_are_one_cost);
    tcase_add_test(tc, bad_budget);
    suite_add_tcase(s, tc);
    return tu_run(s);
}
