/* test_budget_once.c - a budget selection runs the flowchart once per material. This suite
 * links the static library with the linker's --wrap=abrdf_select, so every call the budget
 * code (budget.c) makes to abrdf_select goes through __wrap_abrdf_select, which counts it;
 * the count must be 1 for abrdf_select_budget and for abrdf_budget_candidate, whatever the
 * surface class, and the budget's result must be the one the counted flowchart chose. */
#include <stdlib.h>

#include "abrdf_fit.h"
#include "test_util.h"

int __real_abrdf_select(const abrdf_material *m, abrdf_goal goal, const abrdf_tolerance *tol,
                        const abrdf_costs *costs, abrdf_selection *out, abrdf_params *params,
                        abrdf_select_trace_fn trace, void *trace_user);

static int calls;

int __wrap_abrdf_select(const abrdf_material *m, abrdf_goal goal, const abrdf_tolerance *tol,
                        const abrdf_costs *costs, abrdf_selection *out, abrdf_params *params,
                        abrdf_select_trace_fn trace, void *trace_user)
{
    ++calls;
    return __real_abrdf_select(m, goal, tol, costs, out, params, trace, trace_user);
}

typedef struct counted {
    int reference_steps; /* ABRDF_STEP_REFERENCE: one per flowchart run the budget reports */
    int flowchart_steps; /* steps of the flowchart itself (before the budget's) */
} counted;

static void count(void *user, const abrdf_select_step *s)
{
    counted *c = user;
    if (s->kind == ABRDF_STEP_REFERENCE) ++c->reference_steps;
    if (s->kind < ABRDF_STEP_REFERENCE) ++c->flowchart_steps;
}

/* One material per surface class of the flowchart. */
static abrdf_material material(abrdf_surface type)
{
    abrdf_material m;
    abrdf_material_init(&m);
    m.type = type;
    m.r = type == ABRDF_SURFACE_HAIR ? 0.3 : 0.25;
    m.eta = 1.5;
    m.kd[0] = 0.4, m.kd[1] = 0.2, m.kd[2] = 0.1;
    return m;
}

START_TEST(select_budget_runs_the_flowchart_once)
{
    abrdf_surface types[] = {ABRDF_SURFACE_GENERAL, ABRDF_SURFACE_CLOTH_ROUGH,
                             ABRDF_SURFACE_CLOTH_SHINY, ABRDF_SURFACE_LAYERED_PLASTIC};
    /* The count does not depend on the fits' work: the coarsest direction set, a sphere 16
     * samples across (the defaults took half a minute under the sanitizers). */
    abrdf_view v;
    abrdf_view_init(&v);
    v.resolution = 16;
    size_t ws = abrdf_fit_workspace_size(NULL, &v);
    void *w = malloc(ws);
    for (size_t t = 0; t < sizeof types / sizeof *types; ++t) {
        abrdf_material m = material(types[t]);
        abrdf_budget b;
        abrdf_budget_init(&b);
        b.metric = ABRDF_FIT_L2;
        b.resolution = 1;
        b.view = &v;
        abrdf_selection sel, photo;
        abrdf_params p, pp;
        abrdf_selection_init(&sel);
        abrdf_params_init(ABRDF_MODEL_NONE, &p);
        counted c = {0, 0};
        calls = 0;
        ck_assert_int_eq(abrdf_select_budget(&m, &b, NULL, &sel, &p, count, &c, w, ws), ABRDF_OK);
        ck_assert_msg(calls == 1, "%s: abrdf_select ran %d times in one budget selection",
                      abrdf_surface_name(types[t]), calls);
        ck_assert_int_eq(c.reference_steps, 1);
        /* the flowchart's steps in the trace are those of a plain photoreal selection */
        abrdf_selection_init(&photo);
        abrdf_params_init(ABRDF_MODEL_NONE, &pp);
        ck_assert_int_eq(
            __real_abrdf_select(&m, ABRDF_GOAL_PHOTOREAL, NULL, NULL, &photo, &pp, NULL, NULL),
            ABRDF_OK);
        ck_assert_int_eq(c.flowchart_steps, photo.step_count);
    }
    free(w);
}
END_TEST

START_TEST(budget_candidate_runs_the_flowchart_once)
{
    abrdf_material m = material(ABRDF_SURFACE_GENERAL);
    abrdf_model d, s;
    for (int i = 0; i < 3; ++i) {
        calls = 0;
        ck_assert_int_eq(abrdf_budget_candidate(&m, i, &d, &s), ABRDF_OK);
        ck_assert_int_eq(calls, 1);
    }
}
END_TEST

int main(void)
{
    Suite *s = suite_create("budget_once");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 300);
    tcase_add_test(tc, select_budget_runs_the_flowchart_once);
    tcase_add_test(tc, budget_candidate_runs_the_flowchart_once);
    suite_add_tcase(s, tc);
    return tu_run(s);
}
