/* test_pbr_select.c - the flowchart over a roughness map (pbr_select.h): one branch for a
 * map on one side of every threshold, the safe branch for a map that crosses the smooth
 * threshold, and for the performance goal an approximation that passes at every value. */
#include <math.h>
#include <stdio.h>
#include <string.h>

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

static Suite *suite(void)
{
    Suite *s = suite_create("pbr_select");
    TCase *tc = tcase_create("range");
    tcase_add_test(tc, one_side_of_the_threshold_is_one_branch);
    tcase_add_test(tc, crossing_the_smooth_threshold_takes_the_reference);
    tcase_add_test(tc, performance_choice_passes_everywhere);
    tcase_add_test(tc, bad_ranges_are_refused);
    suite_add_tcase(s, tc);
    return s;
}

int main(void) { return tu_run(suite()); }
