/* test_merl.c - MERL BRDF files (tools/measured: merl.h, measured_file.h): a table written and
 * read back is the same to the bit; the database's scales are applied; negative values are
 * cells not measured; every broken file is refused with one line naming it and its fault,
 * before any large allocation; a refused or failed write leaves nothing behind. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "measured_file.h"
#include "merl.h"
#include "test_util.h"

static char dir[256];

static const char *at(const char *name)
{
    static char buf[4][512];
    static int k;
    k = (k + 1) % 4;
    snprintf(buf[k], sizeof buf[k], "%s/%s", dir, name);
    return buf[k];
}

static void setup(void)
{
    snprintf(dir, sizeof dir, "%s/test_merl.XXXXXX", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
    ck_assert_ptr_nonnull(mkdtemp(dir));
}

static void teardown(void)
{
    DIR *d = opendir(dir);
    struct dirent *e;
    while (d && (e = readdir(d)))
        if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..")) {
            char p[600];
            snprintf(p, sizeof p, "%s/%s", dir, e->d_name);
            if (rmdir(p) != 0) unlink(p);
        }
    if (d) closedir(d);
    rmdir(dir);
}

/* How many entries the test directory holds (temporary files too). */
static int entries(void)
{
    int n = 0;
    DIR *d = opendir(dir);
    struct dirent *e;
    while (d && (e = readdir(d))) n += strcmp(e->d_name, ".") && strcmp(e->d_name, "..");
    if (d) closedir(d);
    return n;
}

static void le32(FILE *f, int32_t v)
{
    uint32_t u = (uint32_t)v;
    for (int k = 0; k < 4; ++k) fputc((int)(u >> (8 * k)) & 0xff, f);
}

static void le64(FILE *f, double d)
{
    uint64_t u;
    memcpy(&u, &d, sizeof u);
    for (int k = 0; k < 8; ++k) fputc((int)(u >> (8 * k)) & 0xff, f);
}

static double read_le64(const unsigned char *p)
{
    uint64_t u = 0;
    for (int k = 7; k >= 0; --k) u = u << 8 | p[k];
    double d;
    memcpy(&d, &u, sizeof d);
    return d;
}

/* A file of grid nh x nd x np whose stored values are stored(c, i); extra bytes appended
 * (negative: that many cut). */
static const char *put_file(const char *name, int nh, int nd, int np, double (*stored)(int, long),
                            long extra)
{
    FILE *f = fopen(at(name), "wb");
    ck_assert_ptr_nonnull(f);
    le32(f, nh), le32(f, nd), le32(f, np);
    long cells = (long)nh * nd * np;
    for (int c = 0; c < 3; ++c)
        for (long i = 0; i < cells; ++i) le64(f, stored(c, i));
    for (long k = 0; k < extra; ++k) fputc(0, f);
    fclose(f);
    if (extra < 0) {
        struct stat st;
        ck_assert_int_eq(stat(at(name), &st), 0);
        ck_assert_int_eq(truncate(at(name), st.st_size + extra), 0);
    }
    return at(name);
}

static double stored_1500(int c, long i) { return (void)c, (void)i, 1500.0; }
static double stored_ramp(int c, long i) { return 0.25 * (double)i + 1000.0 * c; }

/* The refusal of a file: -1, an empty table, one line that starts with the file's name and
 * holds each needle. */
static void refused(const char *path, const char *needle1, const char *needle2)
{
    measured_table t;
    char err[1024];
    ck_assert_int_eq(merl_read(path, &t, err, sizeof err), -1);
    ck_assert_ptr_null(t.data);
    ck_assert_int_eq(t.n_theta_h, 0);
    ck_assert_ptr_null(strchr(err, '\n'));
    ck_assert_msg(!strncmp(err, path, strlen(path)) && err[strlen(path)] == ':', "%s", err);
    ck_assert_msg(strstr(err, needle1), "'%s' lacks '%s'", err, needle1);
    if (needle2) ck_assert_msg(strstr(err, needle2), "'%s' lacks '%s'", err, needle2);
}

/* A small table of known values: every channel different, some cells not measured. */
static void known_table(measured_table *t)
{
    char err[256];
    ck_assert_int_eq(measured_table_alloc(t, 8, 8, 16, err, sizeof err), 0);
    size_t cells = 8 * 8 * 16;
    for (size_t i = 0; i < cells; ++i)
        for (int c = 0; c < 3; ++c)
            t->data[3 * i + c] = (float)(0.001 * (double)(i * 7 % 1013) * (1 + c) + 1e-7 * c);
    t->data[3 * 5 + 1] = -1.0f; /* green of cell 5 */
    t->data[3 * 77] = t->data[3 * 77 + 1] = t->data[3 * 77 + 2] = -1.0f;
    t->data[3 * 100 + 2] = 12345.678f; /* a highlight */
    t->data[3 * 101] = 1e-30f;         /* tiny, still measured */
    t->unmeasured = 2;
}

START_TEST(round_trip_is_bit_exact)
{
    measured_table t, r;
    char err[1024];
    known_table(&t);
    ck_assert_msg(merl_write(at("t.binary"), &t, err, sizeof err) == 0, "%s", err);
    struct stat st;
    ck_assert_int_eq(stat(at("t.binary"), &st), 0);
    ck_assert_int_eq(st.st_size, 12 + 24 * 8 * 8 * 16);
    ck_assert_msg(merl_read(at("t.binary"), &r, err, sizeof err) == 0, "%s", err);
    ck_assert_int_eq(r.n_theta_h, 8);
    ck_assert_int_eq(r.n_theta_d, 8);
    ck_assert_int_eq(r.n_phi_d, 16);
    ck_assert_uint_eq(r.unmeasured, 2);
    ck_assert_int_eq(memcmp(t.data, r.data, 3 * 8 * 8 * 16 * sizeof(float)), 0);
    measured_table_free(&t);
    measured_table_free(&r);
    ck_assert_int_eq(entries(), 1); /* no temporary file left */
}
END_TEST

START_TEST(scales_are_applied_both_ways)
{
    measured_table t;
    char err[1024];
    const char *path = put_file("s.binary", 2, 2, 2, stored_1500, 0);
    ck_assert_msg(merl_read(path, &t, err, sizeof err) == 0, "%s", err);
    ck_assert_uint_eq(t.unmeasured, 0);
    for (int i = 0; i < 8; ++i) {
        ck_assert_float_eq(t.data[3 * i], (float)(1500.0 * (1.0 / 1500.0)));
        ck_assert_float_eq(t.data[3 * i + 1], (float)(1500.0 * (1.15 / 1500.0)));
        ck_assert_float_eq(t.data[3 * i + 2], (float)(1500.0 * (1.66 / 1500.0)));
    }
    /* The writer divides: red 0.5 1/sr is stored as 750, blue 1.66 as 1500. */
    t.data[0] = 0.5f, t.data[2] = 1.66f;
    ck_assert_msg(merl_write(at("w.binary"), &t, err, sizeof err) == 0, "%s", err);
    unsigned char buf[12 + 24 * 8];
    FILE *f = fopen(at("w.binary"), "rb");
    ck_assert_uint_eq(fread(buf, 1, sizeof buf, f), sizeof buf);
    fclose(f);
    ck_assert(buf[0] == 2 && buf[4] == 2 && buf[8] == 2 && !buf[1] && !buf[5] && !buf[9]);
    ck_assert(fabs(read_le64(buf + 12) - 750.0) < 1e-9);
    ck_assert(fabs(read_le64(buf + 12 + 16 * 8) - 1500.0) < 1e-4);
    measured_table_free(&t);
}
END_TEST

static double stored_holes(int c, long i) { return (i == 3 && c == 1) || i == 6 ? -5.0 : 15.0; }

START_TEST(negative_values_are_not_measured)
{
    measured_table t;
    char err[1024];
    const char *path = put_file("h.binary", 2, 2, 2, stored_holes, 0);
    ck_assert_msg(merl_read(path, &t, err, sizeof err) == 0, "%s", err);
    ck_assert_uint_eq(t.unmeasured, 2);
    ck_assert_float_eq(t.data[3 * 3 + 1], -1.0f);
    ck_assert(t.data[3 * 3] > 0 && t.data[3 * 3 + 2] > 0);
    for (int c = 0; c < 3; ++c) ck_assert_float_eq(t.data[3 * 6 + c], -1.0f);
    /* Written back as -1. */
    ck_assert_msg(merl_write(at("h2.binary"), &t, err, sizeof err) == 0, "%s", err);
    unsigned char buf[12 + 24 * 8];
    FILE *f = fopen(at("h2.binary"), "rb");
    ck_assert_uint_eq(fread(buf, 1, sizeof buf, f), sizeof buf);
    fclose(f);
    ck_assert(read_le64(buf + 12 + 8 * (8 + 3)) == -1.0);
    ck_assert(read_le64(buf + 12 + 8 * 6) == -1.0);
    measured_table_free(&t);
}
END_TEST

static double stored_nan(int c, long i) { return c == 1 && i == 5 ? NAN : 1.0; }
static double stored_inf(int c, long i) { return c == 2 && i == 7 ? -INFINITY : 1.0; }
static double stored_huge(int c, long i) { return c == 0 && i == 2 ? 1e12 : 1.0; }

START_TEST(broken_files_are_refused)
{
    refused(at("missing.binary"), "cannot open", NULL);
    ck_assert_int_eq(mkdir(at("d.binary"), 0700), 0);
    refused(at("d.binary"), "is a directory", NULL);
    FILE *f = fopen(at("short.binary"), "wb");
    fputs("12345", f);
    fclose(f);
    refused(at("short.binary"), "5 bytes", "shorter than the 12-byte header");
    refused(put_file("zero.binary", 0, 8, 16, stored_1500, 0), "absurd sizes 0 x 8 x 16", NULL);
    refused(put_file("neg.binary", 8, -3, 16, stored_1500, 0), "absurd sizes 8 x -3 x 16", NULL);
    f = fopen(at("big.binary"), "wb"); /* each axis in range, the product not: header only */
    le32(f, 1024), le32(f, 1024), le32(f, 1024);
    fclose(f);
    refused(at("big.binary"), "absurd sizes 1024 x 1024 x 1024", "16777216 cells");
    f = fopen(at("max.binary"), "wb"); /* INT32_MIN, INT32_MAX: no overflow in the check */
    le32(f, INT32_MIN), le32(f, INT32_MAX), le32(f, INT32_MAX);
    fclose(f);
    refused(at("max.binary"), "absurd sizes", NULL);
    refused(put_file("cut.binary", 2, 2, 2, stored_1500, -1), "truncated: 203 bytes", "takes 204");
    refused(put_file("tail.binary", 2, 2, 2, stored_1500, 3), "3 trailing bytes", "takes 204");
    refused(put_file("nan.binary", 2, 2, 4, stored_nan, 0), "green channel, cell 5", "NaN");
    refused(put_file("inf.binary", 2, 2, 4, stored_inf, 0), "blue channel, cell 7", "an infinity");
    refused(put_file("huge.binary", 2, 2, 4, stored_huge, 0), "red channel, cell 2",
            "above the plausibility bound of 1e+06 1/sr");
    /* A well-formed file next to them reads (the cell index names the grid's order). */
    measured_table t;
    char err[512];
    ck_assert_int_eq(merl_read(put_file("ok.binary", 2, 3, 4, stored_ramp, 0), &t, err, sizeof err),
                     0);
    ck_assert_float_eq(t.data[measured_table_cell(&t, 1, 2, 3) + 2],
                       (float)((0.25 * 23 + 2000.0) * (1.66 / 1500.0)));
    measured_table_free(&t);
}
END_TEST

START_TEST(refused_writes_leave_nothing)
{
    measured_table t;
    char err[1024];
    known_table(&t);
    /* An existing target stays as it was. */
    FILE *f = fopen(at("keep.binary"), "w");
    fputs("old", f);
    fclose(f);
    t.data[3 * 9 + 1] = NAN;
    ck_assert_int_eq(merl_write(at("keep.binary"), &t, err, sizeof err), -1);
    ck_assert_msg(strstr(err, "green channel, cell 9") && strstr(err, "NaN"), "%s", err);
    t.data[3 * 9 + 1] = 2e6f;
    ck_assert_int_eq(merl_write(at("new.binary"), &t, err, sizeof err), -1);
    ck_assert_msg(strstr(err, "above the plausibility bound"), "%s", err);
    t.data[3 * 9 + 1] = INFINITY;
    ck_assert_int_eq(merl_write(at("new.binary"), &t, err, sizeof err), -1);
    ck_assert_msg(strstr(err, "an infinity"), "%s", err);
    t.data[3 * 9 + 1] = 0.5f;
    ck_assert_int_eq(merl_write(at("no/such/dir/x.binary"), &t, err, sizeof err), -1);
    ck_assert_msg(strstr(err, "no/such/dir/x.binary:"), "%s", err);
    int nh = t.n_theta_h;
    t.n_theta_h = 1;
    ck_assert_int_eq(merl_write(at("new.binary"), &t, err, sizeof err), -1);
    ck_assert_msg(strstr(err, "absurd sizes 1 x 8 x 16"), "%s", err);
    t.n_theta_h = nh;
    ck_assert_int_eq(entries(), 1);
    struct stat st;
    ck_assert_int_eq(stat(at("keep.binary"), &st), 0);
    ck_assert_int_eq(st.st_size, 3);
    /* Through an opened output: refused, discarded, nothing left. */
    out_file o;
    ck_assert_int_eq(out_file_open(&o, at("o.binary"), err, sizeof err), 0);
    t.data[0] = NAN;
    ck_assert_int_eq(merl_write_to(&o, &t, err, sizeof err), -1);
    out_file_discard(&o);
    ck_assert_int_eq(entries(), 1);
    measured_table_free(&t);
}
END_TEST

START_TEST(formats_by_extension)
{
    char err[512];
    const measured_format *m = measured_file_format("a/b.binary", 1, err, sizeof err);
    ck_assert_ptr_nonnull(m);
    ck_assert_ptr_eq(m->write_to, merl_write_to);
    ck_assert_ptr_eq(measured_file_format("B.BINARY", 0, err, sizeof err), m);
    ck_assert_ptr_null(measured_file_format("x.bsdf", 1, err, sizeof err));
    ck_assert_msg(strstr(err, "x.bsdf: '.bsdf' is not") && strstr(err, ".binary (MERL"), "%s", err);
    ck_assert_ptr_null(measured_file_format("dir.binary/x", 0, err, sizeof err));
    ck_assert_msg(strstr(err, "no extension"), "%s", err);
    ck_assert_ptr_null(measured_file_format(".binary", 0, err, sizeof err));
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("merl");
    TCase *t = tcase_create("merl");
    tcase_add_checked_fixture(t, setup, teardown);
    tcase_add_test(t, round_trip_is_bit_exact);
    tcase_add_test(t, scales_are_applied_both_ways);
    tcase_add_test(t, negative_values_are_not_measured);
    tcase_add_test(t, broken_files_are_refused);
    tcase_add_test(t, refused_writes_leave_nothing);
    tcase_add_test(t, formats_by_extension);
    suite_add_tcase(s, t);
    return s;
}

int main(void) { return tu_run(suite()); }
