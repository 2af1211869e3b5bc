/* pov_scene_check.c - scene-level cross-check of the POV-Ray port: for every scene and every
 * model (plus the scene's own materials), renders the scene with `abrdf render --precision
 * double` (the reference path) and, after
 * `abrdf export --pov`, with the real `povray` binary at k times the resolution (no
 * antialiasing, EXR), averages k x k blocks (the renderer's stratum centres) and compares.
 * Prints the model x scene -> NMSE table (Markdown); exits 1 if any NMSE reaches 1e-4.
 *
 *   pov_scene_check ABRDF POVRAY INCLUDE_DIR WORK_DIR SIZE [--report] [--size MODEL=N ...]
 *                   SCENE... [-- MODEL...]
 *
 * A SCENE written "emissive:PATH" is exported with --no-shadows (every light summed inside
 * the pigment, no POV-Ray light), "native:PATH" with --native (POV-Ray's own finishes);
 * otherwise a one-light scene uses POV-Ray's light and shadows. --report prints the table
 * without failing (for the native mapping, whose phong/blinn_phong lack N.wi by design).
 * POV-Ray's own trace CPU time of each render is printed too. A model without a POV-Ray
 * function (pov_ported.h) is listed as such, not rendered, and fails the check: every model
 * of the library has a twin.
 * SIZE is the width = height in pixels; k = 2 (abrdf render --spp 4). --size renders MODEL at
 * N x N instead (not larger than SIZE): for a model whose POV-Ray twin is too slow for the
 * full image (huang integrates ~5000 nodes per value and channel). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "abrdf.h"
#include "image_io.h"
#include "metrics.h"
#include "pov_ported.h"

#define K 2    /* samples per pixel side */
#define JOBS 6 /* concurrent jobs: POV-Ray idles through much of a small render */
#define BAR 1e-4
#define MAX_SCENES 8
#define MAX_SIZES 8

/* --size overrides */
static const char *size_model[MAX_SIZES];
static int size_value[MAX_SIZES], nsizes;

static int model_size(const char *model, int size)
{
    for (int i = 0; i < nsizes; ++i)
        if (!strcmp(size_model[i], model) && size_value[i] < size) return size_value[i];
    return size;
}

static const char *scene_path(const char *arg)
{
    if (!strncmp(arg, "emissive:", 9)) return arg + 9;
    if (!strncmp(arg, "native:", 7)) return arg + 7;
    return arg;
}

static const char *scene_mode(const char *arg)
{
    return !strncmp(arg, "emissive:", 9) ? "emissive" : !strncmp(arg, "native:", 7) ? "native" : "";
}

static const char *export_flag(const char *arg)
{
    return !strncmp(arg, "emissive:", 9) ? " --no-shadows"
           : !strncmp(arg, "native:", 7) ? " --native"
                                         : "";
}

static const char *base(const char *path)
{
    const char *s = strrchr(path, '/');
    return s ? s + 1 : path;
}

static void stem(char *out, size_t size, const char *work, const char *scene, const char *model,
                 const char *suffix)
{
    char name[256];
    snprintf(name, sizeof name, "%s%s%s", scene_mode(scene), *scene_mode(scene) ? "_" : "",
             base(scene_path(scene)));
    char *dot = strrchr(name, '.');
    if (dot) *dot = '\0';
    snprintf(out, size, "%s/%s_%s%s", work, name, model, suffix);
}

/* One job: reference render, export, POV-Ray render; the child's exit status says whether
 * all three ran. */
static pid_t job_start(char **argv, const char *scene, const char *model, int size)
{
    const char *abrdf = argv[1], *povray = argv[2], *inc = argv[3], *work = argv[4];
    char ref[4096], pov[4096], big[4096], log[4096], mopt[256] = "";
    stem(ref, sizeof ref, work, scene, model, "_ref.exr");
    stem(pov, sizeof pov, work, scene, model, ".pov");
    stem(big, sizeof big, work, scene, model, "_pov.exr");
    stem(log, sizeof log, work, scene, model, ".log");
    if (strcmp(model, "scene")) snprintf(mopt, sizeof mopt, "--model %s", model);
    static char cmd[65536]; /* child-local after fork; static keeps it off the stack */
    snprintf(cmd, sizeof cmd,
             "'%s' render '%s' %s -o '%s' --width %d --height %d --spp %d --threads 1 --precision "
             "double --no-preview "
             ">'%s' 2>&1 && "
             "'%s' export --pov '%s' %s%s -o '%s' --width %d --height %d >>'%s' 2>&1 && "
             "'%s' -D +WT1 +I'%s' +O'%s' +FE +W%d +H%d -A +L'%s' >>'%s' 2>&1",
             abrdf, scene_path(scene), mopt, ref, size, size, K * K, log, abrdf, scene_path(scene),
             mopt, export_flag(scene), pov, size, size, log, povray, pov, big, K * size, K * size,
             inc, log);
    remove(big);
    fflush(NULL);
    pid_t pid = fork();
    if (pid == 0) _exit(system(cmd) == 0 ? 0 : 1);
    return pid;
}

static int compare(const char *work, const char *scene, const char *model, int size,
                   abrdf_metrics *m)
{
    char ref[4096], big[4096], log[4096], err[512];
    stem(ref, sizeof ref, work, scene, model, "_ref.exr");
    stem(big, sizeof big, work, scene, model, "_pov.exr");
    stem(log, sizeof log, work, scene, model, ".log");
    abrdf_image r, b;
    if (abrdf_image_read(ref, &r, err, sizeof err)) {
        fprintf(stderr, "pov_scene_check: %s (log: %s)\n", err, log);
        return -1;
    }
    if (abrdf_image_read(big, &b, err, sizeof err)) {
        fprintf(stderr, "pov_scene_check: %s (log: %s)\n", err, log);
        abrdf_image_free(&r);
        return -1;
    }
    int rc = -1;
    float *small = NULL;
    if (r.width != size || r.height != size || b.width != K * size || b.height != K * size) {
        fprintf(stderr, "pov_scene_check: %s: unexpected image sizes\n", log);
        goto done;
    }
    small = calloc((size_t)size * size * 3, sizeof *small);
    if (!small) goto done;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x)
            for (int c = 0; c < 3; ++c) {
                double sum = 0;
                for (int sy = 0; sy < K; ++sy)
                    for (int sx = 0; sx < K; ++sx)
                        sum += b.pixels[3 * ((size_t)(K * y + sy) * b.width + (K * x + sx)) + c];
                small[3 * ((size_t)y * size + x) + c] = (float)(sum / (K * K));
            }
    rc = abrdf_metrics_compute(small, r.pixels, size, size, 3, m) == ABRDF_METRICS_OK &&
                 m->nmse_defined
             ? 0
             : -1;
    if (rc)
        fprintf(stderr, "pov_scene_check: %s: no NMSE (non-finite pixels or black reference)\n",
                log);
done:
    free(small);
    abrdf_image_free(&r);
    abrdf_image_free(&b);
    return rc;
}

/* POV-Ray's own timing from its log: "Trace Time: ... using N thread(s) with X CPU-seconds total". */
static double trace_cpu(const char *work, const char *scene, const char *model)
{
    char log[4096], line[512];
    stem(log, sizeof log, work, scene, model, ".log");
    FILE *f = fopen(log, "r");
    double cpu = -1;
    int in_trace = 0;
    while (f && fgets(line, sizeof line, f)) {
        if (strstr(line, "Trace Time:")) in_trace = 1;
        char *w = strstr(line, " with ");
        if (in_trace && w && strstr(line, "CPU-seconds")) {
            cpu = atof(w + 6);
            in_trace = 0;
        }
    }
    if (f) fclose(f);
    return cpu;
}

int main(int argc, char **argv)
{
    if (argc < 7) {
        fprintf(stderr, "usage: pov_scene_check ABRDF POVRAY INCLUDE_DIR WORK_DIR SIZE [--report] "
                        "SCENE... [-- MODEL...]\n");
        return 2;
    }
    int size = atoi(argv[5]);
    if (size < 1 || size > 4096) {
        fprintf(stderr, "pov_scene_check: SIZE must be in [1, 4096]\n");
        return 2;
    }
    const char *scenes[MAX_SCENES];
    int nscenes = 0, i = 6, report = 0;
    for (; i < argc && strcmp(argv[i], "--") && !strncmp(argv[i], "--", 2); ++i) {
        static char names[MAX_SIZES][64];
        if (!strcmp(argv[i], "--report")) {
            report = 1;
        } else if (!strcmp(argv[i], "--size") && i + 1 < argc && nsizes < MAX_SIZES &&
                   sscanf(argv[i + 1], "%63[^=]=%d", names[nsizes], &size_value[nsizes]) == 2 &&
                   size_value[nsizes] >= 1) {
            size_model[nsizes] = names[nsizes];
            ++nsizes;
            ++i;
        } else {
            fprintf(stderr, "pov_scene_check: bad option %s (--report, --size MODEL=N)\n", argv[i]);
            return 2;
        }
    }
    for (; i < argc && strcmp(argv[i], "--"); ++i)
        if (nscenes < MAX_SCENES) scenes[nscenes++] = argv[i];
    const char *models[ABRDF_MODEL_COUNT + 1];
    int nmodels = 0;
    if (i < argc) {
        for (++i; i < argc && nmodels < ABRDF_MODEL_COUNT + 1; ++i) models[nmodels++] = argv[i];
    } else {
        models[nmodels++] = "scene"; /* the scene's own materials */
        for (int id = 0; id < ABRDF_MODEL_COUNT; ++id) {
            const abrdf_model_info *mi = abrdf_model_get((abrdf_model)id);
            /* a table model has no twin: the hosts get its fitted stand-in (MEASURED.md) */
            if (mi && !(mi->needs & ABRDF_NEEDS_TABLE)) models[nmodels++] = mi->name;
        }
    }

    int running = 0;
    for (int m = 0; m < nmodels; ++m)
        for (int s = 0;
             s < nscenes && (!strcmp(models[m], "scene") || pov_ported(argv[3], models[m])); ++s) {
            if (running == JOBS) {
                wait(NULL);
                --running;
            }
            if (job_start(argv, scenes[s], models[m], model_size(models[m], size)) > 0) ++running;
        }
    while (running > 0 && wait(NULL) > 0) --running;

    int fails = 0;
    double worst = 0;
    printf("| model |");
    for (int s = 0; s < nscenes; ++s)
        printf(" %s%s%s%s NMSE | max abs. error | POV-Ray trace CPU s |",
               base(scene_path(scenes[s])), *scene_mode(scenes[s]) ? " (" : "",
               scene_mode(scenes[s]), *scene_mode(scenes[s]) ? ")" : "");
    printf("\n|---|");
    for (int s = 0; s < nscenes; ++s) printf("---|---|---|");
    printf("\n");
    for (int m = 0; m < nmodels; ++m) {
        int msize = model_size(models[m], size);
        if (msize != size)
            printf("| %s (%d x %d pixels) |", models[m], msize, msize);
        else
            printf("| %s |", strcmp(models[m], "scene") ? models[m] : "(scene's materials)");
        if (strcmp(models[m], "scene") && !pov_ported(argv[3], models[m])) {
            for (int s = 0; s < nscenes; ++s) printf(" no POV-Ray twin: FAIL | | |");
            printf("\n");
            ++fails; /* every model of the library has a twin */
            continue;
        }
        for (int s = 0; s < nscenes; ++s) {
            abrdf_metrics mt;
            if (compare(argv[4], scenes[s], models[m], msize, &mt)) {
                printf(" error | | |");
                ++fails;
                continue;
            }
            int ok = mt.nmse < BAR;
            fails += !ok && !report;
            worst = fmax(worst, mt.nmse);
            printf(" %.2e%s | %.2e | %.3f |", mt.nmse, ok || report ? "" : " FAIL", mt.max_abs,
                   trace_cpu(argv[4], scenes[s], models[m]));
        }
        printf("\n");
    }
    printf("\n%dx%d pixels, %d x %d samples per pixel; worst NMSE %.2e (bar %.0e); %d failure(s)\n",
           size, size, K, K, worst, BAR, fails);
    return fails ? 1 : 0;
}
