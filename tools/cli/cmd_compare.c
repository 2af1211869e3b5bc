/* cmd_compare.c - `abrdf compare REF TEST [--json] [--diff heat.png] [--fail NMSE]`: the
 * paper's NMSE of TEST against the reference REF, PSNR, maximum error, the Table-8 class,
 * a false-colour difference map; exit status 0 pass, 1 fail, 2 usage or error (as idiff). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "image_io.h"
#include "metrics.h"
#include "out_file.h"

static int usage(void)
{
    printf("usage: abrdf compare REFERENCE TEST [--json] [--diff HEAT.png] [--fail NMSE]\n\n"
           "Compares TEST with REFERENCE (the first image is the reference) over every pixel\n"
           "and the R, G, B channels, in scene-linear values (8-bit sRGB files are decoded):\n"
           "  NMSE  = sum (TEST - REF)^2 / sum REF^2   (Zavalniuk & Romanyuk 2024, Sec. 4)\n"
           "  PSNR  = 10 log10(peak^2 / MSE) dB, peak = the largest value in either image (as "
           "idiff),\n"
           "  max |TEST - REF| and its pixel (x from the left, y from the top),\n"
           "  class = Table 8: none < 1e-4 <= slight < 2.5e-4 <= noticeable < 1e-3 <= significant\n"
           "--diff writes max-over-channels |TEST - REF| per pixel as a false-colour map\n"
           "(inferno, black = 0, yellow = the maximum error), whole or not at all; it must not\n"
           "be one of the two images.\n"
           "--fail sets the NMSE threshold: PASS if NMSE < threshold (default 1e-4, 'no visible\n"
           "difference'). Exit status: 0 pass, 1 fail, 2 usage or file error, different size or\n"
           "channel count, or NMSE undefined (all-black reference).\n");
    return 0;
}

static void json_number(FILE *f, const char *key, double v)
{
    fprintf(f, "  \"%s\": ", key);
    if (isfinite(v))
        fprintf(f, "%.17g,\n", v);
    else
        fprintf(f, "null,\n");
}

static int write_diff(const char *cmd, const char *path, const abrdf_image *a, const abrdf_image *b,
                      double vmax)
{
    size_t n = (size_t)a->width * (size_t)a->height;
    float *v = malloc(n * sizeof *v);
    if (!v) return cli_fail(cmd, "out of memory");
    for (size_t p = 0; p < n; ++p) {
        float m = 0;
        for (int c = 0; c < 3; ++c)
            m = fmaxf(m, fabsf(b->pixels[3 * p + c] - a->pixels[3 * p + c]));
        v[p] = m;
    }
    char err[1024];
    abrdf_bytes bytes;
    out_file o = OUT_FILE_INIT;
    out_file *const files[1] = {&o};
    int rc = abrdf_image_encode_heatmap(path, a->width, a->height, v, vmax, "inferno", &bytes, err,
                                        sizeof err);
    free(v);
    if (rc) return cli_fail(cmd, "--diff %s", err);
    if (!(rc = out_file_open(&o, path, err, sizeof err))) {
        out_file_write(&o, bytes.data, bytes.size);
        rc = out_file_close(&o, err, sizeof err) || out_file_commit(files, 1, err, sizeof err);
    }
    abrdf_bytes_free(&bytes);
    out_file_discard(&o);
    if (rc) return cli_fail(cmd, "--diff %s", err);
    return 0;
}

/* The comparison as JSON: the images, every metric, the class and the verdict. */
static void print_json(const char *const files[2], const abrdf_image *ref, const abrdf_metrics *m,
                       double threshold, int pass)
{
    const char *cls = m->nmse_defined ? abrdf_nmse_class(m->nmse) : "undefined";
    printf("{\n  \"reference\": ");
    cli_json_string(stdout, files[0]);
    printf(",\n  \"test\": ");
    cli_json_string(stdout, files[1]);
    printf(",\n  \"width\": %d,\n  \"height\": %d,\n  \"channels\": %d,\n", ref->width, ref->height,
           ref->channels);
    json_number(stdout, "nmse", m->nmse_defined ? m->nmse : NAN);
    json_number(stdout, "sse", m->sse);
    json_number(stdout, "reference_energy", m->ref_energy);
    json_number(stdout, "mse", m->mse);
    json_number(stdout, "peak", m->peak);
    json_number(stdout, "psnr", m->psnr);
    json_number(stdout, "max_abs_error", m->max_abs);
    printf("  \"max_pixel\": [%d, %d],\n  \"max_channel\": \"%c\",\n", m->max_x, m->max_y,
           "RGB"[m->max_c]);
    printf("  \"class\": \"%s\",\n", cls);
    json_number(stdout, "threshold", threshold);
    printf("  \"pass\": %s\n}\n", pass ? "true" : "false");
}

/* The comparison for people: NMSE with its Table-8 class, PSNR, the largest error, the
 * verdict. */
static void print_human(const char *const files[2], const abrdf_image *ref, const abrdf_metrics *m,
                        const char *diff, double threshold, int pass)
{
    printf("reference  %s (%dx%d, %d channels)\n", files[0], ref->width, ref->height,
           ref->channels);
    printf("test       %s\n", files[1]);
    if (m->nmse_defined)
        printf("NMSE       %.6e  (%s, Table 8)\n", m->nmse, abrdf_nmse_class_description(m->nmse));
    else
        printf("NMSE       undefined: the reference %s is all black (sum of squares 0)\n",
               files[0]);
    if (isfinite(m->psnr))
        printf("PSNR       %.3f dB (peak %g)\n", m->psnr, m->peak);
    else
        printf("PSNR       %s\n", m->psnr > 0 ? "inf (identical)" : "-inf (no positive value)");
    printf("max error  %.6e at pixel (%d, %d) channel %c\n", m->max_abs, m->max_x, m->max_y,
           "RGB"[m->max_c]);
    if (diff) printf("diff map   %s (0 .. %.6e)\n", diff, m->max_abs);
    if (!m->nmse_defined)
        printf("result     UNDEFINED\n");
    else
        printf("result     %s (NMSE %s %g)\n", pass ? "PASS" : "FAIL",
               pass ? "<" : ">=", threshold);
}

int cmd_compare(int argc, char **argv)
{
    const char *cmd = "compare";
    const char *files[2] = {NULL, NULL}, *diff = NULL;
    int nfiles = 0, json = 0;
    double threshold = ABRDF_NMSE_SLIGHT;
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        if (cli_is_help(a)) return usage();
        int has_val = i + 1 < argc;
        if (!strcmp(a, "--json"))
            json = 1;
        else if (!strcmp(a, "--diff")) {
            if (!has_val) return cli_fail(cmd, "--diff needs an output file (e.g. heat.png)");
            diff = argv[++i];
        } else if (!strcmp(a, "--fail")) {
            if (!has_val || !cli_parse_double(argv[i + 1], &threshold) || threshold <= 0)
                return cli_fail(cmd, "--fail needs a positive NMSE threshold (e.g. 1e-4)");
            ++i;
        } else if (a[0] == '-' && a[1]) {
            return cli_fail(cmd, "unknown option '%s'; options: --json --diff --fail", a);
        } else if (nfiles < 2) {
            files[nfiles++] = a;
        } else {
            return cli_fail(cmd, "unexpected argument '%s' (two images: REFERENCE TEST)", a);
        }
    }
    if (nfiles != 2)
        return cli_fail(cmd, "needs two images: REFERENCE TEST (see abrdf compare --help)");

    char err[1024];
    if (diff) {
        const char *roles[2] = {"reference image", "test image"}, *out_role = "--diff image";
        if (out_files_distinct(&diff, &out_role, 1, files, roles, 2, err, sizeof err))
            return cli_fail(cmd, "%s", err);
        if (abrdf_image_check_output(diff, 0, err, sizeof err))
            return cli_fail(cmd, "--diff %s", err);
    }
    abrdf_image ref, test;
    if (abrdf_image_read(files[0], &ref, err, sizeof err)) return cli_fail(cmd, "%s", err);
    if (abrdf_image_read(files[1], &test, err, sizeof err)) {
        abrdf_image_free(&ref);
        return cli_fail(cmd, "%s", err);
    }
    int rc = 0;
    if (ref.width != test.width || ref.height != test.height || ref.channels != test.channels) {
        rc = cli_fail(cmd,
                      "images differ in size or channels: %s is %dx%d with %d channels, %s is "
                      "%dx%d with %d channels",
                      files[0], ref.width, ref.height, ref.channels, files[1], test.width,
                      test.height, test.channels);
        goto done;
    }
    abrdf_metrics m;
    int mr = abrdf_metrics_compute(test.pixels, ref.pixels, ref.width, ref.height, 3, &m);
    if (mr == ABRDF_METRICS_NONFINITE) {
        const float *bad = ref.pixels + 3 * ((size_t)m.max_y * ref.width + m.max_x) + m.max_c;
        rc = cli_fail(cmd, "%s has a NaN or infinite value at pixel (%d, %d) channel %c",
                      isfinite(*bad) ? files[1] : files[0], m.max_x, m.max_y, "RGB"[m.max_c]);
        goto done;
    }
    if (mr != ABRDF_METRICS_OK) {
        rc = cli_fail(cmd, "cannot compare these images");
        goto done;
    }
    if (diff && (rc = write_diff(cmd, diff, &ref, &test, m.max_abs))) goto done;

    int pass = m.nmse_defined && m.nmse < threshold;
    if (json)
        print_json(files, &ref, &m, threshold, pass);
    else
        print_human(files, &ref, &m, diff, threshold, pass);
    if (!m.nmse_defined) {
        fprintf(stderr, "abrdf compare: NMSE is undefined because the reference %s is all black\n",
                files[0]);
        rc = CLI_EXIT_USAGE;
    } else {
        rc = pass ? 0 : 1;
    }
done:
    abrdf_image_free(&ref);
    abrdf_image_free(&test);
    return rc;
}
