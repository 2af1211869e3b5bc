/* cmd_export.c - `abrdf export --pov|--cycles SCENE -o OUT`: the scene for another renderer.
 * Shared here: parsing, --model/--set and the materials chosen by the selection (table=,
 * adaptive goal=/budget=, --adaptive; as abrdf render, so a budget's fitted parameters are
 * what the ports receive), render_prepare (so every exporter reads the built-in renderer's
 * own camera vectors, materials and lights). The writers live
 * in export_pov.c (POV-Ray SDL, docs/POVRAY.md) and export_cycles.c (Blender/Cycles bpy
 * script with OSL, docs/OSL.md). */
#include <stdlib.h>
#include <string.h>

#include "budget_run.h"
#include "cli.h"
#include "data_path.h"
#include "export.h"
#include "export_pov.h"
#include "scene_select.h"

#ifndef ABRDF_SOURCE_OSL_DIR
#define ABRDF_SOURCE_OSL_DIR ""
#endif
#ifndef ABRDF_INSTALL_OSL_DIR
#define ABRDF_INSTALL_OSL_DIR ""
#endif

static int usage(void)
{
    printf("usage: abrdf export --pov SCENE -o OUT.pov [--model NAME [--set NAME=VALUE ...]]\n"
           "                    [--adaptive --goal G | --adaptive --budget B] [--materials FILE]\n"
           "                    [--width W] [--height H] [--no-shadows | --native]\n"
           "       abrdf export --cycles SCENE -o OUT.py [--model NAME [--set NAME=VALUE ...]]\n"
           "                    [--adaptive --goal G | --adaptive --budget B] [--materials FILE]\n"
           "                    [--width W] [--height H] [--spp N] [--mode eval|closure|generic]\n"
           "                    [--osl-dir DIR]\n\n"
           "--pov writes SCENE (docs/SCENES.md) as POV-Ray 3.7 SDL that shades every object with\n"
           "the library's models (povray_macros/abrdf.inc, docs/POVRAY.md): same camera, lights,\n"
           "primitives and materials. Render it with +L<abrdf>/povray_macros, linear HDR (+FE).\n"
           "--cycles writes a Blender/Cycles (bpy) script for the same scene with the OSL port\n"
           "(osl/, docs/OSL.md); run it with a Python that has bpy.\n\n"
           "  --model/--set      as abrdf render: every material becomes this model\n"
           "  --adaptive --goal G | --budget B   as abrdf render: the selection chooses every\n"
           "                     material's models (a budget's choice with its fitted parameters)\n"
           "  --materials FILE   material-table file merged over data/materials.csv\n"
           "  --width/--height   override the scene's resolution\n"
           "  --no-shadows       (pov) emissive mode even with one light (no shadows); with\n"
           "                     several lights this is the only mode\n"
           "  --native           (pov) POV-Ray's own finishes instead of function pigments:\n"
           "                     lambert, phong, blinn_phong only; directional lights only;\n"
           "                     phong/blinn_phong then lack the factor N.wi (docs/POVRAY.md)\n"
           "  --spp N            (cycles) samples per pixel; default 4\n"
           "  --mode M           (cycles) the script's default mode: eval (exact, default),\n"
           "                     closure (Cycles' closures and lights), generic (abrdf_eval.osl)\n"
           "  --osl-dir DIR      (cycles) abrdf's osl/ directory the script uses; default\n"
           "                     $ABRDF_OSL_DIR, else the source tree's, else the installed one\n");
    return 0;
}

/* The osl/ directory: $ABRDF_OSL_DIR, else the source tree's, else the installed one. */
static const char *osl_dir_default(void)
{
    const char *env = getenv("ABRDF_OSL_DIR");
    if (env && *env) return env;
    char probe[4096];
    snprintf(probe, sizeof probe, "%s/abrdf_osl.h", ABRDF_SOURCE_OSL_DIR);
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
    const char *osl_dir = NULL, *mode = NULL, *goal = NULL, *budget_s = NULL;
    const char *sets[64], *mats[16];
    int nsets = 0, nmats = 0, pov = 0, cycles = 0, no_shadows = 0, native = 0, spp = 0;
    int adaptive = 0;
    render_options opt;
    memset(&opt, 0, sizeof opt);
    opt.spp = 1;
    opt.threads = 1;
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i], *val = i + 1 < argc ? argv[i + 1] : NULL;
        long v;
        if (cli_is_help(a)) return usage();
        if (!strcmp(a, "--pov"))
            pov = 1;
        else if (!strcmp(a, "--cycles"))
            cycles = 1;
        else if (!strcmp(a, "--no-shadows"))
            no_shadows = 1;
        else if (!strcmp(a, "--native"))
            native = 1;
        else if (!strcmp(a, "--adaptive"))
            adaptive = 1;
        else if (!strcmp(a, "-o") || !strcmp(a, "--model") || !strcmp(a, "--set") ||
                 !strcmp(a, "--osl-dir") || !strcmp(a, "--mode") || !strcmp(a, "--goal") ||
                 !strcmp(a, "--budget") || !strcmp(a, "--materials")) {
            if (!val) return cli_fail(cmd, "%s needs a value", a);
            ++i;
            if (!strcmp(a, "-o"))
                out = val;
            else if (!strcmp(a, "--model"))
                model_name = val;
            else if (!strcmp(a, "--osl-dir"))
                osl_dir = val;
            else if (!strcmp(a, "--mode"))
                mode = val;
            else if (!strcmp(a, "--goal"))
                goal = val;
            else if (!strcmp(a, "--budget"))
                budget_s = val;
            else if (!strcmp(a, "--materials")) {
                if (nmats == 16) return cli_fail(cmd, "too many --materials files (16 at most)");
                mats[nmats++] = val;
            } else if (nsets == 64)
                return cli_fail(cmd, "too many --set options (64 at most)");
            else
                sets[nsets++] = val;
        } else if (!strcmp(a, "--width") || !strcmp(a, "--height") || !strcmp(a, "--spp")) {
            long hi = !strcmp(a, "--spp") ? 65536 : SCENE_MAX_RESOLUTION;
            if (!cli_parse_int(val, 1, hi, &v))
                return cli_fail(cmd, "%s needs a whole number in [1, %ld]", a, hi);
            ++i;
            if (!strcmp(a, "--width"))
                opt.width = (int)v;
            else if (!strcmp(a, "--height"))
                opt.height = (int)v;
            else
                spp = (int)v;
        } else if (a[0] == '-') {
            return cli_fail(cmd, "unknown option '%s' (abrdf export --help)", a);
        } else if (!path) {
            path = a;
        } else {
            return cli_fail(cmd, "more than one SCENE ('%s' and '%s')", path, a);
        }
    }
    if (pov + cycles != 1) return cli_fail(cmd, "choose one format: --pov or --cycles");
    if (!path) return cli_fail(cmd, "missing SCENE (abrdf export --help)");
    if (!out) return cli_fail(cmd, "missing -o OUT");
    if (nsets && !model_name) return cli_fail(cmd, "--set needs --model");
    if (pov && (spp || mode || osl_dir))
        return cli_fail(cmd, "--spp, --mode and --osl-dir are options of --cycles");
    if (cycles && (native || no_shadows))
        return cli_fail(cmd, "--native and --no-shadows are options of --pov");
    if (native && no_shadows)
        return cli_fail(cmd, "--native uses POV-Ray's lights (with shadows); drop --no-shadows");
    if (mode && strcmp(mode, "eval") && strcmp(mode, "closure") && strcmp(mode, "generic"))
        return cli_fail(cmd, "--mode is eval, closure or generic, not '%s'", mode);
    if (adaptive && model_name) return cli_fail(cmd, "--adaptive and --model exclude each other");
    if ((goal || budget_s) && !adaptive)
        return cli_fail(cmd, "--%s needs --adaptive", goal ? "goal" : "budget");
    if (goal && budget_s) return cli_fail(cmd, "--goal and --budget exclude each other");
    abrdf_goal g = ABRDF_GOAL_PHOTOREAL;
    if (adaptive && !budget_s && (!goal || abrdf_goal_find(goal, &g) != ABRDF_OK))
        return cli_fail(cmd, "--adaptive needs --goal photoreal, --goal performance or --budget B");
    double budget = -1.0;
    if (budget_s) {
        char berr[256];
        if (budget_parse(budget_s, &budget, berr, sizeof berr))
            return cli_fail(cmd, "--budget: %s", berr);
    }

    scene s;
    char err[512];
    if (scene_parse_file(path, &s, err, sizeof err)) {
        fprintf(stderr, "abrdf export: %s\n", err);
        return 1;
    }
    int rc = 1, prepared = 0;
    render_scene rs;
    FILE *f = NULL;
    mat_table table = {NULL, 0, 0};
    if (adaptive || scene_needs_table(&s) || nmats) {
        char tpath[1024];
        if (data_path_find("materials.csv", tpath, sizeof tpath) != 0) {
            fprintf(stderr, "abrdf export: material table %s not found (set ABRDF_DATA_DIR)\n",
                    tpath);
            goto done;
        }
        if (mat_table_load(&table, tpath, err, sizeof err)) {
            fprintf(stderr, "abrdf export: %s\n", err);
            goto done;
        }
        for (int i = 0; i < nmats; ++i)
            if (mat_table_load(&table, mats[i], err, sizeof err)) {
                fprintf(stderr, "abrdf export: %s\n", err);
                goto done;
            }
    }
    /* the selection's choices, as abrdf render makes them (a budget's prediction samples the
     * image the scene file describes: its resolution, 4 samples per pixel) */
    if (scene_select_budgets(&s, path, &table, adaptive && !budget_s ? (int)g : -1, budget, 4, NULL,
                             err, sizeof err)) {
        fprintf(stderr, "abrdf export: %s\n", err);
        goto done;
    }
    if (model_name) {
        int st = scene_set_model(cmd, &s, model_name, sets, nsets);
        if (st) {
            rc = st;
            goto done;
        }
    }
    if (render_prepare(&s, &opt, &rs, err, sizeof err)) {
        fprintf(stderr, "abrdf export: %s\n", err);
        goto done;
    }
    prepared = 1;
    if (!(f = fopen(out, "w"))) {
        fprintf(stderr, "abrdf export: cannot write %s\n", out);
        goto done;
    }
    if (pov) {
        export_pov_options eo = {!native && !no_shadows && rs.light_count == 1, native, path};
        if (export_pov_write(&rs, &eo, f, err, sizeof err)) {
            fprintf(stderr, "abrdf export: %s: %s\n", out, err);
            goto done;
        }
    } else {
        export_options eo = {path, osl_dir ? osl_dir : osl_dir_default(), spp ? spp : 4,
                             mode ? mode : "eval"};
        if (export_cycles(f, &rs, &eo, err, sizeof err)) {
            fprintf(stderr, "abrdf export: %s: %s\n", out, err);
            goto done;
        }
    }
    rc = 0;
done:
    if (f && fclose(f) && rc == 0) {
        fprintf(stderr, "abrdf export: cannot write %s\n", out);
        rc = 1;
    }
    if (prepared) render_release(&rs);
    mat_table_free(&table);
    scene_free(&s);
    return rc;
}
