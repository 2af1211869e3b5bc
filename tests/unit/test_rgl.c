/* test_rgl.c - RGL .bsdf files (tools/measured/rgl_bsdf.h): the parser refuses every broken
 * file with one line that names it and allocates nothing; closed forms written by rgl_write
 * read back through rgl_read within the tabulation's error. Mitsuba 3 checks the same files
 * in tests/cli/test_rgl_mitsuba.py. */
#define _POSIX_C_SOURCE 200809L
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "rgl_bsdf.h"
#include "rgl_models.h"
#include "test_util.h"

#define GOOD_TEXT "ggx, tabulated by rgl_write for the parser's tests" /* > 16 bytes */
static char dir[64];
static unsigned char *good; /* a valid file (coarse grid), its bytes */
static size_t good_size;

static void setup(void)
{
    snprintf(dir, sizeof dir, "/tmp/abrdf_test_rgl_%ld", (long)getpid());
    mkdir(dir, 0700);
    char path[128], err[512];
    snprintf(path, sizeof path, "%s/good.bsdf", dir);
    rgl_write_grid g = {4, 16, 8};
    ck_assert_msg(rgl_write(path, rgl_model_ggx, NULL, &g, GOOD_TEXT, err, sizeof err) == 0, "%s",
                  err);
    FILE *f = fopen(path, "rb");
    ck_assert_ptr_nonnull(f);
    fseek(f, 0, SEEK_END);
    good_size = (size_t)ftell(f);
    fseek(f, 0, SEEK_SET);
    good = malloc(good_size);
    ck_assert_uint_eq(fread(good, 1, good_size, f), good_size);
    fclose(f);
}

static void teardown(void)
{
    free(good);
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    ck_assert_int_eq(system(cmd), 0);
}

/* The offset of the header entry of field `name` (its u16 name length). */
static size_t entry(const char *name)
{
    size_t at = 18, len = strlen(name);
    for (;;) {
        size_t n = good[at] | (size_t)good[at + 1] << 8;
        unsigned rank = good[at + 2 + n] | (unsigned)good[at + 3 + n] << 8;
        if (n == len && memcmp(good + at + 2, name, n) == 0) return at;
        at += 2 + n + 2 + 1 + 8 + 8 * (size_t)rank;
        ck_assert_uint_lt(at, good_size);
    }
}

static size_t type_at(const char *name) { return entry(name) + 2 + strlen(name) + 2; }
static size_t offset_at(const char *name) { return type_at(name) + 1; }
static size_t shape_at(const char *name, int k) { return offset_at(name) + 8 + 8 * (size_t)k; }

static uint64_t get64(const unsigned char *p)
{
    uint64_t v = 0;
    for (int k = 7; k >= 0; --k) v = v << 8 | p[k];
    return v;
}

static void put64(unsigned char *p, uint64_t v)
{
    for (int k = 0; k < 8; ++k) p[k] = (unsigned char)(v >> (8 * k));
}

/* Parse size bytes of data; expect a refusal naming "case.bsdf" and containing want. */
static void refused(const unsigned char *data, size_t size, const char *want)
{
    rgl_bsdf *b = (rgl_bsdf *)&b;
    char err[512];
    ck_assert_int_eq(rgl_parse(data, size, "case.bsdf", &b, err, sizeof err), -1);
    ck_assert_ptr_null(b);
    ck_assert_msg(strncmp(err, "case.bsdf: ", 11) == 0 && strstr(err, want) && !strchr(err, '\n'),
                  "expected \"%s\" in \"%s\"", want, err);
}

/* A copy of the good file with len bytes at `at` replaced. */
static unsigned char *patched(size_t at, const void *bytes, size_t len)
{
    unsigned char *d = malloc(good_size);
    memcpy(d, good, good_size);
    memcpy(d + at, bytes, len);
    return d;
}

static void refused_patch(size_t at, const void *bytes, size_t len, const char *want)
{
    unsigned char *d = patched(at, bytes, len);
    refused(d, good_size, want);
    free(d);
}

START_TEST(good_file_parses)
{
    rgl_bsdf *b;
    char err[512];
    ck_assert_msg(rgl_parse(good, good_size, "good.bsdf", &b, err, sizeof err) == 0, "%s", err);
    ck_assert_str_eq(rgl_description(b), GOOD_TEXT);
    double wi[3], wo[3], f[3], below[3] = {0.6, 0, -0.8};
    tu_dir(30, 0, wi);
    tu_dir(30, 180, wo);
    rgl_eval(b, wi, wo, f);
    ck_assert(f[0] > 0 && f[1] > 0 && f[2] > 0);
    rgl_eval(b, wi, below, f);
    ck_assert(f[0] == 0 && f[1] == 0 && f[2] == 0);
    rgl_free(b);
}
END_TEST

START_TEST(truncated)
{
    refused(good, 10, "too short");
    refused(good, 40, "ends past the end of the file");
    refused(good, good_size - 1, "outside the data");
    refused(good, 0, "too short");
}
END_TEST

START_TEST(bad_magic_and_version)
{
    refused_patch(0, "tensor_fila", 11, "not a tensor file");
    unsigned char v[2] = {2, 0};
    refused_patch(12, v, 2, "version 2.0");
}
END_TEST

START_TEST(wrong_dtype)
{
    unsigned char t = 9; /* float16: fewer bytes, inside the file, the wrong type */
    refused_patch(type_at("rgb"), &t, 1, "field \"rgb\": float16 of rank 5, expected float32");
    t = 0;
    refused_patch(type_at("ndf"), &t, 1, "unknown type 0");
    t = 12;
    refused_patch(type_at("ndf"), &t, 1, "unknown type 12");
    t = 10; /* description as float32 */
    refused_patch(type_at("jacobian"), &t, 1, "field \"jacobian\"");
}
END_TEST

START_TEST(shape_size_mismatch)
{
    unsigned char e[8];
    put64(e, 2); /* rgb [1, 4, 2, 8, 8]: inside the file, not 3 channels */
    refused_patch(shape_at("rgb", 2), e, 8, "field \"rgb\": shape [1, 4, 2, 8, 8]");
    put64(e, 9); /* vndf [1, 4, 9, 8]: more than its bytes before the next field */
    refused_patch(shape_at("vndf", 2), e, 8, "overlap");
    put64(e, 7); /* luminance [1, 4, 7, 8] against rgb's 8 x 8 */
    refused_patch(shape_at("luminance", 2), e, 8, "field \"luminance\": shape");
    put64(e, 3); /* theta_i of 3 against the vndf's 4 slices */
    refused_patch(shape_at("theta_i", 0), e, 8, "field \"vndf\": shape [1, 4, 8, 8]");
    put64(e, get64(good + offset_at("ndf"))); /* sigma's data on ndf's */
    refused_patch(offset_at("sigma"), e, 8, "overlap");
    put64(e, 4); /* data inside the header */
    refused_patch(offset_at("rgb"), e, 8, "outside the data");
    put64(e, good_size - 8); /* data running past the end */
    refused_patch(offset_at("rgb"), e, 8, "outside the data");
}
END_TEST

START_TEST(huge_sizes)
{
    unsigned char e[8];
    put64(e, (uint64_t)1 << 62);
    refused_patch(shape_at("rgb", 3), e, 8, "shape larger than the file");
    put64(e, (uint64_t)1 << 31); /* with the next extent: the product overflows 64 bits */
    unsigned char two[16];
    memcpy(two, e, 8);
    memcpy(two + 8, e, 8);
    refused_patch(shape_at("rgb", 3), two, 16, "shape larger than the file");
    put64(e, ~(uint64_t)0);
    refused_patch(offset_at("rgb"), e, 8, "outside the data");
    unsigned char n[4] = {0xff, 0xff, 0xff, 0x7f};
    refused_patch(14, n, 4, "fields, expected 1 to");
    unsigned char z[4] = {0, 0, 0, 0};
    refused_patch(14, z, 4, "0 fields");
    unsigned char rank[2] = {0xff, 0xff};
    refused_patch(type_at("rgb") - 2, rank, 2, "rank 65535");
}
END_TEST

START_TEST(nan_inf_negative)
{
    const float bad[3] = {NAN, INFINITY, -1.0f};
    const char *want[3] = {"is nan", "is inf", "expected >= 0"};
    for (int k = 0; k < 3; ++k) {
        unsigned char b4[4];
        memcpy(b4, &bad[k], 4); /* the host is little-endian, as the files are */
        size_t rgb = (size_t)get64(good + offset_at("rgb")) + 4 * 17;
        if (k < 2) refused_patch(rgb, b4, 4, want[k]);
        size_t vndf = (size_t)get64(good + offset_at("vndf")) + 4 * 5;
        refused_patch(vndf, b4, 4, want[k]);
    }
}
END_TEST

START_TEST(missing_and_foreign_fields)
{
    refused_patch(entry("rgb") + 2, "xyz", 3, "no \"rgb\" field");
    unsigned char *d = patched(entry("rgb") + 2, "xyz", 3);
    memcpy(d + entry("description") + 2, "wavelengths", 11);
    refused(d, good_size, "a spectral file");
    free(d);
    refused_patch(entry("sigma") + 2, "ndf\x01", 4, "has byte 0x01");
    refused_patch(entry("sigma") + 2, "sigmb", 5, "no \"sigma\" field");
    refused_patch(entry("sigma") + 2, "phi_i", 5, "field \"phi_i\" appears twice");
    unsigned char e[8];
    put64(e, 2); /* two phi_i slices: isotropic still, but the vndf has one */
    refused_patch(shape_at("phi_i", 0), e, 8, "field \"vndf\": shape [1, 4, 8, 8], expected [2, 4");
    /* Four phi_i slices (anisotropic), in the description's bytes (emptied). */
    d = patched(shape_at("description", 0), "\0\0\0\0\0\0\0\0", 8);
    memcpy(d + offset_at("phi_i"), good + offset_at("description"), 8);
    put64(e, 4);
    memcpy(d + shape_at("phi_i", 0), e, 8);
    refused(d, good_size, "an anisotropic material (4 phi_i slices)");
    free(d);
}
END_TEST

START_TEST(not_regular_files)
{
    rgl_bsdf *b;
    char err[512];
    ck_assert_int_eq(rgl_load(dir, &b, err, sizeof err), -1);
    ck_assert_ptr_null(b);
    ck_assert_msg(strstr(err, "is a directory") != NULL, "%s", err);
    char path[128];
    snprintf(path, sizeof path, "%s/missing.bsdf", dir);
    ck_assert_int_eq(rgl_load(path, &b, err, sizeof err), -1);
    ck_assert_msg(strstr(err, "missing.bsdf: cannot open") != NULL, "%s", err);
    measured_table t;
    ck_assert_int_eq(rgl_read(dir, &t, 8, 8, 8, err, sizeof err), -1);
    ck_assert_ptr_null(t.data);
    snprintf(path, sizeof path, "%s/good.bsdf", dir);
    ck_assert_int_eq(rgl_read(path, &t, 1, 8, 8, err, sizeof err), -1);
    ck_assert_ptr_null(t.data);
    ck_assert_msg(strstr(err, "good.bsdf: theta_h") != NULL, "%s", err);
}
END_TEST

START_TEST(writer_refuses)
{
    char path[128], err[512];
    struct stat st;
    snprintf(path, sizeof path, "%s/bad_grid.bsdf", dir);
    rgl_write_grid g = {1, 16, 8};
    ck_assert_int_eq(rgl_write(path, rgl_model_lambert, NULL, &g, NULL, err, sizeof err), -1);
    ck_assert_msg(strstr(err, "bad_grid.bsdf: grid 1 theta_i") != NULL, "%s", err);
    ck_assert_int_ne(stat(path, &st), 0);
    snprintf(path, sizeof path, "%s/no/such/dir.bsdf", dir);
    g.n_theta_i = 4;
    ck_assert_int_eq(rgl_write(path, rgl_model_lambert, NULL, &g, NULL, err, sizeof err), -1);
    ck_assert_msg(strstr(err, "dir.bsdf") != NULL, "%s", err);
}
END_TEST

/* Every cell of a table read back from a file of model against the closed form: cells with
 * both directions above ELEV_MIN_Z compared, the rest only checked finite and >= 0. */
#define ELEV_MIN_Z 0.2 /* cos 78.5 degrees: nearer the horizon the warp's patches are wide */
static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static void round_trip(const char *name, rgl_brdf_fn model, double median_max, double p99_max,
                       double worst_max)
{
    char path[128], err[512];
    snprintf(path, sizeof path, "%s/%s.bsdf", dir, name);
    rgl_write_grid g = RGL_WRITE_GRID_DEFAULT;
    ck_assert_msg(rgl_write(path, model, NULL, &g, name, err, sizeof err) == 0, "%s", err);
    measured_table t;
    ck_assert_msg(rgl_read(path, &t, 32, 32, 32, err, sizeof err) == 0, "%s", err);
    /* not measured: exactly the cells with a direction below cos 89 degrees */
    size_t low = 0;
    for (int ih = 0; ih < 32; ++ih)
        for (int id = 0; id < 32; ++id)
            for (int ip = 0; ip < 32; ++ip) {
                double wi[3], wo[3];
                measured_table_directions(&t, ih, id, ip, wi, wo);
                low += !(wi[2] > RGL_READ_Z_MIN && wo[2] > RGL_READ_Z_MIN);
            }
    ck_assert_uint_eq(t.unmeasured, low);
    ck_assert_uint_gt(low, 0);
    double *rel = malloc(32 * 32 * 32 * sizeof *rel);
    size_t n = 0;
    for (int ih = 0; ih < 32; ++ih)
        for (int id = 0; id < 32; ++id)
            for (int ip = 0; ip < 32; ++ip) {
                double wi[3], wo[3], want[3];
                measured_table_directions(&t, ih, id, ip, wi, wo);
                const float *cell = t.data + measured_table_cell(&t, ih, id, ip);
                if (!(wi[2] > RGL_READ_Z_MIN && wo[2] > RGL_READ_Z_MIN)) {
                    ck_assert(cell[0] == -1 && cell[1] == -1 && cell[2] == -1);
                    continue;
                }
                for (int c = 0; c < 3; ++c) ck_assert(isfinite(cell[c]) && cell[c] >= 0);
                if (wi[2] < ELEV_MIN_Z || wo[2] < ELEV_MIN_Z) continue;
                model(NULL, wi, wo, want);
                double e = 0;
                for (int c = 0; c < 3; ++c) e = fmax(e, fabs(cell[c] - want[c]) / want[c]);
                rel[n++] = e;
            }
    qsort(rel, n, sizeof *rel, cmp_double);
    double median = rel[n / 2], p99 = rel[n * 99 / 100], worst = rel[n - 1];
    printf("rgl round trip %s: %zu cells, relative error median %.2e, 99%% %.2e, max %.2e\n", name,
           n, median, p99, worst);
    ck_assert_msg(median <= median_max && p99 <= p99_max && worst <= worst_max,
                  "%s: median %g, 99%% %g, max %g", name, median, p99, worst);
    free(rel);
    measured_table_free(&t);
}

/* Measured: lambert median 1.9e-3, 99% 3.3e-2, max 8.2e-2; ggx 5.0e-4, 1.3e-2, 6.8e-2. */
START_TEST(round_trip_lambert) { round_trip("lambert", rgl_model_lambert, 4e-3, 5e-2, 0.12); }
END_TEST

START_TEST(round_trip_ggx) { round_trip("ggx", rgl_model_ggx, 2e-3, 3e-2, 0.1); }
END_TEST

int main(void)
{
    Suite *s = suite_create("rgl");
    TCase *tc = tcase_create("core");
    tcase_add_checked_fixture(tc, setup, teardown);
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, good_file_parses);
    tcase_add_test(tc, truncated);
    tcase_add_test(tc, bad_magic_and_version);
    tcase_add_test(tc, wrong_dtype);
    tcase_add_test(tc, shape_size_mismatch);
    tcase_add_test(tc, huge_sizes);
    tcase_add_test(tc, nan_inf_negative);
    tcase_add_test(tc, missing_and_foreign_fields);
    tcase_add_test(tc, not_regular_files);
    tcase_add_test(tc, writer_refuses);
    tcase_add_test(tc, round_trip_lambert);
    tcase_add_test(tc, round_trip_ggx);
    suite_add_tcase(s, tc);
    return tu_run(s);
}
