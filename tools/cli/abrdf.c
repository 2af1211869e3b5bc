/* abrdf.c - the `abrdf` command: dispatch to subcommands. Exit status: 0 success, 1 a bad
 * scene, input file or failed output, 2 bad arguments (README.md, "Exit status"); a failed
 * write to standard output turns 0 into 1. */
#include <signal.h>
#include <string.h>

#include "cli.h"
#include "out_file.h"

static const cli_command commands[] = {
    {"models", "list every model with its formula, parameters and needs", cmd_models},
    {"eval", "evaluate a model's f_r for one direction pair", cmd_eval},
    {"sample", "draw light directions by a model's importance sampler: wi, pdf, weight",
     cmd_sample},
    {"export",
     "write a scene for another renderer (--pov: POV-Ray 3.7 SDL; --cycles: Blender/Cycles with "
     "OSL)",
     cmd_export},
    {"render",
     "render a scene (docs/RENDERER.md) to EXR + PNG preview with the built-in ray tracer",
     cmd_render},
    {"slice", "f_r and f_r*cos over the outgoing angle in the plane of incidence (CSV)", cmd_slice},
    {"compare", "NMSE (the paper's metric), PSNR, max error and Table-8 class of two images",
     cmd_compare},
    {"tables",
     "the paper's Tables 2, 3, 4, 6, 7 recomputed, beside the published values; gltf: the glTF "
     "mapping's error",
     cmd_tables},
    {"calibrate", "measure ns/eval of every model on this machine; write a cost file",
     cmd_calibrate},
    {"bench", "what accuracy costs in time: cost ratios, image errors, Pareto plot; --render",
     cmd_bench},
    {"advise", "choose the models for a material by the paper's flowchart, and say why",
     cmd_advise},
    {"fit", "fit one model's parameters to another's; errors and the predicted image NMSE",
     cmd_fit},
    {"tabulate", "write a model's f_r on the measured grid as a MERL BRDF file (noise, holes)",
     cmd_tabulate},
    {"inspect", "what a measured BRDF file holds: grid, cells not measured, max f_r, albedo",
     cmd_inspect},
    {"explore", "serve the browser explorer: lobes, lit spheres, two models compared, advice",
     cmd_explore},
};
#define COMMAND_COUNT (sizeof commands / sizeof commands[0])

static void usage(FILE *f)
{
    fprintf(f,
            "abrdf %s - adaptive selection of surface reflectance models\n\n"
            "usage: abrdf COMMAND [options]   (abrdf COMMAND --help for its options)\n\n"
            "commands:\n",
            abrdf_version());
    for (size_t i = 0; i < COMMAND_COUNT; ++i)
        fprintf(f, "  %-10s %s\n", commands[i].name, commands[i].summary);
}

static int dispatch(int argc, char **argv)
{
    if (argc < 2) {
        usage(stderr);
        return CLI_EXIT_USAGE;
    }
    if (cli_is_help(argv[1])) {
        usage(stdout);
        return 0;
    }
    if (!strcmp(argv[1], "--version")) {
        printf("abrdf %s\n", abrdf_version());
        return 0;
    }
    for (size_t i = 0; i < COMMAND_COUNT; ++i)
        if (!strcmp(argv[1], commands[i].name)) {
            static const char *const repeatable[] = {"--set", "--materials", NULL};
            const char *twice = cli_repeated_option(argc - 1, argv + 1, repeatable);
            if (twice)
                return cli_fail(argv[1],
                                "%s is given twice (only --set and --materials repeat, --set "
                                "once per name; the last would silently win)",
                                twice);
            return commands[i].run(argc - 1, argv + 1);
        }
    char names[512] = "", near[256] = "";
    for (size_t i = 0; i < COMMAND_COUNT; ++i) {
        size_t len = strlen(commands[i].name) + 3;
        if (strlen(names) + len < sizeof names)
            strcat(strcat(names, i ? ", " : ""), commands[i].name);
        if (cli_is_near(argv[1], commands[i].name) && strlen(near) + len < sizeof near)
            strcat(strcat(near, *near ? ", " : ""), commands[i].name);
    }
    if (*near)
        fprintf(stderr, "abrdf: unknown command '%s'; did you mean %s? commands: %s\n", argv[1],
                near, names);
    else
        fprintf(stderr, "abrdf: unknown command '%s'; commands: %s\n", argv[1], names);
    return CLI_EXIT_USAGE;
}

#if defined(__SANITIZE_ADDRESS__)
/* The sanitizer build's defaults for this program (ASAN_OPTIONS adds to them): OpenImageIO
 * 2.4's TextureSystem::destroy deletes through a base-class pointer, which AddressSanitizer
 * reports as a new/delete size mismatch inside the library. */
const char *__asan_default_options(void);
const char *__asan_default_options(void) { return "new_delete_type_mismatch=0"; }
#endif

int main(int argc, char **argv)
{
    /* A file-size limit (ulimit -f) makes a write fail with EFBIG, reported like a full disk,
     * instead of killing the process with a half-written file. */
    signal(SIGXFSZ, SIG_IGN);
    int rc = dispatch(argc, argv);
    char who[64] = "abrdf";
    for (size_t i = 0; argc > 1 && i < COMMAND_COUNT; ++i)
        if (!strcmp(argv[1], commands[i].name)) snprintf(who, sizeof who, "abrdf %s", argv[1]);
    if (out_stdout_check(who) && rc == 0) rc = 1;
    return rc;
}
