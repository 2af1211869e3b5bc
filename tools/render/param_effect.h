/* param_effect.h - does a parameter a scene line gives change the reflectance it describes?
 * A scene refuses a parameter that changes nothing (a layer past the stack's layer_count,
 * a selection input the chosen model does not depend on) instead of ignoring it: the test is
 * the reflectance itself, f_r at a fixed set of direction pairs, with the value as given and
 * with another value.
 *
 *   param_nudge       another value of one parameter, inside its range
 *   lobes_differ      do two materials' reflectances differ anywhere on the direction set?
 *   param_matters     does a parameter change a material's reflectance around its value?
 */
#ifndef ABRDF_PARAM_EFFECT_H
#define ABRDF_PARAM_EFFECT_H

#include "abrdf.h"

/* q = p with parameter id moved a tenth of its range (integers: by 1) up (dir > 0) or down,
 * every channel of a colour. Returns 0 if every channel stays in range, else -1. */
int param_nudge(const abrdf_params *p, int id, int dir, abrdf_params *q);
/* 1 if moving parameter id of block p up or down (param_nudge) changes the reflectance of the
 * lobes (lobes_differ), else 0. */
int param_matters(const abrdf_model *lobes, int count, const abrdf_params *p, int id);
/* 1 if the sum of f_r over lobes a (na of them, one block pa) and over lobes b (block pb)
 * differ at one of 24 direction pairs spread over the hemisphere, a third of them in the mirror
 * direction (a lobe as sharp as n = 1e6 is seen there; a tangent frame along x), or
 * if either cannot be evaluated; 0 if they are equal at every pair. */
int lobes_differ(const abrdf_model *a, int na, const abrdf_params *pa, const abrdf_model *b, int nb,
                 const abrdf_params *pb);

#endif
