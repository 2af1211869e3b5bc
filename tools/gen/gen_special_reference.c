/* gen_special_reference.c - writes tests/data/special_reference.txt: values of the expensive
 * reference models (marschner, huang, weidlich_wilkie, belcour) on a fixed grid of parameter
 * sets and direction pairs, from the double scalar path (abrdf_eval, local frame).
 *
 *   gen_special_reference [out.txt]   (default: stdout)
 *
 * The committed file was written by the code before the speed-ups of these models (CHANGELOG
 * 0.3.0); test_special_reference holds every later build to it within 1e-10 relative, so a
 * speed-up cannot change a result. huang's lines were written again when its quadrature's
 * grids became shifted (a change of the model's values: CHANGELOG, "Changed (the models)");
 * the other models' lines are the first ones. One line per value:
 *   model set k   wi_x wi_y wi_z  wo_x wo_y wo_z   f_r f_g f_b
 * with %.17g, so the file reproduces every double exactly. The parameter sets and directions
 * are listed below and in the file's header. */
#include <stdio.h>
#include <string.h>

#include "abrdf.h"

#define PAIRS 40

typedef struct set {
    const char *model;
    const char *assign[4]; /* "name=value" (one value: every component), NULL-terminated */
} set;

static const set sets[] = {
    {"marschner", {NULL}},
    {"marschner", {"r=0.3", "eta=1.7", "melanin=0.2", "cuticle_tilt=-5"}},
    {"marschner", {"aspect_ratio=0.8", "redness=0.1", NULL}},
    {"huang", {NULL}},
    {"huang", {"r=0.12", "eta=1.45", "melanin=0.4", "cuticle_tilt=-3"}},
    {"huang", {"aspect_ratio=1", "r=0.6", "redness=0", NULL}},
    {"weidlich_wilkie", {NULL}},
    {"weidlich_wilkie",
     {"layer_count=2", "layer0_sigma_a=0.5", "layer0_depth=0.3", "layer1_r=0.5"}},
    {"weidlich_wilkie", {"layer_count=1", "layer0_kappa=2", "layer0_r=0.5", NULL}},
    {"belcour", {NULL}},
    {"belcour", {"layer_count=2", "layer1_kappa=0", "layer1_eta=1.3", "layer0_depth=0.5"}},
    {"belcour", {"layer_count=3", "layer2_r=0.6", "layer0_sigma_a=1", "layer0_depth=0.2"}},
};

/* xorshift64*, the sequence of tests/unit/test_grid.c's tg_rng. */
static double uniform(unsigned long long *s)
{
    *s ^= *s >> 12;
    *s ^= *s << 25;
    *s ^= *s >> 27;
    return (double)((*s * 2685821657736338717ull) >> 11) * (1.0 / 9007199254740992.0);
}

/* A direction on the upper hemisphere, z in [0.02, 1]: not so grazing that the sphere's
 * rounding decides. */
static void hemi(unsigned long long *s, double w[3])
{
    double z = 0.02 + 0.98 * uniform(s), phi = 6.283185307179586 * uniform(s);
    double r = z < 1.0 ? __builtin_sqrt(1.0 - z * z) : 0.0;
    w[0] = r * __builtin_cos(phi);
    w[1] = r * __builtin_sin(phi);
    w[2] = z;
}

int main(int argc, char **argv)
{
    FILE *out = argc > 1 ? fopen(argv[1], "w") : stdout;
    if (!out) {
        fprintf(stderr, "gen_special_reference: cannot write %s\n", argv[1]);
        return 1;
    }
    fprintf(out, "# tests/data/special_reference.txt: written by gen_special_reference "
                 "(tools/gen/gen_special_reference.c)\n"
                 "# model set k  wi(3) wo(3)  f(3); parameter sets:\n");
    int nsets = (int)(sizeof sets / sizeof sets[0]);
    for (int s = 0; s < nsets; ++s) {
        fprintf(out, "#   %d %s:", s, sets[s].model);
        for (int a = 0; a < 4 && sets[s].assign[a]; ++a) fprintf(out, " %s", sets[s].assign[a]);
        fprintf(out, "%s\n", sets[s].assign[0] ? "" : " defaults");
    }
    for (int s = 0; s < nsets; ++s) {
        abrdf_model m;
        abrdf_params p;
        if (abrdf_model_find(sets[s].model, &m) || abrdf_params_init(m, &p)) return 1;
        for (int a = 0; a < 4 && sets[s].assign[a]; ++a) {
            char name[64];
            double v;
            int id;
            if (sscanf(sets[s].assign[a], "%63[^=]=%lf", name, &v) != 2 ||
                abrdf_param_find(name, &id)) {
                fprintf(stderr, "gen_special_reference: bad assignment %s\n", sets[s].assign[a]);
                return 1;
            }
            double vv[3] = {v, v, v};
            const abrdf_param_info *pi = abrdf_param_get(id);
            if (abrdf_param_set(&p, id, vv, pi->kind == ABRDF_PARAM_RGB ? 3 : 1)) {
                fprintf(stderr, "gen_special_reference: cannot set %s\n", sets[s].assign[a]);
                return 1;
            }
        }
        unsigned long long rng = 0x9e3779b97f4a7c15ull + (unsigned long long)s;
        for (int k = 0; k < PAIRS; ++k) {
            double wi[3], wo[3], f[3];
            hemi(&rng, wi);
            hemi(&rng, wo);
            if (k == 0) /* the mirror pair: the peak of every specular lobe */
                wo[0] = -wi[0], wo[1] = -wi[1], wo[2] = wi[2];
            int st = abrdf_eval(m, &p, NULL, wi, wo, f);
            if (st) {
                char msg[256];
                abrdf_params_check(m, &p, msg, sizeof msg);
                fprintf(stderr, "gen_special_reference: set %d: %s\n", s, msg);
                return 1;
            }
            fprintf(out, "%s %d %d %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n",
                    sets[s].model, s, k, wi[0], wi[1], wi[2], wo[0], wo[1], wo[2], f[0], f[1],
                    f[2]);
        }
    }
    if (out != stdout && fclose(out)) return 1;
    return 0;
}
