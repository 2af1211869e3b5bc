/* test_util.c - helpers shared by the Check suites. */
#include <math.h>
#include <stdlib.h>
#include "test_util.h"

void tu_dir(double theta_deg, double phi_deg, double out[3])
{
    const double d = 3.14159265358979323846 / 180.0;
    out[0] = sin(theta_deg * d) * cos(phi_deg * d);
    out[1] = sin(theta_deg * d) * sin(phi_deg * d);
    out[2] = cos(theta_deg * d);
}

int tu_close(double a, double b, double rel, double abs_tol)
{
    return fabs(a - b) <= rel * fmax(fabs(a), fabs(b)) + abs_tol;
}

double tu_eval1(abrdf_model m, const abrdf_params *p, const double wi[3], const double wo[3])
{
    double f[3];
    int st = abrdf_eval(m, p, NULL, wi, wo, f);
    ck_assert_int_eq(st, ABRDF_OK);
    return f[0];
}

void tu_count(tu_counts *k, const double f[3])
{
    for (int c = 0; c < 3; ++c) {
        k->evals++;
        if (isnan(f[c]))
            k->nan++;
        else if (isinf(f[c]))
            k->inf++;
        else if (f[c] < 0.0)
            k->neg++;
    }
}

int tu_run(Suite *s)
{
    SRunner *sr = srunner_create(s);
    srunner_run_all(sr, CK_NORMAL);
    int failed = srunner_ntests_failed(sr);
    srunner_free(sr);
    return failed == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

const abrdf_model_info *tu_param_model(int id)
{
    const abrdf_model_info *m = abrdf_model_get((abrdf_model)id);
    return m && !(m->needs & ABRDF_NEEDS_TABLE) ? m : NULL;
}
