/* special.c - dispatch of the models evaluated in double only: hair (hair.h) and layered
 * models (layered.h), their setup once per prepared object and their evaluation from it. */
#include "hair.h"
#include "layered.h"
#include "prepared.h"

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

void abrdf__prep_setup_special(abrdf__prep *pr, unsigned what)
{
    switch (pr->model) {
    case ABRDF_MARSCHNER: abrdf__marschner_setup(&pr->params, &pr->special.marschner); break;
    case ABRDF_HUANG: abrdf__huang_setup(&pr->params, &pr->special.huang); break;
    case ABRDF_BELCOUR:
        abrdf__belcour_setup(&pr->params, &pr->special.belcour, !(what & ABRDF__PREP_ONCE));
        break;
    case ABRDF_WEIDLICH_WILKIE: abrdf__ww_setup(&pr->params, &pr->special.ww); break;
    default: break;
    }
}

void abrdf__eval_special_prepared(const abrdf__prep *pr, const double wi[3], const double wo[3],
                                  double f[3])
{
    f[0] = f[1] = f[2] = 0.0;
    switch (pr->model) {
    case ABRDF_MARSCHNER: abrdf__marschner_eval(&pr->special.marschner, wi, wo, f); break;
    case ABRDF_HUANG: { /* a table's, if prepared on one (abrdf_prepare_huang_table) */
        double fl[1][3];
        abrdf__huang_prepared_run(&pr->special.huang, 1, (const double(*)[3])wi, wo, fl);
        f[0] = fl[0][0], f[1] = fl[0][1], f[2] = fl[0][2];
        break;
    }
    case ABRDF_BELCOUR: abrdf__eval_belcour(&pr->special.belcour, &pr->params, wi, wo, f); break;
    case ABRDF_MEASURED: abrdf__measured_eval(&pr->special.measured, wi, wo, f); break;
    default: break;
    }
}
