/* cmd_render.c - `abrdf render SCENE -o OUT.exr`: render a scene with the built-in ray
 * tracer, write linear EXR and a display-referred PNG preview beside it. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "cli.h"
#include "hair_table_args.h"
#include "scene_choice.h"
#include "budget_run.h"
#include "data_path.h"
#include "image_io.h"
#include "out_file.h"
#include "render.h"
#include "scene_load.h"
#include "scene_select.h"

static int usage(void)
{
    printf(
        "usage: abrdf render SCENE [-o OUT.exr] [--width W] [--height H] [--spp N] [--jitter]\n"
        "                    [--model NAME [--set NAME=VALUE ...] | --adaptive --goal G |\n"
        "                     --adaptive --budget B]\n"
        "                    [--materials FILE ...] [--threads N] [--explain] [--stats]\n"
        "                    [--full] [--precision float|double] [--no-preview]\n"
        "                    [--estimator mis|light|brdf] [--light-samples N]\n"
        "                    [--texture-cache MB] [--hair-table [--hair-table-sizes S]\n"
        "                    [--hair-table-cache DIR]]\n"
        "                    [--config OCIO] [--display D] [--view V]\n\n"
        "Renders SCENE (docs/RENDERER.md, \"Scene format\") to a linear float image (format from\n"
        "the extension, EXR recommended) and an sRGB PNG preview with the same name (.png);\n"
        "without -o, NAME.exr and NAME.png in the current directory for SCENE = .../NAME.scene.\n"
        "Both files are written whole or not at all: they replace existing files only when both\n"
        "are complete.\n"
        "  --width/--height  override the scene's resolution\n"
        "  --spp N           samples per pixel, a square (1, 4, 9, 16, ...); default 4\n"
        "  --jitter          jitter samples inside their strata (deterministic)\n"
        "  --model NAME      render every material with this model (shared parameters kept)\n"
        "  --set NAME=VALUE  with --model: set a parameter of every material\n"
        "  --adaptive --goal photoreal|performance   choose models per material (abrdf_select)\n"
        "  --adaptive --budget none|slight|noticeable|NMSE   the cheapest fitted models whose\n"
        "                    predicted image NMSE against the photoreal choice is within the\n"
        "                    budget (abrdf_select_budget, docs/SELECTION.md, \"The budget mode\")\n"
        "  --materials FILE  material-table file merged over data/materials.csv (table= entries)\n"
        "  --threads N       worker threads (and Embree's build threads); default: online CPUs\n"
        "  --explain         print the effect plan (what is simulated and why) and counters\n"
        "  --stats           print the work counters (and on stderr: the render time, the\n"
        "                    time to read and prepare the scene, Embree's memory)\n"
        "  --precision P     float (default): the fast path, each material's lobes evaluated over\n"
        "                    a tile's hits by the float batch API, within NMSE 1e-8 of double;\n"
        "                    double: the scalar double reference (the ports are checked on it)\n"
        "  --estimator E     sphere, rect and environment lights: mis (default) combines one\n"
        "                    light sample and one BRDF sample per hit by the power heuristic;\n"
        "                    light or brdf uses that strategy alone (docs/RENDERER.md)\n"
        "  --light-samples N samples per hit, sampled light and strategy; default 1\n"
        "  --texture-cache MB  memory of the textures' tile cache (OpenImageIO TextureSystem);\n"
        "                    default 256 (docs/GLTF.md, \"Textures\")\n"
        "  --hair-table      tabulate each huang material's residual lobes once (the rows over\n"
        "                    the threads; ~1 min of one core per material at the default sizes)\n"
        "                    and read them by interpolation: ~150x cheaper per call and\n"
        "                    nearer the converged model (docs/MODELS.md, \"A tabulated huang\")\n"
        "  --hair-table-sizes NT,NV,NP,SETS   the table's theta nodes, view azimuths, light\n"
        "                    azimuths and shift sets (default 24,9,32,16); implies --hair-table\n"
        "  --hair-table-cache DIR   keep each table in DIR (a file per material and sizes) and\n"
        "                    read it there instead of building it again; implies --hair-table\n"
        "                    With --budget, a huang material's budget is predicted against its\n"
        "                    table (the converged model), which it renders if chosen\n"
        "  --full            ignore the effect plan: shadow rays at every lit point, tangent\n"
        "                    frames and ambient everywhere (to measure what the plan saves)\n"
        "  --config/--display/--view   OpenColorIO preview transform (default: built-in sRGB)\n");
    return 0;
}

/* .../NAME.scene -> NAME.exr (in the current directory) in buf; 0, or -1 if it does not fit */
static int default_output(const char *scene, char *buf, size_t size)
{
    const char *base = strrchr(scene, '/');
    base = base ? base + 1 : scene;
    const char *dot = strrchr(base, '.');
    size_t len = dot && dot > base ? (size_t)(dot - base) : strlen(base);
    if (len == 0 || len + 5 > size) return -1;
    memcpy(buf, base, len);
    strcpy(buf + len, ".exr");
    return 0;
}

/* out.exr -> out.png */
static char *preview_path(const char *out)
{
    size_t len = strlen(out);
    const char *dot = strrchr(out, '.'), *slash = strrchr(out, '/');
    if (!dot || (slash && dot < slash)) dot = out + len;
    size_t base = (size_t)(dot - out);
    char *p = malloc(base + 5);
    if (!p) return NULL;
    memcpy(p, out, base);
    strcpy(p + base, ".png");
    return p;
}

#define CMD "render"

/* What the command line asks for. */
typedef struct render_args {
    int help;                            /* --help given: print the usage and stop */
    const char *path, *out;              /* the scene, the linear image (NULL: from the scene) */
    const char *config, *display, *view; /* the preview's OpenColorIO transform */
    scene_choice choice;                 /* --model, --adaptive, --materials, ... */
    int full, explain, stats, preview;
    int texture_cache; /* --texture-cache MB, 0: not given */
    render_options opt;
    hair_table_args hair; /* --hair-table, --hair-table-sizes, --hair-table-cache */
} render_args;

/* --precision and --estimator: a name from a list. 0, or the exit status after the message. */
static int take_named(render_args *ra, const char *a, const char *val)
{
    if (!strcmp(a, "--precision")) {
        if (!strcmp(val, "float"))
            ra->opt.precision = RENDER_FLOAT;
        else if (!strcmp(val, "double"))
            ra->opt.precision = RENDER_DOUBLE;
        else
            return cli_fail(CMD, "--precision must be float or double, not '%s'", val);
    } else {
        if (!strcmp(val, "mis"))
            ra->opt.estimator = RENDER_EST_MIS;
        else if (!strcmp(val, "light"))
            ra->opt.estimator = RENDER_EST_LIGHT;
        else if (!strcmp(val, "brdf"))
            ra->opt.estimator = RENDER_EST_BRDF;
        else
            return cli_fail(CMD, "--estimator must be mis, light or brdf, not '%s'", val);
    }
    return 0;
}

/* One option at argv[*i] (its value taken, *i advanced): 0, or the exit status after the
 * message. */
static int take_option(render_args *ra, int argc, char **argv, int *i)
{
    const char *a = argv[*i], *val = *i + 1 < argc ? argv[*i + 1] : NULL;
    if (!strcmp(a, "--precision") || !strcmp(a, "--estimator")) {
        if (!val) return cli_fail(CMD, "%s needs a value", a);
        ++*i;
        return take_named(ra, a, val);
    }
    int hair = hair_table_option(&ra->hair, CMD, argc, argv, i);
    if (hair) return hair < 0 ? -hair : 0;
    const cli_flag flags[] = {{"--explain", &ra->explain, 1},
                              {"--stats", &ra->stats, 1},
                              {"--jitter", &ra->opt.jitter, 1},
                              {"--no-preview", &ra->preview, 0},
                              {"--full", &ra->full, 1}};
    const cli_string strings[] = {{"-o", &ra->out},
                                  {"--config", &ra->config},
                                  {"--display", &ra->display},
                                  {"--view", &ra->view}};
    const cli_number numbers[] = {
        {"--light-samples", 4096, &ra->opt.light_samples},
        {"--width", SCENE_MAX_RESOLUTION, &ra->opt.width},
        {"--height", SCENE_MAX_RESOLUTION, &ra->opt.height},
        {"--spp", 4096, &ra->opt.spp},
        {"--threads", 64, &ra->opt.threads},
        {"--texture-cache", (long)TEXTURE_CACHE_MB_MAX, &ra->texture_cache}};
    const cli_options table = {flags,   sizeof flags / sizeof *flags,
                               strings, sizeof strings / sizeof *strings,
                               numbers, sizeof numbers / sizeof *numbers};
    int took = cli_option_take(CMD, &table, argc, argv, i);
    if (took) return took == 1 ? 0 : took;
    if (a[0] == '-' && a[1]) return cli_fail(CMD, "unknown option '%s' (abrdf render --help)", a);
    if (ra->path) return cli_fail(CMD, "unexpected argument '%s' (one scene only)", a);
    ra->path = a;
    return 0;
}

/* The command line into ra, the rules between the options checked: 0 (ra->help: print the
 * usage), or the exit status after the message. */
static int render_args_parse(int argc, char **argv, render_args *ra)
{
    memset(ra, 0, sizeof *ra);
    scene_choice_init(&ra->choice);
    ra->preview = 1;
    long cpus = sysconf(_SC_NPROCESSORS_ONLN);
    ra->opt = (render_options){0,
                               0,
                               4,
                               0,
                               cpus > 0 ? (int)(cpus < 64 ? cpus : 64) : 1,
                               0,
                               RENDER_FLOAT,
                               0,
                               RENDER_EST_MIS,
                               1,
                               TEXTURE_CACHE_MB_DEFAULT,
                               NULL};
    for (int i = 1; i < argc; ++i) {
        if (cli_is_help(argv[i])) {
            ra->help = 1;
            return 0;
        }
        int took = scene_choice_option(&ra->choice, CMD, argc, argv, &i);
        if (took < 0) return CLI_EXIT_USAGE;
        int rc = took ? 0 : take_option(ra, argc, argv, &i);
        if (rc) return rc;
    }
    if (!ra->path) return cli_fail(CMD, "missing SCENE (abrdf render --help)");
    long k = lround(sqrt((double)ra->opt.spp));
    if (k * k != ra->opt.spp)
        return cli_fail(CMD,
                        "--spp %d is not a square (1, 4, 9, 16, ...): strata form a k x k grid",
                        ra->opt.spp);
    if (scene_choice_check(&ra->choice, CMD)) return CLI_EXIT_USAGE;
    if (ra->texture_cache) ra->opt.texture_cache_mb = ra->texture_cache;
    int rc = hair_table_check(&ra->hair, CMD);
    if (rc) return rc;
    ra->opt.progress = isatty(2) && !ra->explain;
    return 0;
}

/* Everything that can be refused is refused before the work: outputs that are inputs
 * (first: nothing is read before), the output names and formats, the preview transform.
 * 0, or the exit status after the message. */
static int outputs_refuse(const render_args *ra, const char *png)
{
    char err[1024];
    if (png && !strcmp(png, ra->out))
        return cli_fail(CMD, "output %s leaves no name for the .png preview (--no-preview)",
                        ra->out);
    char tpath[1024];
    data_path_find("materials.csv", tpath, sizeof tpath);
    const char *outs[2] = {ra->out, png}, *out_roles[2] = {"output", "preview"};
    const char *ins[19] = {ra->path, ra->config, tpath},
               *in_roles[19] = {"scene", "--config file", "material table"};
    for (int i = 0; i < ra->choice.how.table_count; ++i)
        ins[3 + i] = ra->choice.mats[i], in_roles[3 + i] = "--materials file";
    if (out_files_distinct(outs, out_roles, 2, ins, in_roles, 3 + ra->choice.how.table_count, err,
                           sizeof err))
        return cli_fail(CMD, "%s", err);
    if (abrdf_image_check_output(ra->out, 1, err, sizeof err) ||
        (png && abrdf_image_check_preview(ra->config, ra->display, ra->view, err, sizeof err)))
        return cli_fail(CMD, "%s", err);
    return 0;
}

/* Wall seconds from a to b. */
static double seconds(struct timespec a, struct timespec b)
{
    return (double)(b.tv_sec - a.tv_sec) + 1e-9 * (double)(b.tv_nsec - a.tv_nsec);
}

/* The render's times on stderr, so stdout stays identical between runs: t[0..2] read, parsed
 * and prepared the scene, t[3..4] the render; cpu its CPU seconds. */
static void print_times(const render_args *ra, const render_scene *rs, const struct timespec t[5],
                        double cpu)
{
    /* CPU time (all threads) is robust on a shared machine; wall time shows the threads. */
    fprintf(stderr,
            "abrdf render: %dx%d, %d spp, %d threads, %s shading%s: %.3f s wall, %.3f s CPU "
            "(ray tracing only)\n",
            rs->width, rs->height, ra->opt.spp, ra->opt.threads,
            render_precision_name(ra->opt.precision), ra->full ? ", --full" : "",
            seconds(t[3], t[4]), cpu);
    fprintf(stderr,
            "abrdf render: scene read in %.3f s, prepared in %.3f s wall (materials, Embree "
            "scene, effect plan); Embree holds %zu bytes\n",
            seconds(t[0], t[1]), seconds(t[1], t[2]), accel_bytes(rs->accel));
    const hair_store *h = ra->opt.hair_tables;
    if (h)
        fprintf(stderr,
                "abrdf render: huang tables %d,%d,%d,%d: %d built in %.3f s wall, %d read from "
                "the cache%s (the budget's predictions and the render share them)\n",
                h->sizes[0], h->sizes[1], h->sizes[2], h->sizes[3], h->built, h->build_seconds,
                h->read, h->cache ? "" : " (none given)");
}

/* The preview (png, if any) and the linear image encoded into their open output files, then
 * committed together, the preview first: 0, or 1 after the message. */
static int write_outputs(const render_args *ra, const render_scene *rs, const float *rgb,
                         const char *png, out_file *png_out, out_file *exr_out)
{
    char err[1024];
    abrdf_bytes bytes;
    if (png) {
        if (abrdf_image_encode_preview(png, rs->width, rs->height, rgb, ra->config, ra->display,
                                       ra->view, &bytes, err, sizeof err)) {
            fprintf(stderr, "abrdf render: %s\n", err);
            return 1;
        }
        out_file_write(png_out, bytes.data, bytes.size);
        abrdf_bytes_free(&bytes);
        if (out_file_close(png_out, err, sizeof err)) {
            fprintf(stderr, "abrdf render: %s\n", err);
            return 1;
        }
    }
    if (abrdf_image_encode_linear(ra->out, rs->width, rs->height, rgb, &bytes, err, sizeof err)) {
        fprintf(stderr, "abrdf render: %s\n", err);
        return 1;
    }
    out_file_write(exr_out, bytes.data, bytes.size);
    abrdf_bytes_free(&bytes);
    out_file *files[2] = {png_out, exr_out};
    if (out_file_close(exr_out, err, sizeof err) ||
        out_file_commit(files + (png ? 0 : 1), png ? 2 : 1, err, sizeof err)) {
        fprintf(stderr, "abrdf render: %s\n", err);
        return 1;
    }
    return 0;
}

/* The parsed scene s, its materials chosen, rendered into the outputs; t[0..1] timed its
 * reading. 0, or the exit status after the message. */
static int render_to_files(render_args *ra, scene *s, const char *png, struct timespec t[5])
{
    char err[1024];
    int rc = 1, prepared = 0;
    float *rgb = NULL;
    render_scene rs;
    out_file exr_out = OUT_FILE_INIT, png_out = OUT_FILE_INIT;
    /* The outputs exist (as temporary files) before the work: a directory that is missing or
     * cannot be written fails now, not after the materials' choices, huang tables (about a
     * minute per material) and the render. */
    if (out_file_open(&exr_out, ra->out, err, sizeof err) ||
        (png && out_file_open(&png_out, png, err, sizeof err))) {
        fprintf(stderr, "abrdf render: %s\n", err);
        goto done;
    }
    /* a budget's prediction samples the image the scene file describes (its resolution, the
     * default 4 samples per pixel), so abrdf export makes the same choices */
    int applied = scene_choice_apply(&ra->choice, CMD, s, ra->path, 4, ra->explain ? stdout : NULL);
    if (applied) {
        rc = applied;
        goto done;
    }
    if (render_prepare(s, &ra->opt, &rs, err, sizeof err)) {
        fprintf(stderr, "abrdf render: %s\n", err);
        goto done;
    }
    clock_gettime(CLOCK_MONOTONIC, &t[2]);
    prepared = 1;
    if (ra->full && render_plan_ignore(&rs)) {
        fprintf(stderr, "abrdf render: out of memory\n");
        goto done;
    }
    if (ra->explain) {
        /* what the scene's reader assumed or left out (a glTF file's defaults) */
        for (const char *q = s->notes; q && *q;) {
            const char *nl = strchr(q, '\n');
            int len = nl ? (int)(nl - q) : (int)strlen(q);
            printf("scene: %.*s\n", len, q);
            q += len + (nl != NULL);
        }
        render_explain(&rs, &ra->opt, stdout);
    }
    rgb = malloc((size_t)rs.width * (size_t)rs.height * 3 * sizeof *rgb);
    if (!rgb) {
        fprintf(stderr, "abrdf render: out of memory for %dx%d\n", rs.width, rs.height);
        goto done;
    }
    render_stats st;
    clock_t c0 = clock();
    clock_gettime(CLOCK_MONOTONIC, &t[3]);
    if (render_image(&rs, &ra->opt, rgb, &st)) {
        fprintf(stderr, "abrdf render: --spp %d is not a square\n", ra->opt.spp);
        goto done;
    }
    clock_gettime(CLOCK_MONOTONIC, &t[4]);
    if (render_texture_error(&rs, err, sizeof err)) {
        fprintf(stderr, "abrdf render: %s\n", err);
        goto done;
    }
    double cpu = (double)(clock() - c0) / CLOCKS_PER_SEC;
    if (ra->explain || ra->stats) {
        render_stats_print(&st, stdout);
        render_textures_print(&rs, stdout);
        fflush(stdout);
        print_times(ra, &rs, t, cpu);
    }
    rc = write_outputs(ra, &rs, rgb, png, &png_out, &exr_out);
done:
    out_file_discard(&exr_out); /* committed: nothing left; else the targets stay as they were */
    out_file_discard(&png_out);
    if (prepared) render_release(&rs);
    free(rgb);
    return rc;
}

int cmd_render(int argc, char **argv)
{
    render_args ra;
    int rc = render_args_parse(argc, argv, &ra);
    if (rc || ra.help) return ra.help ? usage() : rc;
    char out_default[1024];
    if (!ra.out) {
        if (default_output(ra.path, out_default, sizeof out_default))
            return cli_fail(CMD, "no output name from scene %s: give -o OUT.exr", ra.path);
        ra.out = out_default;
    }
    char err[1024], *png = NULL;
    if (ra.preview && !(png = preview_path(ra.out))) {
        fprintf(stderr, "abrdf render: out of memory\n");
        return 1;
    }
    if ((rc = outputs_refuse(&ra, png))) {
        free(png);
        return rc;
    }
    scene s;
    struct timespec t[5];
    clock_gettime(CLOCK_MONOTONIC, &t[0]);
    if (scene_load(ra.path, &s, err, sizeof err)) {
        fprintf(stderr, "abrdf render: %s\n", err);
        free(png);
        return 1;
    }
    clock_gettime(CLOCK_MONOTONIC, &t[1]);
    const char *outs[2] = {ra.out, png}, *out_roles[2] = {"output", "preview"};
    /* one store of huang tables for the budget's predictions and the render */
    hair_store tables;
    if (ra.hair.sizes[0]) {
        hair_store_init(&tables, ra.hair.sizes, ra.hair.cache, ra.opt.threads);
        tables.progress = ra.opt.progress;
        ra.opt.hair_tables = ra.choice.how.hair_tables = &tables;
    }
    if (scene_outputs_distinct(&s, outs, out_roles, 2, err, sizeof err))
        rc = cli_fail(CMD, "%s", err);
    else
        rc = render_to_files(&ra, &s, png, t);
    if (ra.hair.sizes[0]) hair_store_free(&tables);
    scene_free(&s);
    free(png);
    return rc;
}
