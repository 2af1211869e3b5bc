/* pov_grid_check.c - model-level cross-check of the POV-Ray port against libabrdf.
 *
 * For every model in the registry and three parameter sets, renders tests/ports/pov/model_grid.pov
 * with the real `povray` binary (abrdf.inc evaluating the model on a 12 x 12 x 12 grid of
 * (theta_i, theta_o, phi) directions, one pixel per direction and channel, emissive finish,
 * no antialiasing, EXR output), decodes the pixels and compares them with abrdf_eval at the
 * same directions. Prints a Markdown table model x set -> NMSE, max relative error; exits 1
 * if any NMSE or max relative error reaches 1e-4 (or povray fails), or a model has no
 * POV-Ray twin (pov_ported.h).
 *
 *   pov_grid_check POVRAY INCLUDE_DIR SCENE WORK_DIR [--grid MODEL=N,NM ...] [MODEL ...]
 *
 * --grid checks MODEL on an N x N x N grid plus NM sweep cells instead of 12 x 12 x 12 + 576:
 * for a model whose POV-Ray twin is too slow for the full grid (huang integrates ~5000 nodes
 * per value). N^3 + NM must be a multiple of the 48 cells of a pixel row. MODEL "all" sets
 * every model's grid (a later --grid MODEL=... overrides it).
 *
 * POV-Ray 3.7 writes EXR as half floats (11 significant bits, relative spacing 2^-10); the
 * scene splits each value into exponent, high and low mantissa pixels (model_grid.pov) so
 * the comparison resolves ~2^-22 relative. Models without a POV-Ray function (pov_ported.h)
 * are listed as such and not rendered. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "abrdf.h"
#include "image_io.h"
#include "pov_ported.h"

/* The grid, then NM cells of the sweep wi = wo (model_grid.pov); NA = NB = NC = n. */
enum { COLS = 48, N_FULL = 12, NM_FULL = 576 };
typedef struct grid {
    int n, nm;
} grid;
static grid grid_of[ABRDF_MODEL_COUNT];
#define PI 3.14159265358979323846
#define BAR 1e-4

/* The parameter sets of model_grid.pov (set 0: the model's defaults). */
typedef struct pset {
    double kd[3], ks[3], f0[3], n, r, sigma, anisotropic, clearcoat_gloss;
    double hair[7]; /* eta, melanin, redness, cuticle_tilt, aspect_ratio, entry_grid,
                       internal_grid (huang's quadrature: a coarser and a finer mix) */
} pset;
static const pset sets[3] = {
    {{0}, {0}, {0}, 0, 0, 0, 0, 0, {0}},
    {{0.2, 0.5, 0.8},
     {0.9, 0.6, 0.3},
     {0.95, 0.64, 0.54},
     20,
     0.15,
     0.8,
     0.8,
     0.4,
     {1.9, 0.8, 0.5, -5, 0.8, 4, 2}},
    {{0.7, 0.1, 0.4},
     {0.05, 1, 0.5},
     {0.02, 1, 0.3},
     3000,
     0.05,
     1.5,
     1,
     0,
     {1.2, 0.1, 0, 8, 0.75, 3, 4}},
};

static int set_param(abrdf_params *p, const abrdf_model_info *m, const char *name, const double *v,
                     int count)
{
    for (int i = 0; i < m->param_count; ++i) {
        const abrdf_param_info *pi = abrdf_param_get(m->params[i].id);
        if (strcmp(pi->name, name) == 0) return abrdf_param_set(p, m->params[i].id, v, count);
    }
    return ABRDF_OK; /* the model does not read it */
}

static int make_params(const abrdf_model_info *m, int s, abrdf_params *p)
{
    abrdf_params_init(m->id, p);
    if (s == 0) return ABRDF_OK;
    const pset *q = &sets[s];
    int st = set_param(p, m, "kd", q->kd, 3);
    st = st ? st : set_param(p, m, "ks", q->ks, 3);
    st = st ? st : set_param(p, m, "f0", q->f0, 3);
    st = st ? st : set_param(p, m, "n", &q->n, 1);
    st = st ? st : set_param(p, m, "r", &q->r, 1);
    st = st ? st : set_param(p, m, "sigma", &q->sigma, 1);
    st = st ? st : set_param(p, m, "anisotropic", &q->anisotropic, 1);
    st = st ? st : set_param(p, m, "clearcoat_gloss", &q->clearcoat_gloss, 1);
    static const char *hair[7] = {"eta",          "melanin",    "redness",      "cuticle_tilt",
                                  "aspect_ratio", "entry_grid", "internal_grid"};
    for (int k = 0; k < 7 && !st; ++k) st = set_param(p, m, hair[k], &q->hair[k], 1);
    /* layer stacks, as model_grid.pov: {eta, kappa, r, sigma_a r, g, b, depth} */
    static const double layers[3][4][7] = {
        {{0}},
        {{1.5, 0, 0.1, 0.5, 1, 2, 0.3},
         {1.2, 0, 0.3, 0, 0, 0, 0},
         {0.3, 3, 0.25, 0, 0, 0, 0},
         {1.5, 0, 0.1, 0, 0, 0, 0}},
        {{1.5, 0, 0.05, 0, 0, 0, 0},
         {0.7, 0, 0.4, 0.1, 0.1, 0.1, 1},
         {1.5, 0, 0.1, 0, 0, 0, 0},
         {1.5, 0, 0.1, 0, 0, 0, 0}},
    };
    double count = s == 1 ? 3 : 2;
    st = st ? st : set_param(p, m, "layer_count", &count, 1);
    for (int k = 0; k < 4 && !st; ++k) {
        static const char *names[] = {"eta", "kappa", "r", "sigma_a", "depth"};
        static const int at[] = {0, 1, 2, 3, 6}, cnt[] = {1, 1, 1, 3, 1};
        for (int j = 0; j < 5 && !st; ++j) {
            char name[32];
            snprintf(name, sizeof name, "layer%d_%s", k, names[j]);
            st = set_param(p, m, name, &layers[s][k][at[j]], cnt[j]);
        }
    }
    return st;
}

/* f from the three pixel channels (model_grid.pov's encoding). */
static double decode(const float *px)
{
    if (px[0] == 0.0f) return 0.0;
    return ((double)px[1] + (double)px[2] / 1024.0) * ldexp(1.0, (int)lround(px[0]) - 512);
}

/* Renders of one (model, set): POV-Ray spends most of a tiny render's wall time idle, so
 * up to JOBS renders run at once (each with one render thread). */
#define JOBS 6

static void out_path(char *out, size_t size, const char *work, const abrdf_model_info *m, int s)
{
    snprintf(out, size, "%s/grid_%s_%d.exr", work, m->name, s);
}

static pid_t render_start(const char *povray, const char *inc, const char *scene, const char *work,
                          const abrdf_model_info *m, int pov_id, int s)
{
    char out[4096], cmd[16384];
    grid g = grid_of[m->id];
    out_path(out, sizeof out, work, m, s);
    snprintf(cmd, sizeof cmd,
             "'%s' -D -V -GA +WT1 +I'%s' +L'%s' +O'%s' +FE +W%d +H%d -A "
             "Declare=ABRDF_GRID_MODEL=%d Declare=ABRDF_GRID_SET=%d Declare=ABRDF_GRID_N=%d "
             "Declare=ABRDF_GRID_NM=%d >'%s.log' 2>&1",
             povray, scene, inc, out, 3 * COLS, (g.n * g.n * g.n + g.nm) / COLS, pov_id, s, g.n,
             g.nm, out);
    remove(out);
    fflush(NULL);
    pid_t pid = fork();
    if (pid == 0) _exit(system(cmd) == 0 ? 0 : 1);
    return pid;
}

static int check(const char *work, const abrdf_model_info *m, int s, double *nmse, double *maxrel)
{
    char out[4096], err[512];
    out_path(out, sizeof out, work, m, s);
    const int NA = grid_of[m->id].n, NB = NA, NC = NA, NM = grid_of[m->id].nm;
    const int GRID = NA * NB * NC, CELLS = GRID + NM, ROWS = CELLS / COLS;
    abrdf_image img;
    if (abrdf_image_read(out, &img, err, sizeof err)) {
        fprintf(stderr, "pov_grid_check: %s (povray log: %s.log)\n", err, out);
        return -1;
    }
    if (img.width != 3 * COLS || img.height != ROWS) {
        fprintf(stderr, "pov_grid_check: %s is %dx%d\n", out, img.width, img.height);
        abrdf_image_free(&img);
        return -1;
    }
    abrdf_params p;
    if (make_params(m, s, &p)) {
        fprintf(stderr, "pov_grid_check: parameter set %d invalid for %s\n", s, m->name);
        abrdf_image_free(&img);
        return -1;
    }
    double sse = 0, energy = 0, worst = 0;
    for (int k = 0; k < CELLS; ++k) {
        int a = k / (NB * NC), b = (k / NC) % NB, c = k % NC;
        double ti = (a + 0.5) * PI / (2 * NA), to = (b + 0.5) * PI / (2 * NB), ph = c * 2 * PI / NC;
        if (k >= GRID) ti = to = (k - GRID + 0.5) * PI / (2 * NM), ph = 0;
        double wi[3] = {sin(ti), 0, cos(ti)};
        double wo[3] = {sin(to) * cos(ph), sin(to) * sin(ph), cos(to)};
        double f[3];
        abrdf_eval(m->id, &p, NULL, wi, wo, f);
        for (int ch = 0; ch < 3; ++ch) {
            const float *px =
                img.pixels + 3 * ((size_t)(k / COLS) * img.width + 3 * (k % COLS) + ch);
            double g = decode(px), ref = f[ch] < ldexp(1.0, -400) ? 0.0 : f[ch];
            sse += (g - ref) * (g - ref);
            energy += ref * ref;
            double big = fmax(fabs(g), fabs(ref));
            if (big > 0) worst = fmax(worst, fabs(g - ref) / big);
        }
    }
    abrdf_image_free(&img);
    *nmse = energy > 0 ? sse / energy : (sse > 0 ? INFINITY : 0.0);
    *maxrel = worst;
    return 0;
}

int main(int argc, char **argv)
{
    if (argc < 5) {
        fprintf(stderr, "usage: pov_grid_check POVRAY INCLUDE_DIR SCENE WORK_DIR [--grid "
                        "MODEL=N,NM ...] [MODEL ...]\n");
        return 2;
    }
    for (int id = 0; id < ABRDF_MODEL_COUNT; ++id) grid_of[id] = (grid){N_FULL, NM_FULL};
    int first = 5;
    for (; first + 1 < argc && !strcmp(argv[first], "--grid"); first += 2) {
        char name[64];
        int n = 0, nm = 0;
        const abrdf_model_info *gm = NULL;
        int all = 0;
        if (sscanf(argv[first + 1], "%63[^=]=%d,%d", name, &n, &nm) == 3) {
            all = !strcmp(name, "all");
            for (int id = 0; id < ABRDF_MODEL_COUNT && !gm && !all; ++id) {
                const abrdf_model_info *mi = abrdf_model_get((abrdf_model)id);
                if (mi && !strcmp(mi->name, name)) gm = mi;
            }
        }
        if ((!gm && !all) || n < 1 || n > N_FULL || nm < 0 || (n * n * n + nm) % COLS) {
            fprintf(stderr,
                    "pov_grid_check: bad --grid %s (MODEL=N,NM or all=N,NM; N^3 + NM a multiple "
                    "of %d)\n",
                    argv[first + 1], COLS);
            return 2;
        }
        for (int id = 0; id < ABRDF_MODEL_COUNT; ++id)
            if (all || id == (int)gm->id) grid_of[id] = (grid){n, nm};
    }
    int fails = 0, pov_id = 0, running = 0;
    const abrdf_model_info *chosen[ABRDF_MODEL_COUNT];
    int nchosen = 0;
    for (int id = 0; id < ABRDF_MODEL_COUNT; ++id) {
        const abrdf_model_info *m = abrdf_model_get((abrdf_model)id);
        if (!m) continue; /* POV-Ray ids number the registered models in registry order */
        if (m->needs & ABRDF_NEEDS_TABLE) continue; /* a table: no twin (docs/MEASURED.md) */
        int wanted = argc == first;
        for (int i = first; i < argc; ++i) wanted |= strcmp(argv[i], m->name) == 0;
        if (wanted && !pov_ported(argv[2], m->name)) {
            /* Every model of the library has a twin; a new one without it fails the check. */
            printf("| %s | - | no POV-Ray twin: FAIL | (no abrdf_%s in povray_macros) |\n", m->name,
                   m->name);
            ++fails;
        } else if (wanted) {
            chosen[nchosen++] = m;
            for (int s = 0; s < 3; ++s) {
                if (running == JOBS) {
                    wait(NULL);
                    --running;
                }
                if (render_start(argv[1], argv[2], argv[3], argv[4], m, pov_id, s) > 0) ++running;
            }
        }
        ++pov_id;
    }
    while (running > 0 && wait(NULL) > 0) --running;

    double worst_nmse = 0, worst_rel = 0;
    printf("\n| model | params | NMSE | max rel. error |\n|---|---|---|---|\n");
    for (int i = 0; i < nchosen; ++i) {
        const abrdf_model_info *m = chosen[i];
        {
            for (int s = 0; s < 3; ++s) {
                double nmse = 0, rel = 0;
                if (check(argv[4], m, s, &nmse, &rel)) {
                    ++fails;
                    continue;
                }
                int ok = nmse < BAR && rel < BAR;
                fails += !ok;
                worst_nmse = fmax(worst_nmse, nmse);
                worst_rel = fmax(worst_rel, rel);
                grid g = grid_of[m->id];
                char cells[64] = "";
                if (g.n != N_FULL || g.nm != NM_FULL)
                    snprintf(cells, sizeof cells, " (%d x %d x %d + %d cells)", g.n, g.n, g.n,
                             g.nm);
                printf("| %s | %s%s | %.2e | %.2e |%s\n", m->name,
                       s ? (s == 1 ? "set 1" : "set 2") : "defaults", cells, nmse, rel,
                       ok ? "" : " FAIL");
            }
        }
    }
    if (nchosen == 0 && fails == 0) {
        fprintf(stderr, "pov_grid_check: no such model\n");
        return 1;
    }
    printf("\nworst NMSE %.2e, worst max relative error %.2e (bar %.0e); %d failure(s)\n",
           worst_nmse, worst_rel, BAR, fails);
    return fails ? 1 : 0;
}
