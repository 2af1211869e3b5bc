/* special.h - models evaluated by numerical integration or a layer recursion, in double
 * only (hair: Marschner, Huang; layered: Weidlich-Wilkie, Belcour). abrdf__eval_local_d
 * calls them, and the batch path calls that per element and rounds to float. */
#ifndef ABRDF_SPECIAL_H
#define ABRDF_SPECIAL_H
#include "abrdf_internal.h"

/* Local-frame evaluation, f = 0 for an unknown model. The value is the model's own:
 * abrdf__eval_local_d applies the finiteness guard. */
void abrdf__eval_special(abrdf_model model, const abrdf_params *p, const double wi[3],
                         const double wo[3], double f[3]);

#endif
