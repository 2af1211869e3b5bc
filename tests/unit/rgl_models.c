/* rgl_models.c - closed-form BRDFs for the .bsdf tests (rgl_models.h). */
#include "rgl_models.h"

#include <math.h>
#include <string.h>

#define PI 3.14159265358979323846
#define GGX_ALPHA 0.3

void rgl_model_lambert(void *user, const double wi[3], const double wo[3], double rgb[3])
{
    (void)user, (void)wi, (void)wo;
    rgb[0] = rgb[1] = rgb[2] = 0.5 / PI;
}

/* Walter et al. 2007, Eq. 33: D of the half vector's cosine c. */
static double d_ggx(double c, double a2)
{
    double t = c * c * (a2 - 1) + 1;
    return a2 / (PI * t * t);
}

/* Eq. 34: Smith's G1 of a direction's cosine c. */
static double g1_ggx(double c, double a2) { return 2 * c / (c + sqrt(a2 + (1 - a2) * c * c)); }

void rgl_model_ggx(void *user, const double wi[3], const double wo[3], double rgb[3])
{
    (void)user;
    static const double kd[3] = {0.3, 0.2, 0.1}, ks[3] = {0.6, 0.7, 0.9};
    double h[3] = {wi[0] + wo[0], wi[1] + wo[1], wi[2] + wo[2]};
    double len = sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
    double spec = 0, a2 = GGX_ALPHA * GGX_ALPHA;
    if (wi[2] > 0 && wo[2] > 0 && len > 0)
        spec = d_ggx(h[2] / len, a2) * g1_ggx(wi[2], a2) * g1_ggx(wo[2], a2) / (4 * wi[2] * wo[2]);
    for (int c = 0; c < 3; ++c) rgb[c] = kd[c] / PI + ks[c] * spec;
}

rgl_brdf_fn rgl_model_by_name(const char *name)
{
    return strcmp(name, "lambert") == 0 ? rgl_model_lambert
           : strcmp(name, "ggx") == 0   ? rgl_model_ggx
                                        : NULL;
}
