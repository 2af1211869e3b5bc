/* test_materials.c - the material table (data/materials.csv) row by row, its metals against
 * the measured refractive indices (data/metal_nk.csv), and the loader's errors. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "materials.h"
#include "test_util.h"

#define DATA(f) ABRDF_TEST_DATA_DIR "/" f

/* A trace callback keeping the text of the first step (the material's n and r). */
static void first_step(void *user, const abrdf_select_step *st)
{
    char *first = user;
    if (!first[0]) snprintf(first, 256, "%s", st->text);
}

static mat_table load_builtin(void)
{
    mat_table t = {NULL, 0, 0};
    char err[MAT_ERR_MAX];
    int rc = mat_table_load(&t, DATA("materials.csv"), err, sizeof err);
    ck_assert_msg(rc == 0, "%s", err);
    return t;
}

START_TEST(table_has_40_rows_and_every_class)
{
    mat_table t = load_builtin();
    ck_assert_int_ge(t.count, 40);
    int per_type[ABRDF_SURFACE_COUNT] = {0};
    for (int i = 0; i < t.count; ++i) per_type[t.items[i].m.type]++;
    for (int i = 0; i < ABRDF_SURFACE_COUNT; ++i)
        ck_assert_msg(per_type[i] > 0, "no material of type %s",
                      abrdf_surface_name((abrdf_surface)i));
    static const char *const required[] = {
        "gold",        "silver",    "copper",         "aluminium",      "iron",
        "chrome",      "titanium",  "nickel",         "brass",          "platinum",
        "water",       "glass",     "acrylic",        "plastic_red",    "rubber_tire",
        "wood_oak",    "marble",    "concrete",       "skin_light",     "skin_medium",
        "skin_dark",   "wool",      "cotton",         "denim",          "silk",
        "satin",       "velvet",    "hair_blond",     "hair_brown",     "hair_black",
        "hair_red",    "car_paint", "coated_plastic", "varnished_wood", "transparent_plate",
        "coated_steel"};
    for (size_t i = 0; i < sizeof required / sizeof required[0]; ++i)
        ck_assert_msg(mat_table_find(&t, required[i]) != NULL, "material '%s' missing",
                      required[i]);
    mat_table_free(&t);
}
END_TEST

/* Ranges, required fields and plausibility of every row. */
START_TEST(every_row_is_valid_and_plausible)
{
    mat_table t = load_builtin();
    for (int i = 0; i < t.count; ++i) {
        const mat_entry *e = &t.items[i];
        const abrdf_material *m = &e->m;
        ck_assert_msg(strlen(e->source) > 10, "%s: source too short", e->name);
        ck_assert_msg(m->r >= 0.0 || m->n >= 0.0, "%s: neither n nor r", e->name);
        ck_assert(m->r <= 1.0 && m->n <= 1e6);
        ck_assert(m->anisotropy >= 0.0 && m->anisotropy <= 1.0);
        double f0[3];
        for (int c = 0; c < 3; ++c) {
            ck_assert(m->kd[c] >= 0.0 && m->kd[c] <= 1.0 && m->ks[c] >= 0.0 && m->ks[c] <= 1.0);
            double x = m->eta > 0.0 ? (m->eta - 1.0) / (m->eta + 1.0) : 0.0;
            f0[c] = m->eta > 0.0 ? x * x : m->f0[c];
            /* What is reflected at the surface is not available to the diffuse lobe. */
            ck_assert_msg(m->kd[c] + f0[c] <= 1.0, "%s: kd + F0 = %g > 1", e->name,
                          m->kd[c] + f0[c]);
        }
        int metal = m->eta <= 0.0;
        if (metal) {
            /* Measured metals reflect at least 40 % at normal incidence and have no diffuse. */
            for (int c = 0; c < 3; ++c)
                ck_assert_msg(f0[c] >= 0.4 && m->kd[c] == 0.0, "%s", e->name);
        } else {
            /* Dielectrics of this table: eta 1.3-2.42, F0 2-17 %. */
            ck_assert_msg(m->eta >= 1.3 && m->eta <= 2.42, "%s: eta %g", e->name, m->eta);
        }
        if (m->type == ABRDF_SURFACE_HAIR)
            ck_assert(m->melanin >= 0.0 && m->melanin <= 1.0 && m->eta > 1.0);
        if (m->type >= ABRDF_SURFACE_LAYERED_PLASTIC) {
            ck_assert_msg(m->layer_count >= 1, "%s: layered without a coat", e->name);
            ck_assert(m->layers[0].eta >= 1.0 && m->layers[0].eta <= 4.0);
        }
        if (m->type == ABRDF_SURFACE_LAYERED_METAL) ck_assert_int_eq(m->layer_count, 2);
        if (m->type == ABRDF_SURFACE_CLOTH_SHINY)
            ck_assert_msg(m->n > 0.0, "%s: Kajiya-Kay needs n", e->name);
        /* Every row goes through the flowchart for both goals. */
        for (int g = 0; g < ABRDF_GOAL_COUNT; ++g) {
            abrdf_selection s;
            abrdf_selection_init(&s);
            char first[256] = "";
            ck_assert_msg(abrdf_select(m, (abrdf_goal)g, NULL, NULL, &s, NULL, first_step, first) ==
                              ABRDF_OK,
                          "%s: %s", e->name, s.message);
            ck_assert(s.step_count > 2 && strstr(first, e->name));
        }
    }
    mat_table_free(&t);
}
END_TEST

/* F0 of every metal recomputed from its measured n + ik at 650/550/450 nm. */
START_TEST(metal_f0_comes_from_measured_nk)
{
    mat_table t = load_builtin();
    FILE *f = fopen(DATA("metal_nk.csv"), "r");
    ck_assert(f != NULL);
    char line[1024];
    int rows = 0, header = 0;
    while (fgets(line, sizeof line, f)) {
        if (line[0] == '#' || line[0] == '\n') continue;
        if (!header++) continue;
        char name[64];
        double nk[6];
        ck_assert_int_eq(sscanf(line, "%63[^,],%lf,%lf,%lf,%lf,%lf,%lf", name, &nk[0], &nk[1],
                                &nk[2], &nk[3], &nk[4], &nk[5]),
                         7);
        const char *src = line;
        for (int c = 0; c < 7 && src; ++c) src = strchr(src, ',') ? strchr(src, ',') + 1 : NULL;
        ck_assert_msg(src && strlen(src) > 10, "%s: no source", name);
        const mat_entry *e = mat_table_find(&t, name);
        ck_assert_msg(e != NULL, "metal_nk.csv row '%s' has no material", name);
        for (int c = 0; c < 3; ++c) {
            double n = nk[2 * c], k = nk[2 * c + 1];
            double f0 = ((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k);
            ck_assert_msg(fabs(f0 - e->m.f0[c]) <= 0.0006, "%s: F0[%d] %g, from n,k %g", name, c,
                          e->m.f0[c], f0);
        }
        if (e->m.type == ABRDF_SURFACE_LAYERED_METAL) {
            /* The base interface holds the 550 nm index relative to the coat. */
            double coat = e->m.layers[0].eta;
            ck_assert(tu_close(e->m.layers[1].eta * coat, nk[2], 1e-9, 0.0));
            ck_assert(tu_close(e->m.layers[1].kappa * coat, nk[3], 1e-9, 0.0));
        }
        ++rows;
    }
    fclose(f);
    ck_assert_int_ge(rows, 10);
    /* Every metal of the table has its measurement. */
    for (int i = 0; i < t.count; ++i)
        if (t.items[i].m.eta <= 0.0)
            ck_assert_msg(strstr(t.items[i].source, "metal_nk"), "%s", t.items[i].name);
    mat_table_free(&t);
}
END_TEST

/* ---- loader errors -------------------------------------------------------------------- */

static const char *HEADER =
    "name,type,n,r,kd_r,kd_g,kd_b,ks_r,ks_g,ks_b,f0_r,f0_g,f0_b,eta,"
    "anisotropy,melanin,redness,coat_eta,coat_r,coat_depth,coat_sa_r,coat_sa_g,coat_sa_b,"
    "base_eta,base_kappa,source\n";

static void write_file(const char *path, const char *header, const char *body)
{
    FILE *f = fopen(path, "w");
    ck_assert(f != NULL);
    fputs("# a user's material file\n", f);
    fputs(header, f);
    fputs(body, f);
    fclose(f);
}

/* Load a file; expect failure with "path:LINE: <needle>" (line 3 = the first row). */
static void expect_error_at(const char *row, int line, const char *needle)
{
    const char *path = "test_materials_tmp.csv";
    char err[MAT_ERR_MAX], prefix[80];
    write_file(path, HEADER, row);
    mat_table t = {NULL, 0, 0};
    ck_assert_int_eq(mat_table_load(&t, path, err, sizeof err), -1);
    snprintf(prefix, sizeof prefix, "%s:%d: ", path, line);
    ck_assert_msg(strncmp(err, prefix, strlen(prefix)) == 0, "'%s' does not start with '%s'", err,
                  prefix);
    ck_assert_msg(strstr(err, needle) != NULL, "'%s' lacks '%s'", err, needle);
    ck_assert_int_eq(t.count, 0);
    remove(path);
}

static void expect_error(const char *row, const char *needle) { expect_error_at(row, 3, needle); }

#define GOOD "gold,general,,0.2,0,0,0,1,1,1,0.957,0.792,0.408,,,,,,,,,,,,,J&C 1972\n"

START_TEST(loader_reports_file_line_and_problem)
{
    expect_error("gold,general,,abc,0,0,0,1,1,1,0.9,0.8,0.4,,,,,,,,,,,,,src\n",
                 "column 'r': 'abc' is not a finite number");
    expect_error("gold,general,,1.5,0,0,0,1,1,1,0.9,0.8,0.4,,,,,,,,,,,,,src\n",
                 "column 'r': 1.5 is outside [0, 1]");
    expect_error("gold,general,-3,,0,0,0,1,1,1,0.9,0.8,0.4,,,,,,,,,,,,,src\n",
                 "column 'n': -3 is outside [0, 1e+06]");
    expect_error("gold,general,,nan,0,0,0,1,1,1,0.9,0.8,0.4,,,,,,,,,,,,,src\n",
                 "'nan' is not a finite number");
    expect_error("gold,metal,,0.2,0,0,0,1,1,1,0.9,0.8,0.4,,,,,,,,,,,,,src\n",
                 "type 'metal' is not one of: general");
    expect_error("gold,general,,0.2,0,0,0,1,1,1,0.9,0.8,0.4,,,,,,,,,,,,,\n",
                 "column 'source' is empty");
    expect_error("gold,general,,,0,0,0,1,1,1,0.9,0.8,0.4,,,,,,,,,,,,,src\n", "give n or r");
    expect_error("gold,general,,0.2,0,0,,1,1,1,0.9,0.8,0.4,,,,,,,,,,,,,src\n", "give all three");
    expect_error("gold,general,,0.2,0,0,0,1,1,1,,,,,,,,,,,,,,,,src\n", "give f0_r..f0_b or eta");
    expect_error("Gold,general,,0.2,0,0,0,1,1,1,0.9,0.8,0.4,,,,,,,,,,,,,src\n", "name 'Gold'");
    expect_error("gold,general,,0.2\n", "fields, expected 26");
    expect_error("pvc,layered_plastic,,0.2,0.5,0.5,0.5,1,1,1,,,,1.5,,,,,,,,,,,,src\n",
                 "needs the coat columns");
    expect_error(
        "m,layered_metal,,0.1,0,0,0,1,1,1,0.9,0.8,0.4,,,,,1.5,0.1,0.03,0,0,0,0.4,2.5,src\n",
        "outside libabrdf's layer ranges");
    expect_error_at(GOOD GOOD, 4, "material 'gold' is already defined at line 3");
}
END_TEST

START_TEST(loader_rejects_a_bad_header_and_a_missing_file)
{
    const char *path = "test_materials_tmp.csv";
    char err[MAT_ERR_MAX];
    mat_table t = {NULL, 0, 0};
    write_file(path, "name,type,r,n\n", GOOD);
    ck_assert_int_eq(mat_table_load(&t, path, err, sizeof err), -1);
    ck_assert_msg(strstr(err, "test_materials_tmp.csv:2: header: column 3 is 'r', expected 'n'"),
                  "%s", err);
    remove(path);
    ck_assert_int_eq(mat_table_load(&t, "no/such/materials.csv", err, sizeof err), -1);
    ck_assert_msg(strstr(err, "no/such/materials.csv: cannot open: No such file"), "%s", err);
}
END_TEST

/* A user file replaces rows by name and appends new ones; a bad one changes nothing. */
START_TEST(user_file_overrides_by_name)
{
    mat_table t = load_builtin();
    int count = t.count;
    const char *path = "test_materials_tmp.csv";
    char err[MAT_ERR_MAX];
    write_file(path, HEADER,
               "gold,general,,0.01,0,0,0,1,1,1,0.957,0.792,0.408,,,,,,,,,,,,,my polish\n"
               "unobtainium,general,,0.5,0.2,0.2,0.2,1,1,1,,,,1.5,,,,,,,,,,,,made up\n");
    ck_assert_msg(mat_table_load(&t, path, err, sizeof err) == 0, "%s", err);
    ck_assert_int_eq(t.count, count + 1);
    const mat_entry *g = mat_table_find(&t, "gold");
    ck_assert(g->m.r == 0.01 && !strcmp(g->source, "my polish") && g->line == 3);
    ck_assert(g->m.name == g->name);
    ck_assert(mat_table_find(&t, "unobtainium") != NULL);
    write_file(path, HEADER, "silver,general,,7,0,0,0,1,1,1,0.9,0.9,0.9,,,,,,,,,,,,,x\n");
    ck_assert_int_eq(mat_table_load(&t, path, err, sizeof err), -1);
    ck_assert(mat_table_find(&t, "silver")->m.r == 0.15);
    remove(path);
    const char *near[5];
    ck_assert_int_ge(mat_table_nearest(&t, "gld", near, 5), 1);
    ck_assert_str_eq(near[0], "gold");
    ck_assert_int_ge(mat_table_nearest(&t, "alumin", near, 5), 1);
    ck_assert_str_eq(near[0], "aluminium");
    ck_assert_int_eq(mat_table_nearest(&t, "zzzzzzzzzzzz", near, 5), 0);
    mat_table_free(&t);
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("materials");
    TCase *tc = tcase_create("table");
    tcase_add_test(tc, table_has_40_rows_and_every_class);
    tcase_add_test(tc, every_row_is_valid_and_plausible);
    tcase_add_test(tc, metal_f0_comes_from_measured_nk);
    suite_add_tcase(s, tc);
    TCase *ld = tcase_create("loader");
    tcase_add_test(ld, loader_reports_file_line_and_problem);
    tcase_add_test(ld, loader_rejects_a_bad_header_and_a_missing_file);
    tcase_add_test(ld, user_file_overrides_by_name);
    suite_add_tcase(s, ld);
    return s;
}

int main(void) { return tu_run(suite()); }
