/* cmd_render.c - `abrdf render SCENE -o OUT.exr`: render a scene with the built-in ray
 * tracer, write linear EXR and a display-referred PNG preview beside it. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "cli.h"
#include "scene_choice.h"
#include "budget_run.h"
#include "data_path.h"
#include "image_io.h"
#include "out_file.h"
#include "render.h"
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

int cmd_render(int argc, char **argv)
{
    const char *cmd = "render", *path = NULL, *out = NULL;
    const char *config = NULL, *display = NULL, *view = NULL;
    scene_choice choice;
    scene_choice_init(&choice);
    int full = 0, explain = 0, stats = 0, preview = 1;
    long cpus = sysconf(_SC_NPROCESSORS_ONLN);
    render_options opt = {
        0, 0, 4, 0, cpus > 0 ? (int)(cpus < 64 ? cpus : 64) : 1, 0, RENDER_FLOAT, 0, RENDER_EST_MIS,
        1};
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        const char *val = i + 1 < argc ? argv[i + 1] : NULL;
        long v;
        if (cli_is_help(a)) return usage();
        int took = scene_choice_option(&choice, cmd, argc, argv, &i);
        if (took) {
            if (took < 0) return CLI_EXIT_USAGE;
        } else if (!strcmp(a, "--explain"))
            explain = 1;
        else if (!strcmp(a, "--stats"))
            stats = 1;
        else if (!strcmp(a, "--jitter"))
            opt.jitter = 1;
        else if (!strcmp(a, "--no-preview"))
            preview = 0;
        else if (!strcmp(a, "--full"))
            full = 1;
        else if (!strcmp(a, "-o") || !strcmp(a, "--config") || !strcmp(a, "--display") ||
                 !strcmp(a, "--view") || !strcmp(a, "--precision") || !strcmp(a, "--estimator")) {
            if (!val) return cli_fail(cmd, "%s needs a value", a);
            ++i;
            if (!strcmp(a, "-o"))
                out = val;
            else if (!strcmp(a, "--config"))
                config = val;
            else if (!strcmp(a, "--display"))
                display = val;
            else if (!strcmp(a, "--view"))
                view = val;
            else if (!strcmp(a, "--precision")) {
                if (!strcmp(val, "float"))
                    opt.precision = RENDER_FLOAT;
                else if (!strcmp(val, "double"))
                    opt.precision = RENDER_DOUBLE;
                else
                    return cli_fail(cmd, "--precision must be float or double, not '%s'", val);
            } else if (!strcmp(a, "--estimator")) {
                if (!strcmp(val, "mis"))
                    opt.estimator = RENDER_EST_MIS;
                else if (!strcmp(val, "light"))
                    opt.estimator = RENDER_EST_LIGHT;
                else if (!strcmp(val, "brdf"))
                    opt.estimator = RENDER_EST_BRDF;
                else
                    return cli_fail(cmd, "--estimator must be mis, light or brdf, not '%s'", val);
            }
        } else if (!strcmp(a, "--light-samples")) {
            if (!cli_parse_int(val, 1, 4096, &v))
                return cli_fail(cmd, "%s needs a whole number in [1, 4096]", a);
            ++i;
            opt.light_samples = (int)v;
        } else if (!strcmp(a, "--width") || !strcmp(a, "--height") || !strcmp(a, "--spp") ||
                   !strcmp(a, "--threads")) {
            long hi = a[2] == 's' ? 4096 : a[2] == 't' ? 64 : SCENE_MAX_RESOLUTION;
            if (!cli_parse_int(val, 1, hi, &v))
                return cli_fail(cmd, "%s needs a whole number in [1, %ld]", a, hi);
            ++i;
            if (a[2] == 'w')
                opt.width = (int)v;
            else if (a[2] == 'h')
                opt.height = (int)v;
            else if (a[2] == 't')
                opt.threads = (int)v;
            else
                opt.spp = (int)v;
        } else if (a[0] == '-' && a[1]) {
            return cli_fail(cmd, "unknown option '%s' (abrdf render --help)", a);
        } else if (!path) {
            path = a;
        } else {
            return cli_fail(cmd, "unexpected argument '%s' (one scene only)", a);
        }
    }
    if (!path) return cli_fail(cmd, "missing SCENE (abrdf render --help)");
    long k = lround(sqrt((double)opt.spp));
    if (k * k != opt.spp)
        return cli_fail(
            cmd, "--spp %d is not a square (1, 4, 9, 16, ...): strata form a k x k grid", opt.spp);
    if (scene_choice_check(&choice, cmd)) return CLI_EXIT_USAGE;
    opt.progress = isatty(2) && !explain;
    char out_default[1024];
    if (!out) {
        if (default_output(path, out_default, sizeof out_default))
            return cli_fail(cmd, "no output name from scene %s: give -o OUT.exr", path);
        out = out_default;
    }

    /* Everything that can be refused is refused before the work: outputs that are inputs
     * (first: nothing is read before), the output names and formats, the preview transform. */
    char err[1024], *png = NULL;
    if (preview && !(png = preview_path(out))) {
        fprintf(stderr, "abrdf render: out of memory\n");
        return 1;
    }
    if (png && !strcmp(png, out)) {
        free(png);
        return cli_fail(cmd, "output %s leaves no name for the .png preview (--no-preview)", out);
    }
    {
        char tpath[1024];
        data_path_find("materials.csv", tpath, sizeof tpath);
        const char *outs[2] = {out, png}, *out_roles[2] = {"output", "preview"};
        const char *ins[19] = {path, config, tpath},
                   *in_roles[19] = {"scene", "--config file", "material table"};
        for (int i = 0; i < choice.how.table_count; ++i)
            ins[3 + i] = choice.mats[i], in_roles[3 + i] = "--materials file";
        if (out_files_distinct(outs, out_roles, 2, ins, in_roles, 3 + choice.how.table_count, err,
                               sizeof err)) {
            free(png);
            return cli_fail(cmd, "%s", err);
        }
    }
    if (abrdf_image_check_output(out, 1, err, sizeof err) ||
        (png && abrdf_image_check_preview(config, display, view, err, sizeof err))) {
        free(png);
        return cli_fail(cmd, "%s", err);
    }

    scene s;
    struct timespec r0, r1, r2;
    clock_gettime(CLOCK_MONOTONIC, &r0);
    if (scene_parse_file(path, &s, err, sizeof err)) {
        fprintf(stderr, "abrdf render: %s\n", err);
        free(png);
        return 1;
    }
    clock_gettime(CLOCK_MONOTONIC, &r1);
    const char *outs[2] = {out, png}, *out_roles[2] = {"output", "preview"};
    if (scene_outputs_distinct(&s, outs, out_roles, 2, err, sizeof err)) {
        scene_free(&s);
        free(png);
        return cli_fail(cmd, "%s", err);
    }
    int rc = 1;
    float *rgb = NULL;
    render_scene rs;
    int prepared = 0;
    out_file exr_out = OUT_FILE_INIT, png_out = OUT_FILE_INIT;
    out_file *files[2] = {&png_out, &exr_out}; /* committed together, the preview first */
    int nfiles = png ? 2 : 1;
    /* a budget's prediction samples the image the scene file describes (its resolution, the
     * default 4 samples per pixel), so abrdf export makes the same choices */
    int applied = scene_choice_apply(&choice, cmd, &s, path, 4, explain ? stdout : NULL);
    if (applied) {
        rc = applied;
        goto done;
    }
    if (render_prepare(&s, &opt, &rs, err, sizeof err)) {
        fprintf(stderr, "abrdf render: %s\n", err);
        goto done;
    }
    clock_gettime(CLOCK_MONOTONIC, &r2);
    prepared = 1;
    if (full && render_plan_ignore(&rs)) {
        fprintf(stderr, "abrdf render: out of memory\n");
        goto done;
    }
    /* The outputs exist (as temporary files) before the render: a directory that is missing
     * or cannot be written fails now, not after the work. */
    if (out_file_open(&exr_out, out, err, sizeof err) ||
        (png && out_file_open(&png_out, png, err, sizeof err))) {
        fprintf(stderr, "abrdf render: %s\n", err);
        goto done;
    }
    if (explain) render_explain(&rs, &opt, stdout);
    rgb = malloc((size_t)rs.width * (size_t)rs.height * 3 * sizeof *rgb);
    if (!rgb) {
        fprintf(stderr, "abrdf render: out of memory for %dx%d\n", rs.width, rs.height);
        goto done;
    }
    render_stats st;
    struct timespec t0, t1;
    clock_t c0 = clock();
    clock_gettime(CLOCK_MONOTONIC, &t0);
    if (render_image(&rs, &opt, rgb, &st)) {
        fprintf(stderr, "abrdf render: --spp %d is not a square\n", opt.spp);
        goto done;
    }
    clock_gettime(CLOCK_MONOTONIC, &t1);
    double cpu = (double)(clock() - c0) / CLOCKS_PER_SEC;
    if (explain || stats) {
        render_stats_print(&st, stdout);
        /* Wall time on stderr: stdout stays identical between runs. */
        fflush(stdout);
        /* CPU time (all threads) is robust on a shared machine; wall time shows the threads. */
        fprintf(stderr,
                "abrdf render: %dx%d, %d spp, %d threads, %s shading%s: %.3f s wall, %.3f s CPU "
                "(ray tracing only)\n",
                rs.width, rs.height, opt.spp, opt.threads, render_precision_name(opt.precision),
                full ? ", --full" : "",
                (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec), cpu);
        fprintf(stderr,
                "abrdf render: scene read in %.3f s, prepared in %.3f s wall (materials, Embree "
                "scene, effect plan); Embree holds %zu bytes\n",
                (double)(r1.tv_sec - r0.tv_sec) + 1e-9 * (double)(r1.tv_nsec - r0.tv_nsec),
                (double)(r2.tv_sec - r1.tv_sec) + 1e-9 * (double)(r2.tv_nsec - r1.tv_nsec),
                accel_bytes(rs.accel));
    }
    abrdf_bytes bytes;
    if (png) {
        if (abrdf_image_encode_preview(png, rs.width, rs.height, rgb, config, display, view, &bytes,
                                       err, sizeof err)) {
            fprintf(stderr, "abrdf render: %s\n", err);
            goto done;
        }
        out_file_write(&png_out, bytes.data, bytes.size);
        abrdf_bytes_free(&bytes);
        if (out_file_close(&png_out, err, sizeof err)) {
            fprintf(stderr, "abrdf render: %s\n", err);
            goto done;
        }
    }
    if (abrdf_image_encode_linear(out, rs.width, rs.height, rgb, &bytes, err, sizeof err)) {
        fprintf(stderr, "abrdf render: %s\n", err);
        goto done;
    }
    out_file_write(&exr_out, bytes.data, bytes.size);
    abrdf_bytes_free(&bytes);
    if (out_file_close(&exr_out, err, sizeof err) ||
        out_file_commit(files + (png ? 0 : 1), nfiles, err, sizeof err)) {
        fprintf(stderr, "abrdf render: %s\n", err);
        goto done;
    }
    rc = 0;
done:
    out_file_discard(&exr_out); /* committed: nothing left; else the targets stay as they were */
    out_file_discard(&png_out);
    if (prepared) render_release(&rs);
    free(png);
    free(rgb);
    scene_free(&s);
    return rc;
}
