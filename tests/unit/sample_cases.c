/* sample_cases.c - parameter sets and directions of the sampling suites (sample_cases.h). */
#include <stdio.h>
#include <string.h>

#include "sample_cases.h"

/* One parameter at a time: lobes from broad to as peaked as a 24 x 48 grid warped toward
 * the pole resolves (Phong n = 500, alpha_g = 0.0225), the ends of the cloth, clearcoat and
 * anisotropy ranges, one to three layers, other hair indices and tilts. Colours steer the
 * mixtures' lobe probabilities. */
static const struct {
    const char *name;
    double v;
} sc_variations[] = {
    {"n", 1.0},
    {"n", 20.0},
    {"n", 500.0},
    {"r", 0.15},
    {"r", 1.0},
    {"anisotropic", 1.0},
    {"clearcoat_gloss", 0.0},
    {"k_amp", 50.0},
    {"kd", 0.05},
    {"ks", 0.1},
    {"f0", 0.5},
    {"layer_count", 1.0},
    {"layer_count", 2.0},
    {"layer_count", 3.0},
    {"eta", 1.3},
    {"cuticle_tilt", -6.0},
};

int sc_param_sets(abrdf_model model, sc_set *out)
{
    const abrdf_model_info *m = abrdf_model_get(model);
    int n = 0;
    abrdf_params_init(model, &out[n].p);
    snprintf(out[n++].label, sizeof out[0].label, "defaults");
    for (size_t v = 0; v < sizeof sc_variations / sizeof *sc_variations && n < SC_MAX_SETS; ++v) {
        for (int k = 0; k < m->param_count; ++k) {
            const abrdf_model_param *mp = &m->params[k];
            const abrdf_param_info *pi = abrdf_param_get(mp->id);
            double x = sc_variations[v].v;
            if (strcmp(pi->name, sc_variations[v].name) || x < mp->min || x > mp->max ||
                x == mp->def)
                continue;
            abrdf_params_init(model, &out[n].p);
            if (abrdf_param_set(&out[n].p, mp->id, &x, 1) != ABRDF_OK) continue;
            snprintf(out[n++].label, sizeof out[0].label, "%s=%g", pi->name, x);
        }
    }
    return n;
}

void sc_pole(abrdf_model model, const double wo[3], double pole[3], double *warp)
{
    const abrdf_sampler_info *s = abrdf_model_sampler(model);
    const char *name = s ? s->name : "";
    pole[0] = pole[1] = 0.0;
    pole[2] = 1.0;
    *warp = 1.0;
    if (!strcmp(name, "cosine")) return;
    if (!strcmp(name, "fibre_lobes") || !strcmp(name, "hair_lobes")) {
        pole[0] = 1.0;
        pole[2] = 0.0;
        return;
    }
    pole[0] = -wo[0];
    pole[1] = -wo[1];
    pole[2] = wo[2];
    *warp = 2.0;
}
