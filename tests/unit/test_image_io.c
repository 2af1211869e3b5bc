/* test_image_io.c - image files through OpenImageIO/OpenColorIO: float EXR round trip,
 * sRGB preview encoding, grey/alpha handling, the checks made before any work, and errors
 * that name the file. Encoded bytes reach disk through out_file.h, as in the tools. */
#define _POSIX_C_SOURCE 200809L /* mkdtemp */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "image_io.h"
#include "out_file.h"
#include "test_util.h"

static char tmpdir[256];

static const char *tmp_path(const char *name)
{
    static char buf[4][512];
    static int k;
    k = (k + 1) % 4;
    snprintf(buf[k], sizeof buf[k], "%s/%s", tmpdir, name);
    return buf[k];
}

/* The file of an encoder's bytes, as the tools write it; frees the bytes. */
static void save(const char *path, abrdf_bytes *b)
{
    char err[512];
    out_file o = OUT_FILE_INIT;
    out_file *const files[1] = {&o};
    ck_assert_msg(out_file_open(&o, path, err, sizeof err) == 0, "%s", err);
    out_file_write(&o, b->data, b->size);
    ck_assert_msg(out_file_close(&o, err, sizeof err) == 0, "%s", err);
    ck_assert_msg(out_file_commit(files, 1, err, sizeof err) == 0, "%s", err);
    out_file_discard(&o);
    abrdf_bytes_free(b);
    ck_assert_ptr_null(b->data);
}

static int write_linear(const char *path, int w, int h, const float *p, char *err, int size)
{
    abrdf_bytes b;
    if (abrdf_image_encode_linear(path, w, h, p, &b, err, size)) {
        ck_assert_ptr_null(b.data);
        return -1;
    }
    save(path, &b);
    return 0;
}

static int write_preview(const char *path, int w, int h, const float *p, const char *config,
                         const char *display, const char *view, char *err, int size)
{
    abrdf_bytes b;
    if (abrdf_image_encode_preview(path, w, h, p, config, display, view, &b, err, size)) {
        ck_assert_ptr_null(b.data);
        return -1;
    }
    save(path, &b);
    return 0;
}

static float *ramp(int w, int h)
{
    float *p = malloc((size_t)w * h * 3 * sizeof *p);
    for (int i = 0; i < w * h * 3; ++i)
        p[i] = (float)(0.001 + 7.3 * sin(0.37 * i) * sin(0.37 * i)) / (float)(1 + i % 5);
    return p;
}

START_TEST(exr_round_trip_is_exact)
{
    int w = 17, h = 9;
    float *p = ramp(w, h);
    char err[512];
    const char *path = tmp_path("rt.exr");
    ck_assert_int_eq(write_linear(path, w, h, p, err, sizeof err), 0);
    abrdf_image img;
    ck_assert_msg(abrdf_image_read(path, &img, err, sizeof err) == 0, "%s", err);
    ck_assert_int_eq(img.width, w);
    ck_assert_int_eq(img.height, h);
    ck_assert_int_eq(img.channels, 3);
    for (int i = 0; i < w * h * 3; ++i) ck_assert_float_eq(img.pixels[i], p[i]);
    abrdf_image_free(&img);
    ck_assert_ptr_null(img.pixels);
    free(p);
}
END_TEST

/* Half floats: values that are halves come back exactly (the file is an EXR of half
 * channels, half the bytes of float32), others rounded to the nearest half; a name that is
 * not .exr is refused, naming the file. */
START_TEST(exr_half_round_trip)
{
    int w = 17, h = 9;
    float *p = ramp(w, h);
    for (int i = 0; i < w * h * 3; i += 2) { /* every other value a half: 11 significant bits */
        int e;
        float m = frexpf(p[i], &e);
        p[i] = ldexpf(roundf(ldexpf(m, 11)), e - 11);
    }
    char err[512];
    abrdf_bytes b, f;
    const char *path = tmp_path("half.exr");
    ck_assert_msg(abrdf_image_encode_linear_half(path, w, h, p, &b, err, sizeof err) == 0, "%s",
                  err);
    ck_assert_msg(abrdf_image_encode_linear(path, w, h, p, &f, err, sizeof err) == 0, "%s", err);
    ck_assert_uint_lt(b.size, f.size);
    abrdf_bytes_free(&f);
    save(path, &b);
    abrdf_image img;
    ck_assert_msg(abrdf_image_read(path, &img, err, sizeof err) == 0, "%s", err);
    ck_assert_int_eq(img.width, w);
    ck_assert_int_eq(img.height, h);
    for (int i = 0; i < w * h * 3; ++i)
        if (i % 2 == 0)
            ck_assert_float_eq(img.pixels[i], p[i]);
        else
            ck_assert(fabsf(img.pixels[i] - p[i]) <= ldexpf(fabsf(p[i]), -11));
    abrdf_image_free(&img);
    const char *tif = tmp_path("half.tif");
    ck_assert_int_eq(abrdf_image_encode_linear_half(tif, w, h, p, &b, err, sizeof err), -1);
    ck_assert_ptr_null(b.data);
    ck_assert_msg(strstr(err, "half.tif") && strstr(err, ".exr only"), "%s", err);
    free(p);
}
END_TEST

START_TEST(hdr_round_trip_is_close)
{
    int w = 8, h = 4;
    float *p = ramp(w, h);
    char err[512];
    const char *path = tmp_path("rt.hdr");
    ck_assert_msg(write_linear(path, w, h, p, err, sizeof err) == 0, "%s", err);
    abrdf_image img;
    ck_assert_msg(abrdf_image_read(path, &img, err, sizeof err) == 0, "%s", err);
    /* RGBE: 8-bit mantissa shared by the pixel's largest channel. */
    for (int i = 0; i < w * h; ++i) {
        float mx = fmaxf(p[3 * i], fmaxf(p[3 * i + 1], p[3 * i + 2]));
        for (int c = 0; c < 3; ++c)
            ck_assert(fabsf(img.pixels[3 * i + c] - p[3 * i + c]) <= mx / 64);
    }
    abrdf_image_free(&img);
    free(p);
}
END_TEST

START_TEST(preview_is_srgb_encoded)
{
    /* Scene-linear 0.18 (mid grey) -> sRGB 0.4613 -> 8-bit 118; 1.0 -> 255; 4.0 clips. */
    float px[4 * 3] = {0.18f, 0.18f, 0.18f, 1, 1, 1, 0, 0, 0, 4, 4, 4};
    char err[512];
    const char *png = tmp_path("grey.png");
    ck_assert_msg(write_preview(png, 2, 2, px, NULL, NULL, NULL, err, sizeof err) == 0, "%s", err);
    /* Reading decodes sRGB back to linear: 0.18 must come back as exactly code 118's value
     * (codes 117 and 119 decode to 0.1779 and 0.1845). */
    abrdf_image img;
    ck_assert_msg(abrdf_image_read(png, &img, err, sizeof err) == 0, "%s", err);
    double code118 = pow((118 / 255.0 + 0.055) / 1.055, 2.4);
    for (int c = 0; c < 3; ++c) {
        ck_assert_msg(fabs(img.pixels[c] - code118) < 2e-5, "grey decoded to %g, want %g",
                      img.pixels[c], code118);
        ck_assert(fabs(img.pixels[3 + c] - 1) < 1e-5);
        ck_assert(fabs(img.pixels[6 + c]) < 1e-6);
        ck_assert(fabs(img.pixels[9 + c] - 1) < 1e-5);
    }
    abrdf_image_free(&img);
}
END_TEST

START_TEST(preview_rejects_unknown_view)
{
    float px[3] = {0.5f, 0.5f, 0.5f};
    char err[512] = "";
    ck_assert_int_eq(
        write_preview(tmp_path("v.png"), 1, 1, px, NULL, NULL, "NoSuchView", err, sizeof err), -1);
    ck_assert_ptr_nonnull(strstr(err, "NoSuchView"));
    ck_assert_int_eq(write_preview(tmp_path("v.png"), 1, 1, px, "no-such-config.ocio", NULL, NULL,
                                   err, sizeof err),
                     -1);
}
END_TEST

START_TEST(errors_name_the_file)
{
    char err[512] = "";
    abrdf_image img;
    ck_assert_int_eq(abrdf_image_read(tmp_path("missing.exr"), &img, err, sizeof err), -1);
    ck_assert_ptr_nonnull(strstr(err, "missing.exr"));
    ck_assert_ptr_null(img.pixels);
    float px[3] = {1, 2, 3};
    ck_assert_int_eq(write_linear(tmp_path("lin.png"), 1, 1, px, err, sizeof err), -1);
    ck_assert_ptr_nonnull(strstr(err, "lin.png"));
    ck_assert_int_eq(write_linear(tmp_path("zero.exr"), 0, 1, px, err, sizeof err), -1);
    ck_assert_int_eq(write_linear(tmp_path("x.unknownext"), 1, 1, px, err, sizeof err), -1);
    FILE *f = fopen(tmp_path("garbage.exr"), "wb");
    fputs("not an image", f);
    fclose(f);
    ck_assert_int_eq(abrdf_image_read(tmp_path("garbage.exr"), &img, err, sizeof err), -1);
}
END_TEST

START_TEST(heatmap_is_written)
{
    float v[6] = {0, 0.2f, 0.4f, 0.6f, 0.8f, 1};
    char err[512];
    const char *png = tmp_path("heat.png");
    abrdf_bytes b;
    ck_assert_msg(abrdf_image_encode_heatmap(png, 3, 2, v, 1.0, NULL, &b, err, sizeof err) == 0,
                  "%s", err);
    save(png, &b);
    abrdf_image img;
    ck_assert_msg(abrdf_image_read(png, &img, err, sizeof err) == 0, "%s", err);
    ck_assert_int_eq(img.width, 3);
    ck_assert_int_eq(img.channels, 3);
    /* inferno: 0 is near black, 1 is a bright yellow (red and green high, blue lower). */
    ck_assert(img.pixels[0] + img.pixels[1] + img.pixels[2] < 0.01);
    ck_assert(img.pixels[15] > 0.7 && img.pixels[16] > 0.7 && img.pixels[17] < img.pixels[16]);
    abrdf_image_free(&img);
}
END_TEST

/* What the tools check before their work: names they cannot write, transforms they cannot
 * build. Nothing is written by a check. */
START_TEST(checks_before_the_work)
{
    char err[512] = "";
    ck_assert_int_eq(abrdf_image_check_output(tmp_path("a.exr"), 1, err, sizeof err), 0);
    ck_assert_int_eq(abrdf_image_check_output(tmp_path("a.hdr"), 1, err, sizeof err), 0);
    ck_assert_int_eq(abrdf_image_check_output(tmp_path("a.png"), 0, err, sizeof err), 0);
    ck_assert_int_eq(abrdf_image_check_output(tmp_path("a.png"), 1, err, sizeof err), -1);
    ck_assert_ptr_nonnull(strstr(err, "scene-linear"));
    ck_assert_int_eq(abrdf_image_check_output(tmp_path("a.exr"), 0, err, sizeof err), -1);
    ck_assert_int_eq(abrdf_image_check_output(tmp_path("h.xyz"), 0, err, sizeof err), -1);
    /* The reason, not just the name (OpenImageIO's own message for an unknown extension). */
    ck_assert_msg(strlen(strstr(err, "h.xyz: ")) > strlen("h.xyz: ") + 10, "%s", err);
    /* SGI has no in-memory writer: its writes could not be checked, so it is refused. */
    ck_assert_int_eq(abrdf_image_check_output(tmp_path("a.sgi"), 1, err, sizeof err), -1);
    ck_assert_ptr_nonnull(strstr(err, "cannot encode in memory"));
    ck_assert_int_eq(abrdf_image_check_preview(NULL, NULL, NULL, err, sizeof err), 0);
    ck_assert_int_eq(abrdf_image_check_preview(NULL, "nosuch", NULL, err, sizeof err), -1);
    ck_assert_ptr_nonnull(strstr(err, "nosuch"));
    ck_assert_int_eq(abrdf_image_check_preview(NULL, NULL, "NoView", err, sizeof err), -1);
    ck_assert_int_eq(abrdf_image_check_preview(tmp_path("none.ocio"), NULL, NULL, err, sizeof err),
                     -1);
    ck_assert_int_eq(access(tmp_path("a.exr"), F_OK), -1);
}
END_TEST

/* A 4 KiB path keeps the reason of its error: the path is shortened, not the message. */
START_TEST(long_paths_keep_the_reason)
{
    char path[4200], err[256] = "";
    int n = snprintf(path, sizeof path, "%s/", tmpdir);
    while (n < 4000) n += snprintf(path + n, sizeof path - (size_t)n, "long-directory-name/");
    snprintf(path + n, sizeof path - (size_t)n, "image.exr");
    abrdf_image img;
    ck_assert_int_eq(abrdf_image_read(path, &img, err, sizeof err), -1);
    ck_assert_msg(strstr(err, "image.exr: cannot open: No such file or directory"), "%s", err);
    ck_assert_ptr_nonnull(strstr(err, "..."));
    ck_assert_int_eq(abrdf_image_read(tmpdir, &img, err, sizeof err), -1);
    ck_assert_msg(strstr(err, "is a directory"), "%s", err);
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("image_io");
    TCase *t = tcase_create("files");
    tcase_add_test(t, exr_round_trip_is_exact);
    tcase_add_test(t, exr_half_round_trip);
    tcase_add_test(t, hdr_round_trip_is_close);
    tcase_add_test(t, preview_is_srgb_encoded);
    tcase_add_test(t, preview_rejects_unknown_view);
    tcase_add_test(t, errors_name_the_file);
    tcase_add_test(t, heatmap_is_written);
    tcase_add_test(t, checks_before_the_work);
    tcase_add_test(t, long_paths_keep_the_reason);
    suite_add_tcase(s, t);
    return s;
}

int main(void)
{
    snprintf(tmpdir, sizeof tmpdir, "%s/abrdf_image_io_XXXXXX",
             getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
    if (!mkdtemp(tmpdir)) return 1;
    int rc = tu_run(suite());
    char cmd[400];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmpdir);
    if (system(cmd) != 0) rc = 1;
    return rc;
}
