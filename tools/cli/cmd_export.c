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
#include <unistd.h> /* sysconf, isatty */

#include "budget_run.h"
#include "cli.h"
#include "scene_choice.h"
#include "path_msg.h"
#include "data_path.h"
#include "export.h"
#include "export_pov.h"
#include "gltf.h"
#include "hair_table_args.h"
#include "image_io.h"
#include "measured_standin.h"
#include "out_file.h"
#include "scene_load.h"
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
           "                    [--hair-table [--hair-table-sizes S] [--hair-table-cache DIR]]\n"
           "       abrdf export --cycles SCENE -o OUT.py [--model NAME [--set NAME=VALUE ...]]\n"
           "                    [--adaptive --goal G|--budget B] [--materials FILE ...]\n"
           "                    [--width W] [--height H] [--spp N] [--mode eval|closure|generic]\n"
           "                    [--osl-dir DIR] [--hair-table [--hair-table-sizes S]\n"
           "                    [--hair-table-cache DIR]]\n"
           "       abrdf export --gltf SCENE -o OUT.gltf|OUT.glb [--model NAME [--set ...]]\n"
           "                    [--adaptive --goal G|--budget B] [--materials FILE ...]\n"
           "                    [--width W] [--height H]\n\n"
           "--pov writes SCENE (docs/RENDERER.md, \"Scene format\") as POV-Ray 3.7 SDL that\n"
           "shades every object with the library's models (povray_macros/abrdf.inc,\n"
           "docs/POVRAY.md): same camera, lights, primitives and materials. Render it with\n"
           "+L<abrdf>/povray_macros, linear HDR (+FE).\n"
           "--cycles writes a Blender/Cycles (bpy) script for the same scene with the OSL port\n"
           "(osl/, docs/OSL.md); run it with a Python that has bpy.\n"
           "--gltf writes glTF 2.0 (docs/GLTF.md, \"Writing glTF\"): meshes (analytic shapes\n"
           "tessellated), metallic-roughness materials, camera and lights, with what only abrdf\n"
           "reads back (exact shapes, explicit models) in extras; .glb for OUT.glb.\n"
           "SCENE may be a scene file or a glTF file (.gltf, .glb).\n"
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
           "                     $ABRDF_OSL_DIR, else the source tree's, else the installed one\n"
           "  --hair-table       (cycles eval and generic modes, pov) tabulate every huang\n"
           "                     material as abrdf render --hair-table does (~1 min of one\n"
           "                     core per material at the default sizes, over the online\n"
           "                     CPUs); the script holds the tables and its shaders read them\n"
           "                     (docs/OSL.md, \"huang from a table\"); --pov writes each\n"
           "                     as OUT.huang<i>.exr beside OUT, which its macros read\n"
           "                     (docs/POVRAY.md, \"huang from a table\")\n"
           "  --hair-table-sizes NT,NV,NP,SETS   at these sizes (implies --hair-table)\n"
           "  --hair-table-cache DIR   keep the tables in DIR (implies --hair-table)\n");
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

#define CMD "export"

/* What the command line asks for. */
typedef struct export_args {
    int help;                                  /* --help given: print the usage and stop */
    const char *path, *out;                    /* the scene, the output */
    const char *osl_dir, *mode;                /* --cycles: NULL for the defaults */
    scene_choice choice;                       /* --model, --adaptive, --materials, ... */
    int pov, cycles, gltf, no_shadows, native; /* the format and --pov's lighting */
    int spp;                                   /* --cycles: 0 for the default */
    render_options opt;                        /* --width, --height */
    hair_table_args hair; /* --hair-table, --hair-table-sizes, --hair-table-cache */
} export_args;

/* One option at argv[*i] (its value taken, *i advanced): 0, or the exit status after the
 * message. */
static int take_option(export_args *ea, int argc, char **argv, int *i)
{
    const char *a = argv[*i];
    int hair = hair_table_option(&ea->hair, CMD, argc, argv, i);
    if (hair) return hair < 0 ? -hair : 0;
    const cli_flag flags[] = {{"--pov", &ea->pov, 1},
                              {"--cycles", &ea->cycles, 1},
                              {"--gltf", &ea->gltf, 1},
                              {"--no-shadows", &ea->no_shadows, 1},
                              {"--native", &ea->native, 1}};
    const cli_string strings[] = {
        {"-o", &ea->out}, {"--osl-dir", &ea->osl_dir}, {"--mode", &ea->mode}};
    const cli_number numbers[] = {{"--width", SCENE_MAX_RESOLUTION, &ea->opt.width},
                                  {"--height", SCENE_MAX_RESOLUTION, &ea->opt.height},
                                  {"--spp", 65536, &ea->spp}};
    const cli_options table = {flags,   sizeof flags / sizeof *flags,
                               strings, sizeof strings / sizeof *strings,
                               numbers, sizeof numbers / sizeof *numbers};
    int took = cli_option_take(CMD, &table, argc, argv, i);
    if (took) return took == 1 ? 0 : took;
    if (a[0] == '-') return cli_fail(CMD, "unknown option '%s' (abrdf export --help)", a);
    if (ea->path) return cli_fail(CMD, "more than one SCENE ('%s' and '%s')", ea->path, a);
    ea->path = a;
    return 0;
}

/* The command line into ea, the rules between the options checked: 0 (ea->help: print the
 * usage), or the exit status after the message. */
static int export_args_parse(int argc, char **argv, export_args *ea)
{
    memset(ea, 0, sizeof *ea);
    scene_choice_init(&ea->choice);
    ea->opt.spp = 1;
    ea->opt.threads = 1;
    for (int i = 1; i < argc; ++i) {
        if (cli_is_help(argv[i])) {
            ea->help = 1;
            return 0;
        }
        int took = scene_choice_option(&ea->choice, CMD, argc, argv, &i);
        if (took < 0) return CLI_EXIT_USAGE;
        int rc = took ? 0 : take_option(ea, argc, argv, &i);
        if (rc) return rc;
    }
    if (ea->pov + ea->cycles + ea->gltf != 1)
        return cli_fail(CMD, "choose one format: --pov, --cycles or --gltf");
    if (!ea->path) return cli_fail(CMD, "missing SCENE (abrdf export --help)");
    if (!ea->out) return cli_fail(CMD, "missing -o OUT");
    if (ea->pov && (ea->spp || ea->mode || ea->osl_dir))
        return cli_fail(CMD, "--spp, --mode and --osl-dir are options of --cycles");
    if (!ea->pov && (ea->native || ea->no_shadows))
        return cli_fail(CMD, "--native and --no-shadows are options of --pov");
    if (ea->gltf && (ea->spp || ea->mode || ea->osl_dir))
        return cli_fail(CMD, "--spp, --mode and --osl-dir are options of --cycles");
    if (ea->gltf && !scene_is_gltf(ea->out))
        return cli_fail(CMD, "--gltf writes OUT.gltf or OUT.glb, not '%s'", ea->out);
    if (ea->native && ea->no_shadows)
        return cli_fail(CMD, "--native uses POV-Ray's lights (with shadows); drop --no-shadows");
    if (ea->mode && strcmp(ea->mode, "eval") && strcmp(ea->mode, "closure") &&
        strcmp(ea->mode, "generic"))
        return cli_fail(CMD, "--mode is eval, closure or generic, not '%s'", ea->mode);
    if (scene_choice_check(&ea->choice, CMD)) return CLI_EXIT_USAGE;
    int rc = hair_table_check(&ea->hair, CMD);
    if (rc) return rc;
    if (ea->hair.sizes[0] && ea->gltf)
        return cli_fail(CMD, "--hair-table is an option of --cycles and --pov (glTF's "
                             "materials hold no tables)");
    if (ea->hair.sizes[0] && ea->native)
        return cli_fail(CMD, "--hair-table is read by the function pigments, not by --native "
                             "(POV-Ray's own finishes)");
    if (ea->hair.sizes[0] && ea->mode && !strcmp(ea->mode, "closure"))
        return cli_fail(CMD, "--hair-table is read by the eval and generic modes' shaders, not "
                             "by --mode closure (Cycles' own hair closures)");
    return 0;
}

/* The output is never one of the inputs: 0, or the exit status after the message. */
static int output_refuse(const export_args *ea)
{
    char err[1024], tpath[1024];
    data_path_find("materials.csv", tpath, sizeof tpath);
    const char *out_role = "output", *ins[18] = {ea->path, tpath},
               *in_roles[18] = {"scene", "material table"};
    for (int i = 0; i < ea->choice.how.table_count; ++i)
        ins[2 + i] = ea->choice.mats[i], in_roles[2 + i] = "--materials file";
    if (out_files_distinct(&ea->out, &out_role, 1, ins, in_roles, 2 + ea->choice.how.table_count,
                           err, sizeof err))
        return cli_fail(CMD, "%s", err);
    return 0;
}

/* The huang tables of a POV-Ray export (abrdf_huang.inc, Abrdf_Huang_Table): one EXR image
 * per distinct table beside OUT, named OUT less its ".pov" and ".huang<i>.exr" for the first
 * tabulated material i that reads it; materials of the same parameters share it. */
typedef struct pov_tables {
    int n;             /* images */
    char **paths;      /* per material: the image's path, or NULL */
    const char **name; /* per material: its file name, as the .pov names it, or NULL */
    out_file *files;   /* n outputs */
} pov_tables;

static void pov_tables_free(pov_tables *t, int materials)
{
    for (int i = 0; t->files && i < t->n; ++i) out_file_discard(&t->files[i]);
    for (int i = 0; t->paths && i < materials; ++i) free(t->paths[i]);
    free(t->paths), free(t->name), free(t->files);
}

/* Names, checks and writes (not yet committed) the tables of rs's tabulated materials: 0, or
 * 1 after the message. */
static int pov_tables_write(const export_args *ea, const scene *s, const render_scene *rs,
                            pov_tables *t)
{
    char err[1024];
    int nm = rs->material_count;
    t->paths = calloc((size_t)nm, sizeof *t->paths);
    t->name = calloc((size_t)nm, sizeof *t->name);
    t->files = calloc((size_t)nm, sizeof *t->files);
    const double **vals = calloc((size_t)nm, sizeof *vals);
    const char **roles = calloc((size_t)nm + 1, sizeof *roles),
               **outs = calloc((size_t)nm + 1, sizeof *outs);
    int rc = 1;
    if (!t->paths || !t->name || !t->files || !vals || !roles || !outs) {
        fprintf(stderr, "abrdf export: out of memory\n");
        goto done;
    }
    size_t len = strlen(ea->out);
    if (len >= 4 && !strcmp(ea->out + len - 4, ".pov")) len -= 4;
    const char *slash = strrchr(ea->out, '/');
    size_t base = slash ? (size_t)(slash + 1 - ea->out) : 0;
    int n = 0;
    outs[n] = ea->out, roles[n] = "output";
    for (int i = 0; i < nm; ++i) {
        if (!rs->materials[i].used || !rs->materials[i].tabulated) continue;
        vals[i] = hair_store_table(ea->opt.hair_tables, &rs->materials[i].params);
        int j = 0;
        while (j < i && !(t->paths[j] && vals[j] == vals[i])) ++j;
        if (j < i) { /* the same table: the same image */
            t->name[i] = t->name[j];
            continue;
        }
        size_t size = len + 32;
        if (!(t->paths[i] = malloc(size))) {
            fprintf(stderr, "abrdf export: out of memory\n");
            goto done;
        }
        snprintf(t->paths[i], size, "%.*s.huang%d.exr", (int)len, ea->out, i);
        t->name[i] = t->paths[i] + base;
        outs[++n] = t->paths[i], roles[n] = "huang table";
    }
    const char *ins[1] = {ea->path}, *in_roles[1] = {"scene"};
    if (out_files_distinct(outs, roles, n + 1, ins, in_roles, 1, err, sizeof err) ||
        scene_outputs_distinct(s, outs, roles, n + 1, err, sizeof err)) {
        fprintf(stderr, "abrdf export: %s\n", err);
        goto done;
    }
    for (int i = 0; i < nm; ++i) {
        if (!t->paths[i]) continue;
        const double *v = vals[i];
        float *rgb = NULL;
        int w, h;
        abrdf_bytes bytes = {NULL, 0};
        out_file *o = &t->files[t->n];
        if (!v || export_pov_table_image(v, ea->opt.hair_tables->sizes, &rgb, &w, &h)) {
            fprintf(stderr, "abrdf export: %s: no memory for its huang table\n", t->paths[i]);
            goto done;
        }
        *o = (out_file)OUT_FILE_INIT;
        t->n += 1;
        int failed =
            abrdf_image_encode_linear_half(t->paths[i], w, h, rgb, &bytes, err, sizeof err) ||
            out_file_open(o, t->paths[i], err, sizeof err);
        if (!failed) {
            out_file_write(o, bytes.data, bytes.size);
            failed = out_file_close(o, err, sizeof err);
        }
        free(rgb);
        abrdf_bytes_free(&bytes);
        if (failed) {
            fprintf(stderr, "abrdf export: %s\n", err);
            goto done;
        }
    }
    rc = 0;
done:
    free(vals), free(roles), free(outs);
    return rc;
}

/* The prepared scene in the chosen format into the open output o; note: the selection's
 * trace for the file's comments, or NULL; tables: a POV-Ray export's huang tables. 0, or 1
 * after the message. */
static int export_write(const export_args *ea, const render_scene *rs, out_file *o,
                        const char *note, const pov_tables *tables)
{
    char err[1024];
    int failed;
    if (ea->pov) {
        int eval_lit =
            !ea->native && !ea->no_shadows; /* function pigments under POV-Ray's lights */
        export_pov_options eo = {eval_lit && rs->light_count == 1,
                                 eval_lit && rs->light_count > 1,
                                 ea->native,
                                 ea->path,
                                 note,
                                 ea->opt.hair_tables,
                                 tables->name};
        failed = export_pov_write(rs, &eo, o->f, err, sizeof err);
    } else {
        export_options eo = {ea->path,
                             ea->osl_dir ? ea->osl_dir : osl_dir_default(),
                             ea->spp ? ea->spp : 4,
                             ea->mode ? ea->mode : "eval",
                             note,
                             ea->opt.hair_tables};
        failed = export_cycles(o->f, rs, &eo, err, sizeof err);
    }
    if (failed) export_failed(o, ea->path, err, sizeof err);
    return failed ? 1 : 0;
}

/* The scene, its materials chosen, as glTF (a .glb if OUT ends so) written whole or not at
 * all: 0, or 1 after the message. */
static int export_gltf(const export_args *ea, scene *s)
{
    char err[1024];
    if (ea->opt.width) s->camera.width = ea->opt.width;
    if (ea->opt.height) s->camera.height = ea->opt.height;
    unsigned char *bytes = NULL;
    size_t size = 0;
    out_file o = OUT_FILE_INIT;
    out_file *const files[1] = {&o};
    int rc = 1;
    if (gltf_write_memory(s, ea->out, stderr, &bytes, &size, err, sizeof err)) {
        fprintf(stderr, "abrdf export: %s: %s\n", ea->path, err);
    } else if (out_file_open(&o, ea->out, err, sizeof err)) {
        fprintf(stderr, "abrdf export: %s\n", err);
    } else {
        out_file_write(&o, bytes, size);
        if (out_file_close(&o, err, sizeof err) || out_file_commit(files, 1, err, sizeof err))
            fprintf(stderr, "abrdf export: %s\n", err);
        else
            rc = 0;
    }
    out_file_discard(&o);
    free(bytes);
    return rc;
}

/* The parsed scene s, its materials chosen (the trace kept for the file's comments), written
 * whole or not at all. 0, or the exit status after the message. */
static int export_scene(export_args *ea, scene *s)
{
    char err[1024];
    int rc = 1, prepared = 0;
    render_scene rs;
    out_file o = OUT_FILE_INIT;
    out_file **files = NULL;
    pov_tables tables = {0, NULL, NULL, NULL};
    char *notes = NULL;
    size_t notes_len = 0;
    /* The output exists (as a temporary file) before the work: a directory that is missing or
     * cannot be written fails now, not after the tables are built (about a minute per material). */
    if (!ea->gltf && out_file_open(&o, ea->out, err, sizeof err)) {
        fprintf(stderr, "abrdf export: %s\n", err);
        goto done;
    }
    /* and the image module that writes the POV-Ray tables loads now (the same reason) */
    if (ea->pov && ea->opt.hair_tables &&
        abrdf_image_check_output("table.exr", 1, err, sizeof err)) {
        fprintf(stderr, "abrdf export: %s\n", err);
        goto done;
    }
    FILE *trace = open_memstream(&notes, &notes_len);
    if (!trace) {
        fprintf(stderr, "abrdf export: out of memory\n");
        goto done;
    }
    /* a budget's prediction samples the image the scene file describes (its resolution, 4
     * samples per pixel), as abrdf render's does: the same choices */
    int applied = scene_choice_apply(&ea->choice, CMD, s, ea->path, 4, trace);
    if (!applied && measured_standins(s, trace, err, sizeof err)) {
        fprintf(stderr, "abrdf export: %s\n", err);
        applied = 1;
    }
    if (fclose(trace)) {
        fprintf(stderr, "abrdf export: out of memory\n");
        goto done;
    }
    if (applied) {
        rc = applied;
        goto done;
    }
    if (ea->gltf) {
        rc = export_gltf(ea, s);
        goto done;
    }
    for (int i = 0; i < s->material_count; ++i)
        if (s->materials[i].textured)
            fprintf(stderr,
                    "abrdf export: material '%s': its maps are not exported (its factors are)\n",
                    s->materials[i].name);
    if (render_prepare(s, &ea->opt, &rs, err, sizeof err)) {
        fprintf(stderr, "abrdf export: %s\n", err);
        goto done;
    }
    prepared = 1;
    if (ea->pov && ea->opt.hair_tables && pov_tables_write(ea, s, &rs, &tables)) goto done;
    /* the tables, then the file that names them */
    if (!(files = malloc(((size_t)tables.n + 1) * sizeof *files))) {
        fprintf(stderr, "abrdf export: out of memory\n");
        goto done;
    }
    for (int i = 0; i < tables.n; ++i) files[i] = &tables.files[i];
    files[tables.n] = &o;
    if (export_write(ea, &rs, &o, notes_len ? notes : NULL, &tables)) goto done;
    if (out_file_close(&o, err, sizeof err) ||
        out_file_commit(files, tables.n + 1, err, sizeof err)) {
        fprintf(stderr, "abrdf export: %s\n", err);
        goto done;
    }
    rc = 0;
done:
    out_file_discard(&o); /* committed: nothing left; else OUT stays as it was */
    pov_tables_free(&tables, prepared ? rs.material_count : 0);
    free(files);
    free(notes);
    if (prepared) render_release(&rs);
    return rc;
}

int cmd_export(int argc, char **argv)
{
    export_args ea;
    int rc = export_args_parse(argc, argv, &ea);
    if (rc || ea.help) return ea.help ? usage() : rc;
    if ((rc = output_refuse(&ea))) return rc;
    char err[1024];
    scene s;
    if (scene_load(ea.path, &s, err, sizeof err)) {
        fprintf(stderr, "abrdf export: %s\n", err);
        return 1;
    }
    /* one store of huang tables for the budget's predictions and the script, built over the
     * online CPUs */
    hair_store tables;
    if (ea.hair.sizes[0]) {
        long cpus = sysconf(_SC_NPROCESSORS_ONLN);
        hair_store_init(&tables, ea.hair.sizes, ea.hair.cache,
                        cpus > 1 ? (cpus < 64 ? (int)cpus : 64) : 1);
        tables.progress = isatty(2);
        ea.opt.hair_tables = ea.choice.how.hair_tables = &tables;
    }
    const char *out_role = "output";
    if (scene_outputs_distinct(&s, &ea.out, &out_role, 1, err, sizeof err))
        rc = cli_fail(CMD, "%s", err);
    else
        rc = export_scene(&ea, &s);
    if (ea.hair.sizes[0]) hair_store_free(&tables);
    scene_free(&s);
    return rc;
}
