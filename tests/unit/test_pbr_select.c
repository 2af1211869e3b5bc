/* test_pbr_select.c - the flowchart over a roughness map (pbr_select.h): one branch for a
 * map on one side of every threshold, the safe branch for a map that crosses the smooth
 * threshold, and for the performance goal an approximation that passes at every value. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "budget_run.h"
#include "pbr_select.h"
#include "test_util.h"

static pbr_range range_of(double lo, double hi, int count)
{
    pbr_range r;
    memset(&r, 0, sizeof r);
    r.count = count;
    for (int i = 0; i < count; ++i) {
        r.r[i] = lo + (hi - lo) * i / (count - 1);
        r.share[i] = 1.0 / count;
    }
    r.what = "roughness map t.png";
    return r;
}

static abrdf_pbr dielectric(void)
{
    abrdf_pbr p;
    abrdf_pbr_init(&p);
    p.metallic = 0;
    p.base_color[0] = 0.7, p.base_color[1] = 0.2, p.base_color[2] = 0.1;
    return p;
}

static const char *last_text(const select_trace *t) { return t->steps[t->count - 1].text; }

START_TEST(one_side_of_the_threshold_is_one_branch)
{
    abrdf_pbr p = dielectric();
    pbr_range r = range_of(0.005, 0.03, 8); /* the paper's alpha (r) <= 0.03: smooth */
    abrdf_selection sel;
    abrdf_params params;
    select_trace t = SELECT_TRACE_INIT;
    char msg[256];
    ck_assert_msg(pbr_select_range(&p, &r, ABRDF_GOAL_PHOTOREAL, NULL, NULL, &sel, &params, &t, msg,
                                   sizeof msg) == 0,
                  "%s", msg);
    ck_assert_int_eq(sel.diffuse, ABRDF_LAMBERT_FRESNEL);
    ck_assert_int_eq(sel.specular, ABRDF_F_2E);
    ck_assert_msg(strstr(last_text(&t), "every value takes the same branch"), "%s", last_text(&t));
    ck_assert_msg(strstr(last_text(&t), "roughness map t.png"), "%s", last_text(&t));
    select_trace_free(&t);
}
END_TEST

START_TEST(crossing_the_smooth_threshold_takes_the_reference)
{
    abrdf_pbr p = dielectric();
    pbr_range r = range_of(0.01, 0.6, 12); /* the smooth threshold: r = 0.03 */
    abrdf_selection sel;
    abrdf_params params;
    select_trace t = SELECT_TRACE_INIT;
    char msg[256];
    ck_assert_msg(pbr_select_range(&p, &r, ABRDF_GOAL_PHOTOREAL, NULL, NULL, &sel, &params, &t, msg,
                                   sizeof msg) == 0,
                  "%s", msg);
    ck_assert_int_eq(sel.specular, ABRDF_DISNEY_SPECULAR);
    ck_assert_int_eq(sel.diffuse, ABRDF_DISNEY_DIFFUSE);
    const char *s = last_text(&t);
    ck_assert_msg(strstr(s, "crosses") && strstr(s, "f_2e") && strstr(s, "reference"), "%s", s);
    /* the median texel of the rough branch: r within that branch's values */
    ck_assert(params.r > 0.03 && params.r <= 0.6);
    select_trace_free(&t);
}
END_TEST

/* The performance choice passes the tolerances at every value (checked here with the
 * library's own error evaluation), and is no dearer than needed: every cheaper Table-1
 * approximation fails somewhere. */
START_TEST(performance_choice_passes_everywhere)
{
    abrdf_pbr p = dielectric();
    pbr_range r = range_of(0.08, 0.7, 16);
    abrdf_selection sel;
    abrdf_params params;
    select_trace t = SELECT_TRACE_INIT;
    char msg[256];
    ck_assert_msg(pbr_select_range(&p, &r, ABRDF_GOAL_PERFORMANCE, NULL, NULL, &sel, &params, &t,
                                   msg, sizeof msg) == 0,
                  "%s", msg);
    abrdf_tolerance tol;
    abrdf_tolerance_init(&tol);
    abrdf_costs paper;
    abrdf_costs_paper(&paper);
    double cost = abrdf_costs_get(&paper, sel.specular);
    static const abrdf_model table1[] = {ABRDF_F2, ABRDF_F4,  ABRDF_F8,  ABRDF_F16,
                                         ABRDF_FS, ABRDF_FKV, ABRDF_FKUB};
    for (size_t k = 0; k < sizeof table1 / sizeof table1[0]; ++k) {
        int passes_all = 1;
        for (int i = 0; i < r.count; ++i) {
            double n = abrdf_alpha_g_to_n(r.r[i] * r.r[i]);
            abrdf_approx_error e;
            ck_assert_int_eq(abrdf_approx_error_eval(table1[k], n, &e), ABRDF_OK);
            passes_all &= e.max_rel_pct <= tol.max_rel_pct && e.max_abs <= tol.max_abs;
        }
        if (table1[k] == sel.specular)
            ck_assert_msg(passes_all, "%s fails somewhere", abrdf_model_get(sel.specular)->name);
        else if (passes_all)
            ck_assert_msg(abrdf_costs_get(&paper, table1[k]) >= cost, "%s is cheaper and passes",
                          abrdf_model_get(table1[k])->name);
    }
    ck_assert_msg(strstr(last_text(&t), "0.08") && strstr(last_text(&t), "0.7"), "%s",
                  last_text(&t));
    select_trace_free(&t);
}
END_TEST

START_TEST(bad_ranges_are_refused)
{
    abrdf_pbr p = dielectric();
    pbr_range r = range_of(0.1, 0.5, 4);
    abrdf_selection sel;
    abrdf_params params;
    select_trace t = SELECT_TRACE_INIT;
    char msg[256];
    r.r[2] = 1.5;
    ck_assert_int_eq(pbr_select_range(&p, &r, ABRDF_GOAL_PHOTOREAL, NULL, NULL, &sel, &params, &t,
                                      msg, sizeof msg),
                     -1);
    ck_assert_msg(strstr(msg, "t.png") && strstr(msg, "1.5"), "%s", msg);
    r.count = 0;
    ck_assert_int_eq(pbr_select_range(&p, &r, ABRDF_GOAL_PHOTOREAL, NULL, NULL, &sel, &params, &t,
                                      msg, sizeof msg),
                     -1);
    ck_assert_int_eq(t.count, 0);
}
END_TEST

/* The default sphere at 32 samples across: the budget's fits in a fraction of the time. */
static const abrdf_view *small_view(void)
{
    static abrdf_view v;
    abrdf_view_init(&v);
    v.resolution = 32;
    return &v;
}

/* The sanitizer build (PBR_SELECT_QUICK) fits on the coarsest direction set: the same code on
 * a fraction of the work (ten budget selections took minutes there); the Release build runs
 * the default fits, whose values the checks were written for. */
#ifdef PBR_SELECT_QUICK
#define FIT_RESOLUTION 1
#else
#define FIT_RESOLUTION 0
#endif

/* One value: the budget over the map is the budget mode's own choice for that material. */
START_TEST(budget_of_one_value_is_the_budget_mode)
{
    abrdf_pbr p = dielectric();
    pbr_range r = range_of(0.3, 0.6, 2);
    r.count = 1; /* r 0.3 alone */
    pbr_budget_choice c;
    select_trace t = SELECT_TRACE_INIT;
    char msg[256];
    ck_assert_msg(pbr_budget_range_at(&p, &r, 2.5e-4, FIT_RESOLUTION, NULL, small_view(), &c, &t,
                                      msg, sizeof msg) == 0,
                  "%s", msg);
    abrdf_pbr q = p;
    q.roughness = 0.3;
    abrdf_material am;
    abrdf_material_init(&am);
    ck_assert_int_eq(abrdf_pbr_material(&q, &am), ABRDF_OK);
    budget_result b;
    ck_assert_int_eq(
        budget_run_at(&am, 2.5e-4, FIT_RESOLUTION, NULL, small_view(), &b, msg, sizeof msg), 0);
    ck_assert_int_eq(c.specular, b.sel.specular);
    ck_assert_int_eq(c.diffuse, b.sel.diffuse);
    ck_assert_double_eq_tol(c.nmse, b.sel.err_nmse, 1e-15);
    ck_assert(c.within && c.groups == 1);
    budget_result_free(&b);
    select_trace_free(&t);
}
END_TEST

/* A map over several values: the winner's NMSE over the map is within the budget, and no
 * pair the trace lists as within is more than 15 % cheaper. An impossible budget falls back
 * to the photoreal choice over the map. */
START_TEST(budget_over_a_map)
{
    abrdf_pbr p = dielectric();
    pbr_range r = range_of(0.15, 0.6, 3);
    pbr_budget_choice c;
    select_trace t = SELECT_TRACE_INIT;
    char msg[256];
    ck_assert_msg(pbr_budget_range_at(&p, &r, 1e-3, FIT_RESOLUTION, NULL, small_view(), &c, &t, msg,
                                      sizeof msg) == 0,
                  "%s", msg);
    ck_assert(c.within && c.nmse < 1e-3 && c.groups == 3);
    int pairs = 0;
    for (int k = 0; k < t.count; ++k) {
        const abrdf_select_step *st = &t.steps[k];
        if (!strstr(st->text, "predicts NMSE")) continue;
        ++pairs;
        if (strstr(st->text, ": within")) {
            double cost = atof(strstr(st->text, "cost ") + 5);
            ck_assert_msg(cost >= c.cost / 1.15 - 1e-9, "%s is cheaper than the winner", st->text);
        }
    }
    ck_assert_int_ge(pairs, 3);
    select_trace_free(&t);
    /* a budget nothing but the reference meets: the reference, the same at every value */
    ck_assert_int_eq(pbr_budget_range_at(&p, &r, 1e-14, FIT_RESOLUTION, NULL, small_view(), &c, &t,
                                         msg, sizeof msg),
                     0);
    ck_assert(c.within && c.nmse == 0);
    ck_assert_int_eq(c.specular, ABRDF_DISNEY_SPECULAR);
    select_trace_free(&t);
    /* across the smooth threshold the references differ (f_2e, GGX): nothing fitted at
     * every value meets it, and the photoreal choice over the map (GGX) is taken */
    r = range_of(0.01, 0.6, 2);
    ck_assert_int_eq(pbr_budget_range_at(&p, &r, 1e-14, FIT_RESOLUTION, NULL, small_view(), &c, &t,
                                         msg, sizeof msg),
                     0);
    ck_assert(!c.within);
    ck_assert_int_eq(c.specular, ABRDF_DISNEY_SPECULAR);
    ck_assert_msg(strstr(t.steps[t.count - 1].text, "photoreal choice"), "%s",
                  t.steps[t.count - 1].text);
    select_trace_free(&t);
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("pbr_select");
    TCase *tc = tcase_create("range");
    tcase_add_test(tc, one_side_of_the_threshold_is_one_branch);
    tcase_add_test(tc, crossing_the_smooth_threshold_takes_the_reference);
    tcase_add_test(tc, performance_choice_passes_everywhere);
    tcase_add_test(tc, bad_ranges_are_refused);
    suite_add_tcase(s, tc);
    TCase *tb = tcase_create("budget"); /* the budget mode fits every candidate: seconds */
    tcase_set_timeout(tb, 600);
    tcase_add_test(tb, budget_of_one_value_is_the_budget_mode);
    tcase_add_test(tb, budget_over_a_map);
    suite_add_tcase(s, tb);
    return s;
}

int main(void) { return tu_run(suite()); }
