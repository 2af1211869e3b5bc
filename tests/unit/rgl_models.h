/* rgl_models.h - closed-form BRDFs that the .bsdf tests tabulate with rgl_write (rgl_bsdf.h).
 *
 *   rgl_model_lambert  kd / pi, kd = 0.5 in every channel
 *   rgl_model_ggx      a coloured Lambert base plus a GGX lobe (Walter et al., EGSR 2007,
 *                      Eq. 33 with the separable Smith G1 of Eq. 34), alpha_g = 0.3, no Fresnel
 *   rgl_model_by_name  one of the two by name ("lambert", "ggx"), or NULL
 */
#ifndef ABRDF_TEST_RGL_MODELS_H
#define ABRDF_TEST_RGL_MODELS_H

#include "rgl_bsdf.h"

void rgl_model_lambert(void *user, const double wi[3], const double wo[3], double rgb[3]);
void rgl_model_ggx(void *user, const double wi[3], const double wo[3], double rgb[3]);
rgl_brdf_fn rgl_model_by_name(const char *name);

#endif
