/* cmd_tables.c - `abrdf tables N`: the paper's tables recomputed, beside the published ones. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"
#include "tables.h"

static const table_gen generators[] = {
    {"2", "maximum relative error (%) of the Table-1 approximations in the highlight zone",
     tables_error},
    {"3", "maximum absolute error of the Table-1 approximations", tables_error},
    {"4", "cost: the paper's Zen 4 cycles beside ns/eval measured on this machine", tables_cost},
    {"6", "image experiment: min NMSE over n of f_phe, f_be, f_2e, f_16e vs Disney GGX (robot)",
     tables_images},
    {"7", "image experiment: min NMSE over n of f_ge, f_ctphe, f_ct2e, f_ct16e vs Disney GGX",
     tables_images},
    {"gltf", "not the paper's: the glTF mapping's error (docs/GLTF.md, \"The mapping\")",
     tables_gltf},
};
#define GEN_COUNT (sizeof generators / sizeof generators[0])

static int usage(void)
{
    printf("usage: abrdf tables N [--csv | --markdown] [--paper FILE] [--costs FILE] [--reps N]\n\n"
           "Recomputes table N of Zavalniuk & Romanyuk 2024 and prints it beside the published\n"
           "values (data/paper_tables.csv) with the difference and, for Tables 2-3, the mean\n"
           "absolute deviation per model. Markdown by default.\n"
           "  --paper FILE   published values from FILE instead of the installed data file\n"
           "  --costs FILE   Table 4: ns/eval from a cost file (abrdf calibrate -o FILE)\n"
           "                 instead of measuring now\n"
           "  --reps N       Table 4: repetitions when measuring now (default 3, quick)\n"
           "Tables 6-7 (rendered; docs/TABLES.md, \"Tables 6 and 7\"):\n"
           "  --width W --height H   image size (default 128 x 128)\n"
           "  --spp N        samples per pixel, a square (default 1: pixel centres)\n"
           "  --threads N    render threads (default: online CPUs)\n"
           "  --f0 V         Fresnel F0 of the reference and the Fresnel lobes (default 0.04)\n"
           "  --kd V         Lambert albedo under the specular (default 0.5; 0: specular only)\n"
           "  --scene FILE   render another scene than the built-in robot\n\n"
           "tables:\n");
    for (size_t i = 0; i < GEN_COUNT; ++i)
        printf("  %-3s %s\n", generators[i].id, generators[i].summary);
    return 0;
}

int cmd_tables(int argc, char **argv)
{
    const char *cmd = "tables";
    const char *id = NULL, *paper_path = NULL;
    tables_opts o = {0, NULL, 3, {0}};
    paper_images_defaults(&o.images);
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        long v;
        if (cli_is_help(a)) return usage();
        if (!strcmp(a, "--csv"))
            o.csv = 1;
        else if (!strcmp(a, "--markdown"))
            o.csv = 0;
        else if (!strcmp(a, "--paper")) {
            if (i + 1 >= argc) return cli_fail(cmd, "--paper needs a file");
            paper_path = argv[++i];
        } else if (!strcmp(a, "--costs")) {
            if (i + 1 >= argc)
                return cli_fail(cmd, "--costs needs a cost file (abrdf calibrate -o FILE)");
            o.costs_path = argv[++i];
        } else if (!strcmp(a, "--reps")) {
            if (i + 1 >= argc || !cli_parse_int(argv[++i], 1, 1000, &v))
                return cli_fail(cmd, "--reps needs a whole number in [1, 1000]");
            o.reps = (int)v;
        } else if (!strcmp(a, "--width") || !strcmp(a, "--height") || !strcmp(a, "--spp") ||
                   !strcmp(a, "--threads")) {
            long hi = a[2] == 's' ? 4096 : a[2] == 't' ? 64 : 16384;
            if (i + 1 >= argc || !cli_parse_int(argv[++i], 1, hi, &v))
                return cli_fail(cmd, "%s needs a whole number in [1, %ld]", a, hi);
            if (a[2] == 'w')
                o.images.width = (int)v;
            else if (a[2] == 'h')
                o.images.height = (int)v;
            else if (a[2] == 't')
                o.images.threads = (int)v;
            else
                o.images.spp = (int)v;
            long k = lround(sqrt((double)v));
            if (a[2] == 's' && k * k != v)
                return cli_fail(cmd, "--spp %ld is not a square (1, 4, 9, 16, ...)", v);
        } else if (!strcmp(a, "--f0") || !strcmp(a, "--kd")) {
            double d;
            if (i + 1 >= argc || !cli_parse_double(argv[++i], &d) || d < 0 || d > 1)
                return cli_fail(cmd, "%s needs a value in [0, 1]", a);
            if (a[2] == 'f')
                o.images.f0 = d;
            else
                o.images.kd = d;
        } else if (!strcmp(a, "--scene")) {
            if (i + 1 >= argc) return cli_fail(cmd, "--scene needs a scene file");
            o.images.scene_path = argv[++i];
        } else if (a[0] == '-' && a[1]) {
            return cli_fail(cmd,
                            "unknown option '%s'; options: --csv --markdown --paper --costs --reps "
                            "--width --height --spp --threads --f0 --kd --scene",
                            a);
        } else if (!id) {
            id = a;
        } else {
            return cli_fail(cmd, "unexpected argument '%s' (one table at a time)", a);
        }
    }
    char ids[64] = "";
    for (size_t i = 0; i < GEN_COUNT; ++i) strcat(strcat(ids, i ? ", " : ""), generators[i].id);
    if (!id) return cli_fail(cmd, "which table? available: %s", ids);
    const table_gen *gen = NULL;
    for (size_t i = 0; i < GEN_COUNT; ++i)
        if (!strcmp(id, generators[i].id)) gen = &generators[i];
    if (!gen) return cli_fail(cmd, "no table '%s'; available: %s", id, ids);

    o.images.progress = isatty(2);
    paper_data paper;
    char err[1200];
    if (paper_data_load(paper_path, &paper, err, sizeof err) != 0) {
        fprintf(stderr, "abrdf %s: %s\n", cmd, err);
        return 1;
    }
    int rc = gen->run(gen, &o, &paper);
    paper_data_free(&paper);
    return rc;
}
