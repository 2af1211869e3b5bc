/* cmd_export.c - `abrdf export --pov|--cycles SCENE -o OUT`: the scene for another renderer.
 * Shared here: parsing, the material table and the selection of table= and adaptive materials
 * (--materials, --adaptive --goal|--budget, as abrdf render, so a budget's fitted
 * parameters are what the ports receive; the trace goes into the file as comments),
 * --model/--set, render_prepare (so every exporter reads the built-in renderer's own camera
 * vectors, materials and lights), and the output, written whole or not at all (out_file.h).
 * The writers live in export_pov.c (POV-Ray SDL, docs/POVRAY.md) and export_cycles.c
 * (Blender/Cycles bpy script with OSL, docs/OSL.md). */
#define _POSIX_C_SOURCE 200809L /* open_memstream */
#include <stdlib.h>
#include <string.h>

#include "budget_run.h"
#include "cli.h"
#include "scene_choice.h"
#include "path_msg.h"
#include "data_path.h"
#include "export.h"
#include "export_pov.h"
#include "out_file.h"
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
           "                    [--adaptive --goal G|--budget B] [--materials FILE ...]\n"
           "                    [--width W] [--height H] [--no-shadows | --native]\n"
           "       abrdf export --cycles SCENE -o OUT.py [--model NAME [--set NAME=VALUE ...]]\n"
           "                    [--adaptive --goal G|--budget B] [--materials FILE ...]\n"
           "                    [--width W] [--height H] [--spp N] [--mode eval|closure|generic]\n"
           "                    [--osl-dir DIR]\n\n"
           "--pov writes SCENE (docs/RENDERER.md, \"Scene format\") as POV-Ray 3.7 SDL that\n"
           "shades every object with the library's models (povray_macros/abrdf.inc,\n"
           "docs/POVRAY.md): same camera, lights, primitives and materials. Render it with\n"
           "+L<abrdf>/povray_macros, linear HDR (+FE).\n"
           "--cycles writes a Blender/Cycles (bpy) script for the same scene with the OSL port\n"
           "(osl/, docs/OSL.md); run it with a Python that has bpy.\n"
           "table= and adaptive materials are exported as the models the selection chose, with\n"
           "its trace as comments. OUT is written whole or not at all, never over SCENE.\n\n"
           "  --model/--set      as abrdf render: every material becomes this model\n"
           "  --adaptive --goal G | --budget B   as abrdf render: the selection chooses every\n"
           "                     material's models (a budget's choice with its fitted parameters)\n"
           "  --materials FILE   material-table file merged over data/materials.csv\n"
           "  --width/--height   override the scene's resolution\n"
           "  --no-shadows       (pov) emissive mode: every light in the pigment, no shadows.\n"
           "                     Otherwise one light uses POV-Ray's light and shadows, and\n"
           "                     several lights one render each: povray Declare=Abrdf_Pass=k\n"
           "                     for k = 0 .. N-1, images summed (oiiotool --add)\n"
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

/* An exporter failed: a failed write is reported with its reason (out_file_close's), any
 * other problem with the exporter's message. */
/* A writer failed: a failed write names the output (out_file), anything else is about what
 * the scene asks for and names the scene. */
static void export_failed(out_file *o, const char *scene_path, char *err, size_t err_size)
{
    char shown[256];
    if (o->error && out_file_close(o, err, err_size))
        fprintf(stderr, "abrdf export: %s\n", err);
    else
        fprintf(stderr, "abrdf export: %s: %s\n",
                path_short(shown, sizeof shown, scene_path, sizeof shown - 1), err);
}

int cmd_export(int argc, char **argv)
{
    const char *cmd = "export", *path = NULL, *out = NULL, *osl_dir = NULL, *mode = NULL;
    scene_choice choice;
    scene_choice_init(&choice);
    int pov = 0, cycles = 0, no_shadows = 0, native = 0, spp = 0;
    render_options opt;
    memset(&opt, 0, sizeof opt);
    opt.spp = 1;
    opt.threads = 1;
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i], *val = i + 1 < argc ? argv[i + 1] : NULL;
        long v;
        if (cli_is_help(a)) return usage();
        int took = scene_choice_option(&choice, cmd, argc, argv, &i);
        if (took) {
            if (took < 0) return CLI_EXIT_USAGE;
        } else if (!strcmp(a, "--pov"))
            pov = 1;
        else if (!strcmp(a, "--cycles"))
            cycles = 1;
        else if (!strcmp(a, "--no-shadows"))
            no_shadows = 1;
        else if (!strcmp(a, "--native"))
            native = 1;
        else if (!strcmp(a, "-o") || !strcmp(a, "--osl-dir") || !strcmp(a, "--mode")) {
            if (!val) return cli_fail(cmd, "%s needs a value", a);
            ++i;
            if (!strcmp(a, "-o"))
                out = val;
            else if (!strcmp(a, "--osl-dir"))
                osl_dir = val;
            else
                mode = val;
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
    if (pov && (spp || mode || osl_dir))
        return cli_fail(cmd, "--spp, --mode and --osl-dir are options of --cycles");
    if (cycles && (native || no_shadows))
        return cli_fail(cmd, "--native and --no-shadows are options of --pov");
    if (native && no_shadows)
        return cli_fail(cmd, "--native uses POV-Ray's lights (with shadows); drop --no-shadows");
    if (mode && strcmp(mode, "eval") && strcmp(mode, "closure") && strcmp(mode, "generic"))
        return cli_fail(cmd, "--mode is eval, closure or generic, not '%s'", mode);
    if (scene_choice_check(&choice, cmd)) return CLI_EXIT_USAGE;

    char err[1024];
    {
        char tpath[1024];
        data_path_find("materials.csv", tpath, sizeof tpath);
        const char *out_role = "output", *ins[18] = {path, tpath},
                   *in_roles[18] = {"scene", "material table"};
        for (int i = 0; i < choice.how.table_count; ++i)
            ins[2 + i] = choice.mats[i], in_roles[2 + i] = "--materials file";
        if (out_files_distinct(&out, &out_role, 1, ins, in_roles, 2 + choice.how.table_count, err,
                               sizeof err))
            return cli_fail(cmd, "%s", err);
    }
    scene s;
    if (scene_parse_file(path, &s, err, sizeof err)) {
        fprintf(stderr, "abrdf export: %s\n", err);
        return 1;
    }
    const char *out_role = "output";
    if (scene_outputs_distinct(&s, &out, &out_role, 1, err, sizeof err)) {
        scene_free(&s);
        return cli_fail(cmd, "%s", err);
    }
    int rc = 1, prepared = 0;
    render_scene rs;
    out_file o = OUT_FILE_INIT;
    out_file *const files[1] = {&o};
    /* The selection's trace, kept for the file's comments. */
    char *notes = NULL;
    size_t notes_len = 0;
    FILE *trace = open_memstream(&notes, &notes_len);
    if (!trace) {
        fprintf(stderr, "abrdf export: out of memory\n");
        goto done;
    }
    /* a budget's prediction samples the image the scene file describes (its resolution, 4
     * samples per pixel), as abrdf render's does: the same choices */
    int applied = scene_choice_apply(&choice, cmd, &s, path, 4, trace);
    if (fclose(trace)) {
        fprintf(stderr, "abrdf export: out of memory\n");
        goto done;
    }
    if (applied) {
        rc = applied;
        goto done;
    }
    if (render_prepare(&s, &opt, &rs, err, sizeof err)) {
        fprintf(stderr, "abrdf export: %s\n", err);
        goto done;
    }
    prepared = 1;
    if (out_file_open(&o, out, err, sizeof err)) {
        fprintf(stderr, "abrdf export: %s\n", err);
        goto done;
    }
    const char *note = notes_len ? notes : NULL;
    if (pov) {
        int eval_lit = !native && !no_shadows; /* function pigments under POV-Ray's lights */
        export_pov_options eo = {eval_lit && rs.light_count == 1, eval_lit && rs.light_count > 1,
                                 native, path, note};
        if (export_pov_write(&rs, &eo, o.f, err, sizeof err)) {
            export_failed(&o, path, err, sizeof err);
            goto done;
        }
    } else {
        export_options eo = {path, osl_dir ? osl_dir : osl_dir_default(), spp ? spp : 4,
                             mode ? mode : "eval", note};
        if (export_cycles(o.f, &rs, &eo, err, sizeof err)) {
            export_failed(&o, path, err, sizeof err);
            goto done;
        }
    }
    if (out_file_close(&o, err, sizeof err) || out_file_commit(files, 1, err, sizeof err)) {
        fprintf(stderr, "abrdf export: %s\n", err);
        goto done;
    }
    rc = 0;
done:
    out_file_discard(&o); /* committed: nothing left; else OUT stays as it was */
    free(notes);
    if (prepared) render_release(&rs);
    scene_free(&s);
    return rc;
}
