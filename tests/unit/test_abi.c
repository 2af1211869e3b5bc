/* test_abi.c - the rules of abrdf.h's STABLE LAYOUTS, checked on the layouts themselves
 * (abi_layout.c compiled against three sets of headers):
 *   - against the 0.2.0 release (tests/data/abi): every 0.2.0 field keeps its offset and
 *     size, every value keeps its value, a struct with struct_size or owned by the library
 *     only grows, every other struct keeps its size;
 *   - against this tree with every *_COUNT one higher (cmake/abrdf_abi_headers.cmake): no
 *     public struct changes size or layout, so adding a model, a surface class, a goal or a
 *     step kind does not break a compiled caller. */
#include <stdio.h>
#include <string.h>
#include "abi_layout.h"
#include "test_util.h"

/* The structs that may grow: the caller's (they start with struct_size) and the library's
 * own (handed out by pointer). Every other struct is frozen. */
static const char *const growing[] = {"abrdf_params",       "abrdf_material",   "abrdf_tolerance",
                                      "abrdf_selection",    "abrdf_param_info", "abrdf_model_info",
                                      "abrdf_select_rules", "abrdf_select_step"};
static const char *const with_struct_size[] = {"abrdf_params", "abrdf_material", "abrdf_tolerance",
                                               "abrdf_selection"};

static int listed(const char *name, const char *const *list, size_t n)
{
    for (size_t i = 0; i < n; ++i)
        if (!strcmp(name, list[i])) return 1;
    return 0;
}

static const abi_entry *find(const abi_entry *t, const abi_entry *like)
{
    for (; t->name; ++t)
        if (t->kind == like->kind && !strcmp(t->name, like->name) &&
            (!like->field || (t->field && !strcmp(t->field, like->field))))
            return t;
    return NULL;
}

static const char *what(const abi_entry *e, char *buf, size_t size)
{
    snprintf(buf, size, "%s%s%s", e->name, e->field ? "." : "", e->field ? e->field : "");
    return buf;
}

START_TEST(release_0_2_0_layout_only_grows_at_the_end)
{
    int structs = 0, fields = 0, values = 0;
    for (const abi_entry *old = abi_layout_0_2_0; old->name; ++old) {
        char w[128];
        const abi_entry *now = find(abi_layout_now, old);
        ck_assert_msg(now != NULL, "%s of 0.2.0 is gone", what(old, w, sizeof w));
        switch (old->kind) {
        case ABI_STRUCT:
            ++structs;
            if (listed(old->name, growing, sizeof growing / sizeof *growing))
                ck_assert_msg(now->size >= old->size, "%s shrank: %zu < %zu bytes", old->name,
                              now->size, old->size);
            else
                ck_assert_msg(now->size == old->size, "%s is frozen but now has %zu bytes, not %zu",
                              old->name, now->size, old->size);
            break;
        case ABI_FIELD:
            ++fields;
            ck_assert_msg(now->offset == old->offset && now->size == old->size,
                          "%s moved or changed size: offset %zu size %zu, 0.2.0 had %zu, %zu",
                          what(old, w, sizeof w), now->offset, now->size, old->offset, old->size);
            if (!strcmp(old->field, "struct_size")) ck_assert_uint_eq(old->offset, 0);
            break;
        case ABI_VALUE:
            ++values;
            ck_assert_msg(now->offset == old->offset, "%s changed value", old->name);
            break;
        }
    }
    /* Every struct, field and value of abi_layout.c was compared. */
    ck_assert_int_eq(structs, 14);
    ck_assert_int_eq(fields, 121);
    ck_assert_int_eq(values, 75);
    for (size_t i = 0; i < sizeof with_struct_size / sizeof *with_struct_size; ++i) {
        abi_entry f = {ABI_FIELD, with_struct_size[i], "struct_size", 0, 0};
        const abi_entry *e = find(abi_layout_0_2_0, &f);
        ck_assert_msg(e && e->offset == 0 && e->size == sizeof(size_t), "%s lacks struct_size",
                      with_struct_size[i]);
    }
}
END_TEST

START_TEST(no_struct_depends_on_a_count)
{
    int compared = 0;
    for (const abi_entry *now = abi_layout_now; now->name; ++now) {
        char w[128];
        const abi_entry *more = find(abi_layout_counts, now);
        ck_assert_msg(more != NULL, "%s missing with grown counts", what(now, w, sizeof w));
        if (now->kind == ABI_VALUE) continue;
        ck_assert_msg(more->offset == now->offset && more->size == now->size,
                      "%s depends on a count: %zu bytes at %zu with one more model, surface, goal "
                      "and step kind, %zu at %zu now",
                      what(now, w, sizeof w), more->size, more->offset, now->size, now->offset);
        ++compared;
    }
    ck_assert_int_eq(compared, 14 + 121);
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("abi");
    TCase *tc = tcase_create("layouts");
    tcase_add_test(tc, release_0_2_0_layout_only_grows_at_the_end);
    tcase_add_test(tc, no_struct_depends_on_a_count);
    suite_add_tcase(s, tc);
    return s;
}

int main(void) { return tu_run(suite()); }
