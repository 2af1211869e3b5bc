/* special.c - dispatch of the models evaluated in double only (hair and layered models). */
#include "special.h"

int abrdf__is_double_only(abrdf_model model)
{
    (void)model;
    return 0;
}

void abrdf__eval_special(abrdf_model model, const abrdf_params *p, const double wi[3],
                         const double wo[3], double f[3])
{
    (void)model; (void)p; (void)wi; (void)wo;
    f[0] = f[1] = f[2] = 0.0;
}
