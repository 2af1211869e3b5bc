/* test_select.c - the paper's flowchart (Fig. 2) as abrdf_select walks it: one test per
 * branch, asserting the chosen models AND the trace (its texts and machine-readable fields).
 * Expected choices are recomputed here from abrdf_approx_error_eval and the cost table, so
 * the tests follow the error analysis rather than pasted numbers. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "abrdf_select.h"
#include "test_util.h"

static abrdf_material mat(double n, double r)
{
    abrdf_material m;
    abrdf_material_init(&m);
    m.n = n;
    m.r = r;
    return m;
}

static abrdf_tolerance tol(double max_rel_pct, double max_abs)
{
    abrdf_tolerance t;
    abrdf_tolerance_init(&t);
    t.max_rel_pct = max_rel_pct;
    t.max_abs = max_abs;
    return t;
}

/* A trace step as the test keeps it: the step's fields with its text copied. */
typedef struct kept_step {
    abrdf_step_kind kind;
    abrdf_model model;
    double value, threshold, value2, threshold2, cost;
    int passed;
    char text[256];
} kept_step;

#define MAX_STEPS 32 /* the flowchart makes at most 14 decisions */

/* One run of abrdf_select: the result, the parameter block and the trace. */
typedef struct run {
    abrdf_selection sel;
    abrdf_params params;
    int step_count;
    kept_step steps[MAX_STEPS];
} run;

static void keep(void *user, const abrdf_select_step *st)
{
    run *r = user;
    ck_assert_int_lt(r->step_count, MAX_STEPS);
    kept_step *k = &r->steps[r->step_count++];
    k->kind = st->kind;
    k->model = st->model;
    k->value = st->value;
    k->threshold = st->threshold;
    k->value2 = st->value2;
    k->threshold2 = st->threshold2;
    k->cost = st->cost;
    k->passed = st->passed;
    ck_assert_int_lt(snprintf(k->text, sizeof k->text, "%s", st->text), (int)sizeof k->text);
}

static int select_run(run *r, const abrdf_material *m, abrdf_goal goal, const abrdf_tolerance *t,
                      const abrdf_costs *c)
{
    abrdf_selection_init(&r->sel);
    abrdf_params_init(ABRDF_MODEL_NONE, &r->params);
    r->step_count = 0;
    int st = abrdf_select(m, goal, t, c, &r->sel, &r->params, keep, r);
    ck_assert_int_eq(r->step_count, r->sel.step_count);
    return st;
}

static run sel_ok(const abrdf_material *m, abrdf_goal goal, const abrdf_tolerance *t,
                  const abrdf_costs *c)
{
    run r;
    int st = select_run(&r, m, goal, t, c);
    ck_assert_msg(st == ABRDF_OK, "abrdf_select failed: %s", r.sel.message);
    ck_assert_str_eq(r.sel.message, "");
    return r;
}

/* The first step of `kind` (and `model`, unless ABRDF_MODEL_NONE); fails if none. */
static const kept_step *step(const run *s, abrdf_step_kind kind, abrdf_model model)
{
    for (int i = 0; i < s->step_count; ++i)
        if (s->steps[i].kind == kind && (model == ABRDF_MODEL_NONE || s->steps[i].model == model))
            return &s->steps[i];
    ck_abort_msg("no trace step of kind %d for model %d", (int)kind, (int)model);
    return NULL;
}

static int has_step(const run *s, abrdf_step_kind kind)
{
    for (int i = 0; i < s->step_count; ++i)
        if (s->steps[i].kind == kind) return 1;
    return 0;
}

static void text_has(const kept_step *st, const char *needle)
{
    ck_assert_msg(strstr(st->text, needle) != NULL, "trace line '%s' lacks '%s'", st->text, needle);
}

/* The cheapest candidate within tolerance, recomputed independently of select.c. */
static abrdf_model expected_cheapest(double n, const abrdf_tolerance *t, const abrdf_costs *c)
{
    const abrdf_select_rules *R = abrdf_select_rules_get();
    abrdf_model best = ABRDF_MODEL_NONE;
    double best_cost = INFINITY, best_rel = INFINITY;
    for (int i = 0; i < R->candidate_count; ++i) {
        abrdf_approx_error e;
        if (abrdf_approx_error_eval(R->candidates[i], n, &e) != ABRDF_OK) continue;
        double cost = abrdf_costs_get(c, R->candidates[i]);
        if (e.max_rel_pct <= t->max_rel_pct && e.max_abs <= t->max_abs && cost >= 0 &&
            (cost < best_cost || (cost == best_cost && e.max_rel_pct < best_rel))) {
            best = R->candidates[i];
            best_cost = cost;
            best_rel = e.max_rel_pct;
        }
    }
    return best;
}

/* ---- performance branch --------------------------------------------------------------- */

START_TEST(performance_n300_rel2_picks_f8)
{
    abrdf_material m = mat(300, -1);
    abrdf_tolerance t = tol(2.0, 0.05);
    run s = sel_ok(&m, ABRDF_GOAL_PERFORMANCE, &t, NULL);
    abrdf_costs paper;
    abrdf_costs_paper(&paper);
    ck_assert_int_eq(s.sel.specular, expected_cheapest(300, &t, &paper));
    ck_assert_int_eq(s.sel.specular, ABRDF_F8);
    ck_assert_int_eq(s.sel.diffuse, ABRDF_LAMBERT);
    ck_assert(s.sel.err_rel_pct > 0.0 && s.sel.err_rel_pct <= 2.0 && s.sel.err_abs <= 0.05);
    ck_assert(s.sel.cost_specular == 14.0);
    /* Every Table-1 approximation is in the trace, in the rules' order. */
    const abrdf_select_rules *R = abrdf_select_rules_get();
    int k = 0;
    for (int i = 0; i < s.step_count; ++i)
        if (s.steps[i].kind == ABRDF_STEP_CANDIDATE)
            ck_assert_int_eq(s.steps[i].model, R->candidates[k++]);
    ck_assert_int_eq(k, R->candidate_count);
    const kept_step *f2 = step(&s, ABRDF_STEP_CANDIDATE, ABRDF_F2);
    ck_assert(!f2->passed && f2->value > 2.0 && f2->threshold == 2.0 && f2->cost == 8.0);
    text_has(f2, "f2: rel ");
    text_has(f2, "> 2%");
    text_has(f2, "rejected");
    const kept_step *f16 = step(&s, ABRDF_STEP_CANDIDATE, ABRDF_F16);
    ck_assert(f16->passed && f16->value <= 2.0 && f16->value2 <= 0.05 && f16->threshold2 == 0.05);
    text_has(f16, "passes");
    const kept_step *c = step(&s, ABRDF_STEP_CHEAPEST, ABRDF_F8);
    ck_assert(c->passed && c->cost == 14.0 && c->value == s.sel.err_rel_pct &&
              c->value2 == s.sel.err_abs);
    text_has(c, "f8: rel ");
    text_has(c, "<= 2%");
    text_has(c, "<= 0.05");
    text_has(c, "14 cycles: cheapest that passes");
    text_has(step(&s, ABRDF_STEP_INPUT, ABRDF_MODEL_NONE), "n 300 (given)");
    text_has(step(&s, ABRDF_STEP_DIFFUSE, ABRDF_LAMBERT), "lambert (Eq. 1)");
    ck_assert(!has_step(&s, ABRDF_STEP_FALLBACK));
    ck_assert_int_eq(abrdf_params_check(s.sel.specular, &s.params, NULL, 0), ABRDF_OK);
}
END_TEST

START_TEST(performance_loose_tolerance_picks_f4_at_n1000)
{
    abrdf_material m = mat(1000, -1);
    abrdf_tolerance t = tol(4.0, 0.1);
    run s = sel_ok(&m, ABRDF_GOAL_PERFORMANCE, &t, NULL);
    abrdf_costs paper;
    abrdf_costs_paper(&paper);
    ck_assert_int_eq(s.sel.specular, expected_cheapest(1000, &t, &paper));
    ck_assert_int_eq(s.sel.specular, ABRDF_F4);
    text_has(step(&s, ABRDF_STEP_CHEAPEST, ABRDF_F4), "11 cycles: cheapest that passes");
    text_has(step(&s, ABRDF_STEP_CANDIDATE, ABRDF_F2), "> 4%");
}
END_TEST

START_TEST(performance_tight_rel_no_abs_limit_picks_f16)
{
    abrdf_material m = mat(300, -1);
    abrdf_tolerance t = tol(1.0, INFINITY);
    run s = sel_ok(&m, ABRDF_GOAL_PERFORMANCE, &t, NULL);
    ck_assert_int_eq(s.sel.specular, ABRDF_F16);
    const kept_step *f8 = step(&s, ABRDF_STEP_CANDIDATE, ABRDF_F8);
    ck_assert(!f8->passed);
    text_has(f8, "> 1%");
    ck_assert(strstr(f8->text, "abs ") && !strstr(f8->text, "<= inf"));
    ck_assert(isinf(f8->threshold2));
}
END_TEST

START_TEST(performance_exact_at_n_equal_m)
{
    abrdf_material m = mat(2, -1);
    run s = sel_ok(&m, ABRDF_GOAL_PERFORMANCE, NULL, NULL); /* default tolerances */
    ck_assert_int_eq(s.sel.specular, ABRDF_F2);
    ck_assert(s.sel.err_rel_pct < 1e-9 && s.sel.err_abs < 1e-9);
    text_has(step(&s, ABRDF_STEP_CHEAPEST, ABRDF_F2), "rel 0% <= 2%");
}
END_TEST

START_TEST(performance_none_passes_falls_back_to_blinn_phong)
{
    abrdf_material m = mat(300, -1);
    abrdf_tolerance t = tol(0.1, 0.001);
    run s = sel_ok(&m, ABRDF_GOAL_PERFORMANCE, &t, NULL);
    ck_assert_int_eq(s.sel.specular, ABRDF_BLINN_PHONG);
    ck_assert_int_eq(s.sel.diffuse, ABRDF_LAMBERT);
    ck_assert(s.sel.err_rel_pct == 0.0 && s.sel.err_abs == 0.0);
    for (int i = 0; i < s.step_count; ++i)
        if (s.steps[i].kind == ABRDF_STEP_CANDIDATE) ck_assert(!s.steps[i].passed);
    const kept_step *f = step(&s, ABRDF_STEP_FALLBACK, ABRDF_BLINN_PHONG);
    text_has(f, "no Table-1 approximation passes at n 300");
    text_has(f, "blinn_phong");
    ck_assert(!has_step(&s, ABRDF_STEP_CHEAPEST));
}
END_TEST

START_TEST(performance_calibrated_costs_change_the_choice)
{
    abrdf_costs c;
    abrdf_costs_init(&c, "ns/eval (measured)");
    abrdf_costs_set(&c, ABRDF_F8, 2.0);
    abrdf_costs_set(&c, ABRDF_F16, 1.5); /* measured: f16 cheaper than f8 on this host */
    abrdf_material m = mat(300, -1);
    abrdf_tolerance t = tol(2.0, 0.05);
    run s = sel_ok(&m, ABRDF_GOAL_PERFORMANCE, &t, &c);
    ck_assert_int_eq(s.sel.specular, ABRDF_F16);
    text_has(step(&s, ABRDF_STEP_CHEAPEST, ABRDF_F16), "1.5 ns/eval: cheapest that passes");
    text_has(step(&s, ABRDF_STEP_CANDIDATE, ABRDF_F2), "cost unknown");
    ck_assert_str_eq(s.sel.cost_unit, "ns/eval (measured)");
    /* Equal costs: the smaller relative error wins. */
    abrdf_costs_set(&c, ABRDF_F8, 3.0);
    abrdf_costs_set(&c, ABRDF_F16, 3.0);
    s = sel_ok(&m, ABRDF_GOAL_PERFORMANCE, &t, &c);
    ck_assert_int_eq(s.sel.specular, ABRDF_F16);
    /* A candidate that passes but has no cost cannot be ranked. */
    abrdf_costs_set(&c, ABRDF_F8, -1.0);
    abrdf_costs_set(&c, ABRDF_F16, -1.0);
    s = sel_ok(&m, ABRDF_GOAL_PERFORMANCE, &t, &c);
    ck_assert_int_eq(s.sel.specular, ABRDF_BLINN_PHONG);
    text_has(step(&s, ABRDF_STEP_CANDIDATE, ABRDF_F8), "cannot be ranked");
}
END_TEST

START_TEST(performance_derives_n_from_r_and_ignores_surface_class)
{
    abrdf_material m = mat(-1, 0.3);
    m.type = ABRDF_SURFACE_HAIR;
    run s = sel_ok(&m, ABRDF_GOAL_PERFORMANCE, NULL, NULL);
    double n = abrdf_alpha_g_to_n(0.09);
    ck_assert(tu_close(s.sel.n, n, 1e-12, 0.0) && s.params.n == s.sel.n);
    text_has(step(&s, ABRDF_STEP_INPUT, ABRDF_MODEL_NONE), "from r");
    text_has(step(&s, ABRDF_STEP_SURFACE, ABRDF_MODEL_NONE),
             "surface hair: not used by the performance branch");
    ck_assert_int_eq(s.sel.diffuse, ABRDF_LAMBERT);
}
END_TEST

/* ---- photoreal, general surfaces ------------------------------------------------------ */

START_TEST(photoreal_rough_is_disney)
{
    abrdf_material m = mat(-1, 0.3);
    run s = sel_ok(&m, ABRDF_GOAL_PHOTOREAL, NULL, NULL);
    ck_assert_int_eq(s.sel.diffuse, ABRDF_DISNEY_DIFFUSE);
    ck_assert_int_eq(s.sel.specular, ABRDF_DISNEY_SPECULAR);
    const kept_step *r = step(&s, ABRDF_STEP_ROUGHNESS, ABRDF_MODEL_NONE);
    ck_assert(!r->passed && r->value == 0.3 && r->threshold == 0.03);
    ck_assert_str_eq(r->text, "alpha 0.3 > 0.03: rough");
    text_has(step(&s, ABRDF_STEP_ANISOTROPY, ABRDF_DISNEY_SPECULAR),
             "anisotropy 0 <= 0: disney_specular");
    text_has(step(&s, ABRDF_STEP_DIFFUSE, ABRDF_DISNEY_DIFFUSE), "disney_diffuse (Eq. 3)");
    ck_assert(s.params.r == 0.3 && s.sel.err_rel_pct < 0 && s.sel.err_nmse < 0);
    ck_assert_int_eq(abrdf_params_check(s.sel.specular, &s.params, NULL, 0), ABRDF_OK);
}
END_TEST

START_TEST(photoreal_rough_anisotropic)
{
    abrdf_material m = mat(-1, 0.4);
    m.anisotropy = 0.5;
    run s = sel_ok(&m, ABRDF_GOAL_PHOTOREAL, NULL, NULL);
    ck_assert_int_eq(s.sel.specular, ABRDF_DISNEY_SPECULAR_ANISO);
    ck_assert_int_eq(s.sel.diffuse, ABRDF_DISNEY_DIFFUSE);
    const kept_step *a = step(&s, ABRDF_STEP_ANISOTROPY, ABRDF_DISNEY_SPECULAR_ANISO);
    ck_assert(a->passed && a->value == 0.5);
    text_has(a, "anisotropy 0.5 > 0: disney_specular_aniso");
    ck_assert(s.params.anisotropic == 0.5);
}
END_TEST

START_TEST(photoreal_smooth_is_lambert_fresnel_plus_f2e)
{
    abrdf_material m = mat(-1, 0.02);
    m.eta = 1.5;
    run s = sel_ok(&m, ABRDF_GOAL_PHOTOREAL, NULL, NULL);
    ck_assert_int_eq(s.sel.diffuse, ABRDF_LAMBERT_FRESNEL);
    ck_assert_int_eq(s.sel.specular, ABRDF_F_2E);
    ck_assert_str_eq(step(&s, ABRDF_STEP_ROUGHNESS, ABRDF_MODEL_NONE)->text,
                     "alpha 0.02 <= 0.03: smooth");
    /* n from r: 2/alpha_g^2 - 2 = 1.25e7, clamped to the parameter's 1e6. */
    const kept_step *e = step(&s, ABRDF_STEP_EXPONENT, ABRDF_F_2E);
    text_has(e, "from r 0.02");
    text_has(e, "clamped to 1e6");
    ck_assert(s.params.n == 1e6 && s.sel.n == 1e6);
    ck_assert(tu_close(s.params.f0[1], 0.04, 1e-12, 0.0)); /* ((1.5-1)/(1.5+1))^2 */
    /* The paper's Table 6: alpha_g 0.0004 is nearest 0.0005 (f_2E NMSE 0.0001, slight). */
    ck_assert(s.sel.err_nmse == 0.0001);
    ck_assert_int_eq(abrdf_params_check(s.sel.specular, &s.params, NULL, 0), ABRDF_OK);
}
END_TEST

START_TEST(photoreal_smooth_keeps_a_given_exponent)
{
    abrdf_material m = mat(500, 0.01);
    run s = sel_ok(&m, ABRDF_GOAL_PHOTOREAL, NULL, NULL);
    ck_assert_int_eq(s.sel.specular, ABRDF_F_2E);
    ck_assert(s.params.n == 500);
    text_has(step(&s, ABRDF_STEP_EXPONENT, ABRDF_F_2E), "n 500 (given)");
}
END_TEST

START_TEST(photoreal_boundary_r_0_03_is_smooth)
{
    abrdf_material m = mat(-1, 0.03);
    run s = sel_ok(&m, ABRDF_GOAL_PHOTOREAL, NULL, NULL);
    ck_assert_int_eq(s.sel.specular, ABRDF_F_2E);
    const kept_step *r = step(&s, ABRDF_STEP_ROUGHNESS, ABRDF_MODEL_NONE);
    ck_assert(r->passed);
    ck_assert_str_eq(r->text, "alpha 0.03 <= 0.03: smooth");
    m.r = nextafter(0.03, 1.0);
    s = sel_ok(&m, ABRDF_GOAL_PHOTOREAL, NULL, NULL);
    ck_assert_int_eq(s.sel.specular, ABRDF_DISNEY_SPECULAR);
    ck_assert(!step(&s, ABRDF_STEP_ROUGHNESS, ABRDF_MODEL_NONE)->passed);
}
END_TEST

START_TEST(photoreal_smooth_ignores_anisotropy_and_says_so)
{
    abrdf_material m = mat(-1, 0.01);
    m.anisotropy = 0.7;
    run s = sel_ok(&m, ABRDF_GOAL_PHOTOREAL, NULL, NULL);
    ck_assert_int_eq(s.sel.specular, ABRDF_F_2E);
    const kept_step *a = step(&s, ABRDF_STEP_ANISOTROPY, ABRDF_MODEL_NONE);
    ck_assert(!a->passed);
    text_has(a, "anisotropy 0.7 ignored");
}
END_TEST

/* ---- photoreal, special surfaces ------------------------------------------------------ */

static run special(abrdf_surface type, abrdf_model expect, const char *why)
{
    abrdf_material m = mat(-1, 0.3);
    m.type = type;
    if (type >= ABRDF_SURFACE_LAYERED_PLASTIC) {
        m.layer_count = 1;
        m.layers[0].eta = 1.5;
        m.layers[0].r = 0.3;
        m.layers[0].depth = 0.05;
    }
    run s = sel_ok(&m, ABRDF_GOAL_PHOTOREAL, NULL, NULL);
    ck_assert_int_eq(s.sel.specular, expect);
    ck_assert_int_eq(s.sel.diffuse, ABRDF_MODEL_NONE); /* the special model has its own */
    const kept_step *st = step(&s, ABRDF_STEP_SURFACE, expect);
    text_has(st, abrdf_surface_name(type));
    text_has(st, why);
    text_has(step(&s, ABRDF_STEP_SPECIAL, expect), abrdf_model_get(expect)->name);
    ck_assert(!has_step(&s, ABRDF_STEP_ROUGHNESS));
    /* The block evaluates: the special model takes the material's parameters. */
    ck_assert_int_eq(abrdf_params_check(expect, &s.params, NULL, 0), ABRDF_OK);
    if (m.layer_count > 0) ck_assert_int_eq(s.params.layer_count, m.layer_count);
    return s;
}

START_TEST(photoreal_cloth_rough_is_neubelt_pettineo)
{
    special(ABRDF_SURFACE_CLOTH_ROUGH, ABRDF_NEUBELT_PETTINEO, "Eq. 10");
}
END_TEST

START_TEST(photoreal_cloth_shiny_is_kajiya_kay)
{
    special(ABRDF_SURFACE_CLOTH_SHINY, ABRDF_KAJIYA_KAY, "Eq. 11");
}
END_TEST

START_TEST(photoreal_hair_is_huang)
{
    run s = special(ABRDF_SURFACE_HAIR, ABRDF_HUANG, "Eqs. 12-14");
    ck_assert(s.params.melanin == 0.3);
}
END_TEST

START_TEST(photoreal_layered_plastic_is_weidlich_wilkie)
{
    run s = special(ABRDF_SURFACE_LAYERED_PLASTIC, ABRDF_WEIDLICH_WILKIE, "Eq. 15");
    ck_assert(s.params.layers[0].eta == 1.5 && s.params.layers[0].depth == 0.05);
}
END_TEST

START_TEST(photoreal_layered_plate_is_belcour)
{
    special(ABRDF_SURFACE_LAYERED_PLATE, ABRDF_BELCOUR, "Eq. 16");
}
END_TEST

START_TEST(photoreal_layered_metal_is_belcour_not_weidlich_wilkie)
{
    run s = special(ABRDF_SURFACE_LAYERED_METAL, ABRDF_BELCOUR, "Weidlich-Wilkie (Eq. 15)");
    text_has(step(&s, ABRDF_STEP_SURFACE, ABRDF_BELCOUR), "smooth metal under a rough coat");
    text_has(step(&s, ABRDF_STEP_SPECIAL, ABRDF_BELCOUR), "top layer r 0.3");
}
END_TEST

/* ---- inputs, rules, names ------------------------------------------------------------- */

START_TEST(invalid_inputs_are_rejected_with_a_message)
{
    run s;
    abrdf_material m = mat(-1, -1);
    ck_assert_int_eq(select_run(&s, &m, ABRDF_GOAL_PHOTOREAL, NULL, NULL), ABRDF_E_RANGE);
    ck_assert(strstr(s.sel.message, "neither n nor r"));
    m = mat(-1, 1.5);
    ck_assert_int_eq(select_run(&s, &m, ABRDF_GOAL_PHOTOREAL, NULL, NULL), ABRDF_E_RANGE);
    ck_assert(strstr(s.sel.message, "r = 1.5"));
    m = mat(NAN, 0.3);
    ck_assert_int_eq(select_run(&s, &m, ABRDF_GOAL_PERFORMANCE, NULL, NULL), ABRDF_E_RANGE);
    ck_assert(strstr(s.sel.message, "n = "));
    m = mat(100, -1);
    m.kd[1] = 1.2;
    ck_assert_int_eq(select_run(&s, &m, ABRDF_GOAL_PERFORMANCE, NULL, NULL), ABRDF_E_RANGE);
    ck_assert(strstr(s.sel.message, "kd[1]"));
    m = mat(100, -1);
    abrdf_tolerance t = tol(-1.0, 0.05);
    ck_assert_int_eq(select_run(&s, &m, ABRDF_GOAL_PERFORMANCE, &t, NULL), ABRDF_E_RANGE);
    t.max_rel_pct = 2.0;
    t.max_abs = NAN;
    ck_assert_int_eq(select_run(&s, &m, ABRDF_GOAL_PERFORMANCE, &t, NULL), ABRDF_E_RANGE);
    ck_assert_int_eq(select_run(&s, &m, (abrdf_goal)7, NULL, NULL), ABRDF_E_RANGE);
    m.type = (abrdf_surface)99;
    ck_assert_int_eq(select_run(&s, &m, ABRDF_GOAL_PHOTOREAL, NULL, NULL), ABRDF_E_RANGE);
    ck_assert_int_eq(select_run(&s, NULL, ABRDF_GOAL_PHOTOREAL, NULL, NULL), ABRDF_E_NULL);
    ck_assert_int_eq(abrdf_select(&m, ABRDF_GOAL_PHOTOREAL, NULL, NULL, NULL, NULL, NULL, NULL),
                     ABRDF_E_NULL);
}
END_TEST

/* cost[] is public: a NaN or an infinity written into it is refused, for either goal, with
 * the model named (it used to pass through as a NaN cost of the choice). */
START_TEST(non_finite_costs_are_rejected)
{
    run s;
    abrdf_material m = mat(300, -1);
    abrdf_costs c;
    abrdf_costs_paper(&c);
    ck_assert_int_eq(abrdf_costs_set(&c, ABRDF_F8, NAN), ABRDF_E_RANGE); /* the setter refuses */
    for (int goal = 0; goal < 2; ++goal) {
        c.cost[ABRDF_F8] = NAN;
        ck_assert_int_eq(select_run(&s, &m, (abrdf_goal)goal, NULL, &c), ABRDF_E_RANGE);
        ck_assert_msg(strstr(s.sel.message, "f8") && strstr(s.sel.message, "nan"), "%s",
                      s.sel.message);
        c.cost[ABRDF_F8] = -INFINITY;
        ck_assert_int_eq(select_run(&s, &m, (abrdf_goal)goal, NULL, &c), ABRDF_E_RANGE);
        c.cost[ABRDF_F8] = 14.0;
        c.cost[ABRDF_COSTS_CAPACITY - 1] = INFINITY; /* an id no model has yet */
        ck_assert_int_eq(select_run(&s, &m, (abrdf_goal)goal, NULL, &c), ABRDF_E_RANGE);
        c.cost[ABRDF_COSTS_CAPACITY - 1] = -1.0;
        ck_assert_int_eq(select_run(&s, &m, (abrdf_goal)goal, NULL, &c), ABRDF_OK);
        ck_assert(isfinite(s.sel.cost_total));
    }
}
END_TEST

/* struct_size (abrdf.h, STABLE LAYOUTS): a struct never initialised, or smaller than the
 * 0.2.0 layout, is refused with ABRDF_E_SIZE and a message naming it; nothing is written
 * into a result that is itself too small. */
START_TEST(struct_size_is_checked)
{
    run s;
    abrdf_material m = mat(-1, 0.3);
    m.struct_size = 0;
    ck_assert_int_eq(select_run(&s, &m, ABRDF_GOAL_PHOTOREAL, NULL, NULL), ABRDF_E_SIZE);
    ck_assert(strstr(s.sel.message, "abrdf_material: struct_size 0"));
    ck_assert_int_eq(s.step_count, 0);
    m = mat(-1, 0.3);
    abrdf_tolerance t = tol(2.0, 0.05);
    t.struct_size = sizeof t.struct_size;
    ck_assert_int_eq(select_run(&s, &m, ABRDF_GOAL_PERFORMANCE, &t, NULL), ABRDF_E_SIZE);
    ck_assert(strstr(s.sel.message, "abrdf_tolerance: struct_size"));
    abrdf_params p;
    abrdf_params_init(ABRDF_MODEL_NONE, &p);
    p.struct_size = offsetof(abrdf_params, layers);
    abrdf_selection sel;
    abrdf_selection_init(&sel);
    ck_assert_int_eq(abrdf_select(&m, ABRDF_GOAL_PHOTOREAL, NULL, NULL, &sel, &p, NULL, NULL),
                     ABRDF_E_SIZE);
    ck_assert(strstr(sel.message, "abrdf_params: struct_size"));
    /* A result too small to hold a message is left alone. */
    abrdf_selection_init(&sel);
    sel.struct_size = offsetof(abrdf_selection, message);
    sel.specular = ABRDF_F2;
    ck_assert_int_eq(abrdf_select(&m, ABRDF_GOAL_PHOTOREAL, NULL, NULL, &sel, NULL, NULL, NULL),
                     ABRDF_E_SIZE);
    ck_assert_int_eq(sel.specular, ABRDF_F2);
    /* The _init functions refuse a size below the 0.2.0 layout and write nothing. */
    m.n = 7.0;
    ck_assert_int_eq(abrdf_material_init_sized(&m, sizeof m - 1 - sizeof m.layers), ABRDF_E_SIZE);
    ck_assert(m.n == 7.0);
    ck_assert_int_eq(abrdf_tolerance_init_sized(&t, 0), ABRDF_E_SIZE);
    ck_assert_int_eq(abrdf_selection_init_sized(&sel, 1), ABRDF_E_SIZE);
    ck_assert_int_eq(abrdf_material_init_sized(NULL, sizeof m), ABRDF_E_NULL);
    /* Without params or trace the selection is the same. */
    abrdf_selection_init(&sel);
    m = mat(-1, 0.3);
    ck_assert_int_eq(abrdf_select(&m, ABRDF_GOAL_PHOTOREAL, NULL, NULL, &sel, NULL, NULL, NULL),
                     ABRDF_OK);
    ck_assert_int_eq(sel.specular, ABRDF_DISNEY_SPECULAR);
    ck_assert_int_eq(sel.step_count, sel_ok(&m, ABRDF_GOAL_PHOTOREAL, NULL, NULL).step_count);
}
END_TEST

START_TEST(rules_table_holds_the_flowchart)
{
    const abrdf_select_rules *R = abrdf_select_rules_get();
    ck_assert(R->smooth_r_max == 0.03 && R->aniso_min == 0.0);
    ck_assert_int_eq(R->candidate_count, 7);
    ck_assert_int_eq(R->perf_diffuse, ABRDF_LAMBERT);
    ck_assert_int_eq(R->perf_fallback, ABRDF_BLINN_PHONG);
    ck_assert_int_eq(R->special[ABRDF_SURFACE_GENERAL], ABRDF_MODEL_NONE);
    for (int i = 0; i < R->candidate_count; ++i)
        ck_assert_str_eq(abrdf_model_get(R->candidates[i])->equation, "Table 1");
    ck_assert_int_eq(R->surface_count, ABRDF_SURFACE_COUNT);
    for (int i = 0; i < R->surface_count; ++i)
        ck_assert(R->special_reason[i] && *R->special_reason[i]);
    for (int i = 1; i < R->surface_count; ++i) ck_assert(abrdf_model_get(R->special[i]) != NULL);
    /* The paper's Table 6 (f_2E column): 18 rows, alpha_g decreasing, NMSE in (0, 0.1). */
    double a, v, prev = INFINITY;
    int rows = 0;
    for (; abrdf_select_table6(rows, &a, &v) == ABRDF_OK; ++rows) {
        ck_assert(a < prev && v > 0.0 && v < 0.1);
        prev = a;
    }
    ck_assert_int_eq(rows, 18);
    ck_assert_int_eq(abrdf_select_table6(-1, &a, &v), ABRDF_E_RANGE);
    ck_assert_int_eq(abrdf_select_table6(0, NULL, &v), ABRDF_E_NULL);
}
END_TEST

START_TEST(names_round_trip_and_agree_with_the_registry)
{
    /* Every model the trace can name is registered; "none" is not a model. */
    for (int i = 0; i < ABRDF_MODEL_COUNT; ++i) ck_assert(abrdf_model_get((abrdf_model)i) != NULL);
    ck_assert(abrdf_model_get(ABRDF_MODEL_NONE) == NULL);
    static const char *const steps[ABRDF_STEP_KIND_COUNT] = {
        "input",     "goal",       "diffuse",  "candidate", "cheapest",  "fallback", "surface",
        "roughness", "anisotropy", "exponent", "special",   "reference", "fit",      "budget"};
    for (int i = 0; i < ABRDF_STEP_KIND_COUNT; ++i)
        ck_assert_str_eq(abrdf_step_name((abrdf_step_kind)i), steps[i]);
    ck_assert(abrdf_step_name(ABRDF_STEP_KIND_COUNT) == NULL);
    for (int i = 0; i < ABRDF_SURFACE_COUNT; ++i) {
        abrdf_surface s;
        ck_assert_int_eq(abrdf_surface_find(abrdf_surface_name((abrdf_surface)i), &s), ABRDF_OK);
        ck_assert_int_eq(s, i);
    }
    abrdf_goal g;
    ck_assert_int_eq(abrdf_goal_find("photoreal", &g), ABRDF_OK);
    ck_assert_int_eq(g, ABRDF_GOAL_PHOTOREAL);
    ck_assert_int_eq(abrdf_goal_find("fast", &g), ABRDF_E_RANGE);
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("select");
    TCase *p = tcase_create("performance");
    tcase_add_test(p, performance_n300_rel2_picks_f8);
    tcase_add_test(p, performance_loose_tolerance_picks_f4_at_n1000);
    tcase_add_test(p, performance_tight_rel_no_abs_limit_picks_f16);
    tcase_add_test(p, performance_exact_at_n_equal_m);
    tcase_add_test(p, performance_none_passes_falls_back_to_blinn_phong);
    tcase_add_test(p, performance_calibrated_costs_change_the_choice);
    tcase_add_test(p, performance_derives_n_from_r_and_ignores_surface_class);
    suite_add_tcase(s, p);
    TCase *g = tcase_create("photoreal_general");
    tcase_add_test(g, photoreal_rough_is_disney);
    tcase_add_test(g, photoreal_rough_anisotropic);
    tcase_add_test(g, photoreal_smooth_is_lambert_fresnel_plus_f2e);
    tcase_add_test(g, photoreal_smooth_keeps_a_given_exponent);
    tcase_add_test(g, photoreal_boundary_r_0_03_is_smooth);
    tcase_add_test(g, photoreal_smooth_ignores_anisotropy_and_says_so);
    suite_add_tcase(s, g);
    TCase *sp = tcase_create("photoreal_special");
    tcase_add_test(sp, photoreal_cloth_rough_is_neubelt_pettineo);
    tcase_add_test(sp, photoreal_cloth_shiny_is_kajiya_kay);
    tcase_add_test(sp, photoreal_hair_is_huang);
    tcase_add_test(sp, photoreal_layered_plastic_is_weidlich_wilkie);
    tcase_add_test(sp, photoreal_layered_plate_is_belcour);
    tcase_add_test(sp, photoreal_layered_metal_is_belcour_not_weidlich_wilkie);
    suite_add_tcase(s, sp);
    TCase *in = tcase_create("inputs");
    tcase_add_test(in, invalid_inputs_are_rejected_with_a_message);
    tcase_add_test(in, non_finite_costs_are_rejected);
    tcase_add_test(in, struct_size_is_checked);
    tcase_add_test(in, rules_table_holds_the_flowchart);
    tcase_add_test(in, names_round_trip_and_agree_with_the_registry);
    suite_add_tcase(s, in);
    return s;
}

int main(void) { return tu_run(suite()); }
