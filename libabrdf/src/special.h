/* special.h - models evaluated by numerical integration or a layer recursion, in double
 * only (hair: Marschner, Huang; layered: Weidlich-Wilkie, Belcour). The batch path calls
 * them per element and rounds to float. */
#ifndef ABRDF_SPECIAL_H
#define ABRDF_SPECIAL_H
#include "abrdf_internal.h"

/* Local-frame evaluation, f = 0 for an unknown model; never NaN/Inf/negative. */
void abrdf__eval_special(abrdf_model model, const abrdf_params *p, const double wi[3],
                         const double wo[3], double f[3]);

#endif
