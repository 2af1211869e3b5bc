/* cmd_calibrate.c - `abrdf calibrate`: measure ns/eval of every model on this machine and
 * write a cost file (cost_file.h) that `abrdf advise --costs` and `abrdf tables 4 --costs` read. */
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "cost_file.h"
#include "measure.h"
#include "out_file.h"

static int usage(void)
{
    printf("usage: abrdf calibrate [-o FILE] [--reps N] [--pairs N] [--quick]\n\n"
           "Measures the cost of every registered model on this machine: nanoseconds per\n"
           "evaluation on the float batch path (abrdf_eval_batch), N random front-facing\n"
           "direction pairs in structure-of-arrays form, warm cache, median of the repetitions.\n"
           "A bare powf Blinn-Phong loop is measured in the same run as the unit of the ratios,\n"
           "and the core's clock (the cycle counter where the kernel exposes it, else a chain\n"
           "of dependent additions), which states each cost in cycles too.\n"
           "Writes the cost file to FILE (default: standard output), whole or not at all; its\n"
           "format is described in the file's header.\n"
           "  --reps N    timed repetitions (default 7)\n"
           "  --pairs N   direction pairs per batch (default 4096)\n"
           "  --quick     3 repetitions of 5 ms instead of 7 of 20 ms\n");
    return 0;
}

static void progress(const char *name) { fprintf(stderr, " %s", name); }

int cmd_calibrate(int argc, char **argv)
{
    const char *cmd = "calibrate";
    const char *out_path = NULL;
    long reps = -1, pairs = -1;
    int quick = 0;
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        if (cli_is_help(a)) return usage();
        if (!strcmp(a, "-o") || !strcmp(a, "--output")) {
            if (i + 1 >= argc) return cli_fail(cmd, "%s needs a file name", a);
            out_path = argv[++i];
        } else if (!strcmp(a, "--reps")) {
            if (i + 1 >= argc || !cli_parse_int(argv[++i], 1, 1000, &reps))
                return cli_fail(cmd, "--reps needs a whole number in [1, 1000]");
        } else if (!strcmp(a, "--pairs")) {
            if (i + 1 >= argc || !cli_parse_int(argv[++i], 16, 1 << 20, &pairs))
                return cli_fail(cmd, "--pairs needs a whole number in [16, 1048576]");
        } else if (!strcmp(a, "--quick")) {
            quick = 1;
        } else {
            return cli_fail(
                cmd, "unknown argument '%s'; options: -o FILE --reps N --pairs N --quick", a);
        }
    }
    measure_opts mo;
    measure_defaults(&mo, quick);
    if (reps > 0) mo.reps = (int)reps;
    if (pairs > 0) mo.pairs = (size_t)pairs;

    /* The output exists (as a temporary file) before the measurement: a directory that is
     * missing or read-only fails now. */
    FILE *out = stdout;
    out_file o = OUT_FILE_INIT;
    out_file *const files[1] = {&o};
    char err[1024];
    if (out_path) {
        if (out_file_open(&o, out_path, err, sizeof err)) {
            fprintf(stderr, "abrdf %s: %s\n", cmd, err);
            return 1;
        }
        out = o.f;
    }
    char command[512] = "abrdf";
    for (int i = 0; i < argc; ++i)
        if (strlen(command) + strlen(argv[i]) + 2 < sizeof command)
            strcat(strcat(command, " "), argv[i]);
    char how[256];
    snprintf(how, sizeof how,
             "float batch path, %zu random front-facing pairs (SoA, warm cache), "
             "median of %d repetitions of %.0f ms, default parameters",
             mo.pairs, mo.reps, 1e3 * mo.rep_seconds);

    abrdf_costs costs;
    double unit_ns;
    fprintf(stderr, "abrdf calibrate: timing");
    int rc = measure_models(&mo, NULL, 0, &costs, &unit_ns, progress);
    fprintf(stderr, "\n");
    if (rc != 0) {
        fprintf(stderr, "abrdf %s: out of memory\n", cmd);
        out_file_discard(&o);
        return 1;
    }
    clock_rate clock;
    clock_rate_measure(&clock);
    costs_write(out, &costs, unit_ns, command, how, &clock);
    if (out_path) {
        rc = out_file_close(&o, err, sizeof err) || out_file_commit(files, 1, err, sizeof err);
        out_file_discard(&o);
        if (rc) {
            fprintf(stderr, "abrdf %s: %s\n", cmd, err);
            return 1;
        }
        fprintf(stderr, "abrdf calibrate: wrote %s\n", out_path);
    }
    return 0;
}
