/* cmd_export.c - `abrdf export --FORMAT SCENE -o OUT`: the scene for another renderer.
 * The formats are a table; each writer lives in its own file (export_*.c, export.h). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "export.h"

#ifndef ABRDF_SOURCE_OSL_DIR
#define ABRDF_SOURCE_OSL_DIR ""
#endif
#ifndef ABRDF_INSTALL_OSL_DIR
#define ABRDF_INSTALL_OSL_DIR ""
#endif

typedef struct export_format {
    const char *flag;
    const char *what;
    int (*write)(FILE *f, const render_scene *rs, const export_options *opt, char *err,
                 size_t err_size);
} export_format;

static const export_format formats[] = {
    {"--cycles", "Blender/Cycles bpy script with the OSL shaders (docs/OSL.md)", export_cycles},
};
#define FORMAT_COUNT ((int)(sizeof formats / sizeof formats[0]))

static int usage(void)
{
    printf("usage: abrdf export FORMAT SCENE -o OUT [--model NAME [--set NAME=VALUE ...]]\n"
           "                    [--width W] [--height H] [--spp N] [--mode eval|closure]\n"
           "                    [--osl-dir DIR]\n\nFORMAT:\n");
    for (int i = 0; i < FORMAT_COUNT; ++i) printf("  %-10s %s\n", formats[i].flag, formats[i].what);
    printf("\n  --model/--set     as abrdf render: every material with one model\n"
           "  --width/--height  override the scene's resolution\n"
           "  --spp N           samples per pixel of the host renderer; default 4\n"
           "  --mode            the script's default mode (--cycles); default eval\n"
           "  --osl-dir DIR     abrdf's osl/ directory the script uses; default: the source\n"
           "                    tree's when run from the build tree, else the installed one\n");
    return 0;
}

/* The osl/ directory: --osl-dir, else $ABRDF_OSL_DIR, else source tree, else installed. */
static const char *osl_dir_default(void)
{
    const char *env = getenv("ABRDF_OSL_DIR");
    if (env && *env) return env;
    char probe[4096];
    snprintf(probe, sizeof probe, "%s/abrdf.h", ABRDF_SOURCE_OSL_DIR);
    FILE *f = fopen(probe, "r");
    if (f) {
        fclose(f);
        return ABRDF_SOURCE_OSL_DIR;
    }
    return ABRDF_INSTALL_OSL_DIR;
}

int cmd_export(int argc, char **argv)
{
    const char *cmd = "export", *path = NULL, *out = NULL, *model_name = NULL;
    const char *osl_dir = NULL, *mode = "eval";
    const char *sets[64];
    int nsets = 0;
    const export_format *fmt = NULL;
    render_options ropt = {0, 0, 4, 0, 1, 0, 0};
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        const char *val = i + 1 < argc ? argv[i + 1] : NULL;
        long v;
        if (cli_is_help(a)) return usage();
        int is_format = 0;
        for (int k = 0; k < FORMAT_COUNT; ++k)
            if (!strcmp(a, formats[k].flag)) {
                if (fmt && fmt != &formats[k]) return cli_fail(cmd, "one format at a time");
                fmt = &formats[k];
                is_format = 1;
            }
        if (is_format) continue;
        if (!strcmp(a, "-o") || !strcmp(a, "--model") || !strcmp(a, "--set") ||
            !strcmp(a, "--osl-dir") || !strcmp(a, "--mode")) {
            if (!val) return cli_fail(cmd, "%s needs a value", a);
            ++i;
            if (!strcmp(a, "-o")) out = val;
            else if (!strcmp(a, "--model")) model_name = val;
            else if (!strcmp(a, "--osl-dir")) osl_dir = val;
            else if (!strcmp(a, "--mode")) mode = val;
            else if (nsets == 64) return cli_fail(cmd, "too many --set options (64 at most)");
            else sets[nsets++] = val;
        } else if (!strcmp(a, "--width") || !strcmp(a, "--height") || !strcmp(a, "--spp")) {
            long hi = a[2] == 's' ? 65536 : SCENE_MAX_RESOLUTION;
            if (!cli_parse_int(val, 1, hi, &v))
                return cli_fail(cmd, "%s needs a whole number in [1, %ld]", a, hi);
            ++i;
            if (a[2] == 'w') ropt.width = (int)v;
            else if (a[2] == 'h') ropt.height = (int)v;
            else ropt.spp = (int)v;
        } else if (a[0] == '-' && a[1]) {
            return cli_fail(cmd, "unknown option '%s' (abrdf export --help)", a);
        } else if (!path) {
            path = a;
        } else {
            return cli_fail(cmd, "unexpected argument '%s' (one scene only)", a);
        }
    }
    if (!fmt) {
        char list[256] = "";
        for (int k = 0; k < FORMAT_COUNT; ++k)
            snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", k ? ", " : "",
                     formats[k].flag);
        return cli_fail(cmd, "missing FORMAT (one of: %s)", list);
    }
    if (!path) return cli_fail(cmd, "missing SCENE (abrdf export --help)");
    if (!out) return cli_fail(cmd, "missing -o OUT");
    if (nsets && !model_name) return cli_fail(cmd, "--set needs --model (the scene file sets materials' parameters)");
    if (strcmp(mode, "eval") && strcmp(mode, "closure"))
        return cli_fail(cmd, "--mode is eval or closure, not '%s'", mode);
    if (!osl_dir) osl_dir = osl_dir_default();

    scene s;
    char err[512];
    if (scene_parse_file(path, &s, err, sizeof err)) {
        fprintf(stderr, "abrdf export: %s\n", err);
        return 1;
    }
    int rc = 1, prepared = 0;
    render_scene rs;
    FILE *f = NULL;
    if (model_name) {
        abrdf_model m;
        if (cli_model(cmd, model_name, &m)) {
            rc = CLI_EXIT_USAGE;
            goto done;
        }
        if (render_set_model(&s, m, err, sizeof err)) {
            fprintf(stderr, "abrdf export: %s\n", err);
            goto done;
        }
        for (int i = 0; i < nsets; ++i)
            for (int j = 0; j < s.material_count; ++j)
                if (cli_set_param(cmd, m, &s.materials[j].params, sets[i])) {
                    rc = CLI_EXIT_USAGE;
                    goto done;
                }
    }
    if (render_prepare(&s, &ropt, &rs, err, sizeof err)) {
        fprintf(stderr, "abrdf export: %s\n", err);
        goto done;
    }
    prepared = 1;
    f = fopen(out, "w");
    if (!f) {
        fprintf(stderr, "abrdf export: cannot write %s\n", out);
        goto done;
    }
    export_options eo = {path, osl_dir, ropt.spp, mode};
    if (fmt->write(f, &rs, &eo, err, sizeof err)) {
        fprintf(stderr, "abrdf export: %s\n", err);
        goto done;
    }
    rc = 0;
done:
    if (f && fclose(f) && rc == 0) {
        fprintf(stderr, "abrdf export: cannot write %s\n", out);
        rc = 1;
    }
    if (prepared) render_release(&rs);
    scene_free(&s);
    return rc;
}
