/* test_abi_old_caller.c - a caller compiled against the headers of the 0.2.0 release
 * (tests/data/abi), as a program built then would be, run against this library
 * (test_abi_old_caller) and against abrdf_abi_grown, the library as a later release could
 * be: one more model, surface class, goal and step kind, and a new field at the end of every
 * struct that may grow (test_abi_old_caller_grown; libabrdf/CMakeLists.txt).
 *
 * Everything must work as abrdf.h's STABLE LAYOUTS promise: the library writes no byte past
 * the caller's struct_size (each struct it writes sits in a heap block followed by a guard
 * pattern that must survive), reads none past it (inputs sit in blocks of exactly their size,
 * which the sanitizer build checks), evaluates with the caller's values and the defaults of
 * whatever the caller's layout lacks, and "no model" is ABRDF_MODEL_NONE whatever the
 * library's model count. The numbers are checked against closed forms. */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "abrdf_select_0_2_0.h"

#define PI 3.14159265358979323846
#define GUARD 64
#define GUARD_BYTE 0xA5

/* A heap block of `size` bytes, filled with garbage as a stack would be, and GUARD guard
 * bytes after it. */
static void *guarded(size_t size)
{
    unsigned char *p = malloc(size + GUARD);
    ck_assert(p != NULL);
    memset(p, 0x5A, size);
    memset(p + size, GUARD_BYTE, GUARD);
    return p;
}

static void guard_intact(const void *block, size_t size, const char *what)
{
    const unsigned char *g = (const unsigned char *)block + size;
    for (int i = 0; i < GUARD; ++i)
        ck_assert_msg(g[i] == GUARD_BYTE,
                      "the library wrote byte %d past the caller's %s "
                      "(%zu bytes)",
                      i, what, size);
}

/* An input the library only reads, in a block of exactly its size. */
static void *exact_copy(const void *src, size_t size)
{
    void *p = malloc(size);
    ck_assert(p != NULL);
    memcpy(p, src, size);
    return p;
}

static int close_to(double a, double b, double rel) { return fabs(a - b) <= rel * fabs(b); }

START_TEST(the_library_knows_this_header)
{
    ck_assert_int_ge(abrdf_model_count(), ABRDF_MODEL_COUNT);
    for (int i = 0; i < ABRDF_MODEL_COUNT; ++i) ck_assert(abrdf_model_get((abrdf_model)i) != NULL);
    ck_assert(abrdf_model_get(ABRDF_MODEL_NONE) == NULL);
    const abrdf_select_rules *R = abrdf_select_rules_get();
    ck_assert_int_ge(R->surface_count, ABRDF_SURFACE_COUNT);
    ck_assert_int_eq(R->special[ABRDF_SURFACE_GENERAL], ABRDF_MODEL_NONE);
    ck_assert_str_eq(abrdf_step_name(ABRDF_STEP_SPECIAL), "special");
#ifdef ABI_GROWN
    /* The grown library really is larger than this caller's header (by this tree's models
     * added since 0.2.0 and the grown one). */
    ck_assert_int_gt(abrdf_model_count(), ABRDF_MODEL_COUNT + 1);
    ck_assert_int_eq(R->surface_count, ABRDF_SURFACE_COUNT + 1);
#endif
}
END_TEST

START_TEST(params_of_this_layout)
{
    abrdf_params *p = guarded(sizeof *p);
    ck_assert_int_eq(abrdf_params_init(ABRDF_LAMBERT, p), ABRDF_OK);
    guard_intact(p, sizeof *p, "abrdf_params");
    ck_assert_uint_eq(p->struct_size, sizeof *p);
    const double kd[3] = {0.2, 0.4, 0.6};
    memcpy(p->kd, kd, sizeof kd);
    abrdf_params *in = exact_copy(p, sizeof *p);
    const double wi[3] = {0.3, 0.0, 1.0}, wo[3] = {-0.2, 0.1, 1.0};
    double f[3];
    ck_assert_int_eq(abrdf_eval(ABRDF_LAMBERT, in, NULL, wi, wo, f), ABRDF_OK);
    for (int c = 0; c < 3; ++c) ck_assert(close_to(f[c], kd[c] / PI, 1e-15)); /* Eq. 1 */
    free(in);

    /* Blinn-Phong, ks (N.H)^n (Eq. 4), through the scalar, batch and shading paths. */
    ck_assert_int_eq(abrdf_params_init(ABRDF_BLINN_PHONG, p), ABRDF_OK);
    guard_intact(p, sizeof *p, "abrdf_params");
    int id;
    const double n = 20.0;
    ck_assert_int_eq(abrdf_param_find("n", &id), ABRDF_OK);
    ck_assert_int_eq(abrdf_param_set(p, id, &n, 1), ABRDF_OK);
    double back[3];
    ck_assert_int_eq(abrdf_param_read(p, id, back), 1);
    ck_assert(back[0] == 20.0 && p->n == 20.0);
    guard_intact(p, sizeof *p, "abrdf_params");
    in = exact_copy(p, sizeof *p);
    char msg[256];
    ck_assert_int_eq(abrdf_params_check(ABRDF_BLINN_PHONG, in, msg, sizeof msg), ABRDF_OK);
    double li = sqrt(0.09 + 1.0), lo = sqrt(0.04 + 0.01 + 1.0), h[3];
    for (int c = 0; c < 3; ++c) h[c] = wi[c] / li + wo[c] / lo;
    double expect = pow(h[2] / sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]), n) * p->ks[0];
    ck_assert_int_eq(abrdf_eval(ABRDF_BLINN_PHONG, in, NULL, wi, wo, f), ABRDF_OK);
    ck_assert_msg(close_to(f[0], expect, 1e-12), "blinn_phong %.17g, by hand %.17g", f[0], expect);
    float x[6] = {(float)(wi[0] / li), (float)(wi[1] / li), (float)(wi[2] / li),
                  (float)(wo[0] / lo), (float)(wo[1] / lo), (float)(wo[2] / lo)};
    float fr, fg, fb;
    abrdf_batch b = {1, &x[0], &x[1], &x[2], &x[3], &x[4], &x[5], &fr, &fg, &fb};
    ck_assert_int_eq(abrdf_eval_batch(ABRDF_BLINN_PHONG, in, &b), ABRDF_OK);
    ck_assert_msg(close_to(fr, expect, 1e-4), "batch %.9g, by hand %.17g", fr, expect);
    const double light[3] = {2.0, 2.0, 2.0}, ambient[3] = {0.1, 0.1, 0.1};
    double out[3];
    ck_assert_int_eq(
        abrdf_shade(ABRDF_MODEL_NONE, ABRDF_BLINN_PHONG, in, NULL, wi, wo, light, ambient, out),
        ABRDF_OK);
    ck_assert(close_to(out[0], 0.1 + 2.0 * (1.0 / li) * expect, 1e-12));
    free(in);
    free(p);
}
END_TEST

/* Counts the trace's steps and keeps the kind of the last. */
typedef struct trace_count {
    int count;
    abrdf_step_kind last;
} trace_count;

static void count_step(void *user, const abrdf_select_step *s)
{
    trace_count *t = user;
    ck_assert(s->text && *s->text);
    ck_assert(abrdf_step_name(s->kind) != NULL);
    ++t->count;
    t->last = s->kind;
}

START_TEST(selection_of_this_layout)
{
    abrdf_material *m = guarded(sizeof *m);
    abrdf_tolerance *t = guarded(sizeof *t);
    abrdf_selection *s = guarded(sizeof *s);
    abrdf_params *p = guarded(sizeof *p);
    ck_assert_int_eq(abrdf_material_init(m), ABRDF_OK);
    ck_assert_int_eq(abrdf_tolerance_init(t), ABRDF_OK);
    ck_assert_int_eq(abrdf_selection_init(s), ABRDF_OK);
    ck_assert_int_eq(abrdf_params_init(ABRDF_MODEL_NONE, p), ABRDF_OK);
    guard_intact(m, sizeof *m, "abrdf_material");
    guard_intact(t, sizeof *t, "abrdf_tolerance");
    guard_intact(s, sizeof *s, "abrdf_selection");
    guard_intact(p, sizeof *p, "abrdf_params");
    ck_assert(m->n == -1.0 && m->r == -1.0 && m->melanin == 0.3 && m->kd[0] == 0.8);
    ck_assert(t->max_rel_pct == 2.0 && t->max_abs == 0.05);
    ck_assert(s->diffuse == ABRDF_MODEL_NONE && s->specular == ABRDF_MODEL_NONE);

    /* Performance, n = 300, rel 2 %, abs 0.05: f8 at 14 cycles (docs/SELECTION.md). */
    m->n = 300.0;
    abrdf_material *min = exact_copy(m, sizeof *m);
    abrdf_tolerance *tin = exact_copy(t, sizeof *t);
    trace_count tr = {0, ABRDF_STEP_INPUT};
    ck_assert_int_eq(abrdf_select(min, ABRDF_GOAL_PERFORMANCE, tin, NULL, s, p, count_step, &tr),
                     ABRDF_OK);
    ck_assert_int_eq(s->diffuse, ABRDF_LAMBERT);
    ck_assert_int_eq(s->specular, ABRDF_F8);
    ck_assert(s->cost_specular == 14.0 && s->err_rel_pct > 0.0 && s->err_rel_pct <= 2.0);
    ck_assert(p->n == 300.0 && p->struct_size == sizeof *p);
    ck_assert_int_eq(tr.count, 11);
    ck_assert_int_eq(s->step_count, 11);
    ck_assert_int_eq(tr.last, ABRDF_STEP_CHEAPEST);
    ck_assert_str_eq(s->message, "");
    free(min);

    /* Photoreal cloth: the special model is the whole reflectance, the diffuse slot is
     * ABRDF_MODEL_NONE (not the library's model count), and the block evaluates. */
    m->type = ABRDF_SURFACE_CLOTH_ROUGH;
    m->n = -1.0;
    m->r = 0.3;
    min = exact_copy(m, sizeof *m);
    ck_assert_int_eq(abrdf_select(min, ABRDF_GOAL_PHOTOREAL, NULL, NULL, s, p, NULL, NULL),
                     ABRDF_OK);
    ck_assert_int_eq(s->diffuse, ABRDF_MODEL_NONE);
    ck_assert_int_eq(s->specular, ABRDF_NEUBELT_PETTINEO);
    const double wi[3] = {0.3, 0.0, 1.0}, wo[3] = {-0.2, 0.1, 1.0};
    double f[3];
    ck_assert_int_eq(abrdf_eval(s->specular, p, NULL, wi, wo, f), ABRDF_OK);
    ck_assert(isfinite(f[0]) && f[0] > 0.0);
    free(min);

    /* Photoreal, rough general surface: Disney diffuse + specular, shaded from the block. */
    m->type = ABRDF_SURFACE_GENERAL;
    m->r = 0.2;
    min = exact_copy(m, sizeof *m);
    ck_assert_int_eq(abrdf_select(min, ABRDF_GOAL_PHOTOREAL, NULL, NULL, s, p, NULL, NULL),
                     ABRDF_OK);
    ck_assert_int_eq(s->diffuse, ABRDF_DISNEY_DIFFUSE);
    ck_assert_int_eq(s->specular, ABRDF_DISNEY_SPECULAR);
    ck_assert(p->r == 0.2 && s->r == 0.2 && s->err_rel_pct < 0.0);
    const double light[3] = {1, 1, 1}, ambient[3] = {0, 0, 0};
    double out[3];
    ck_assert_int_eq(abrdf_shade(s->diffuse, s->specular, p, NULL, wi, wo, light, ambient, out),
                     ABRDF_OK);
    ck_assert(isfinite(out[0]) && out[0] > 0.0);
    free(min);
    free(tin);

    guard_intact(m, sizeof *m, "abrdf_material");
    guard_intact(t, sizeof *t, "abrdf_tolerance");
    guard_intact(s, sizeof *s, "abrdf_selection");
    guard_intact(p, sizeof *p, "abrdf_params");
    free(m);
    free(t);
    free(s);
    free(p);
}
END_TEST

START_TEST(costs_of_this_layout)
{
    abrdf_costs *c = guarded(sizeof *c);
    ck_assert_int_eq(abrdf_costs_paper(c), ABRDF_OK);
    guard_intact(c, sizeof *c, "abrdf_costs");
    ck_assert(abrdf_costs_get(c, ABRDF_F2) == 8.0 && abrdf_costs_get(c, ABRDF_F16) == 17.0);
    /* Measured costs that make f16 the cheapest passing candidate. */
    ck_assert_int_eq(abrdf_costs_init(c, "ns/eval"), ABRDF_OK);
    ck_assert_int_eq(abrdf_costs_set(c, ABRDF_F8, 2.0), ABRDF_OK);
    ck_assert_int_eq(abrdf_costs_set(c, ABRDF_F16, 1.5), ABRDF_OK);
    guard_intact(c, sizeof *c, "abrdf_costs");
    abrdf_material m;
    abrdf_selection s;
    abrdf_material_init(&m);
    abrdf_selection_init(&s);
    m.n = 300.0;
    ck_assert_int_eq(abrdf_select(&m, ABRDF_GOAL_PERFORMANCE, NULL, c, &s, NULL, NULL, NULL),
                     ABRDF_OK);
    ck_assert_int_eq(s.specular, ABRDF_F16);
    ck_assert_str_eq(s.cost_unit, "ns/eval");
    free(c);
}
END_TEST

START_TEST(too_small_is_refused)
{
    ck_assert(strstr(abrdf_strerror(ABRDF_E_SIZE), "struct_size") != NULL);
    abrdf_params p;
    abrdf_params_init(ABRDF_LAMBERT, &p);
    p.struct_size = 0; /* a block never initialised */
    const double wi[3] = {0, 0, 1}, wo[3] = {0, 0, 1};
    double f[3] = {1, 1, 1};
    ck_assert_int_eq(abrdf_eval(ABRDF_LAMBERT, &p, NULL, wi, wo, f), ABRDF_E_SIZE);
    ck_assert(f[0] == 0.0 && f[1] == 0.0 && f[2] == 0.0);
    char msg[256];
    ck_assert_int_eq(abrdf_params_check(ABRDF_LAMBERT, &p, msg, sizeof msg), ABRDF_E_SIZE);
    ck_assert_msg(strstr(msg, "struct_size 0") && strstr(msg, "abrdf_params_init"), "%s", msg);
    ck_assert_int_eq(abrdf_params_init_sized(ABRDF_LAMBERT, &p, sizeof p - sizeof p.layers),
                     ABRDF_E_SIZE);
    /* A result block too small to hold the message is left untouched. */
    abrdf_selection *s = guarded(sizeof *s);
    abrdf_selection_init(s);
    s->struct_size = 8;
    s->specular = ABRDF_F2;
    abrdf_material m;
    abrdf_material_init(&m);
    m.r = 0.3;
    ck_assert_int_eq(abrdf_select(&m, ABRDF_GOAL_PHOTOREAL, NULL, NULL, s, NULL, NULL, NULL),
                     ABRDF_E_SIZE);
    ck_assert_int_eq(s->specular, ABRDF_F2);
    guard_intact(s, sizeof *s, "abrdf_selection");
    free(s);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("abi_old_caller");
    TCase *tc = tcase_create("release_0_2_0");
    tcase_add_test(tc, the_library_knows_this_header);
    tcase_add_test(tc, params_of_this_layout);
    tcase_add_test(tc, selection_of_this_layout);
    tcase_add_test(tc, costs_of_this_layout);
    tcase_add_test(tc, too_small_is_refused);
    suite_add_tcase(s, tc);
    SRunner *r = srunner_create(s);
    srunner_run_all(r, CK_NORMAL);
    int failed = srunner_ntests_failed(r);
    srunner_free(r);
    return failed ? EXIT_FAILURE : EXIT_SUCCESS;
}
