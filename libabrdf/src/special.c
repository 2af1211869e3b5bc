/* special.c - dispatch of the models evaluated in double only: hair (hair.h) and layered
 * models (layered.h). */
#include "special.h"
#include "hair.h"
#include "layered.h"

int abrdf__is_double_only(abrdf_model model)
{
    switch (model) {
    case ABRDF_MARSCHNER:
    case ABRDF_HUANG:
    case ABRDF_WEIDLICH_WILKIE:
    case ABRDF_BELCOUR: return 1;
    default: return 0;
    }
}

void abrdf__eval_special(abrdf_model model, const abrdf_params *p, const double wi[3],
                         const double wo[3], double f[3])
{
    f[0] = f[1] = f[2] = 0.0;
    switch (model) {
    case ABRDF_MARSCHNER: abrdf__marschner_eval(p, wi, wo, f); break;
    case ABRDF_HUANG: abrdf__huang_eval(p, wi, wo, f); break;
    case ABRDF_WEIDLICH_WILKIE: abrdf__eval_weidlich_wilkie(p, wi, wo, f); break;
    case ABRDF_BELCOUR: abrdf__eval_belcour(p, wi, wo, f); break;
    default: break;
    }
}
